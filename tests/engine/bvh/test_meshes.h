// Meshes, random rays and a brute-force reference shared by the BVH tests.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "engine/bvh/bvh.h"
#include "engine/bvh/watertight_triangle.h"
#include "engine/core/ray.h"
#include "engine/core/rng.h"
#include "engine/core/vec.h"
#include "engine/scene/geometry_tables.h"

namespace ptlab::bvh_test {

/// An indexed mesh: shared vertices, so neighbouring triangles see bit-identical positions.
struct IndexedMesh {
  std::vector<Vec3f> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;

  TriangleTable ToTable() const {
    TriangleTable t;
    for (const auto& tri : triangles) {
      t.Append(vertices[tri[0]], vertices[tri[1]], vertices[tri[2]]);
    }
    return t;
  }
};

inline float Uniform(Pcg32& rng, float lo, float hi) { return lo + (hi - lo) * rng.NextFloat(); }

inline Vec3f UniformSphereDirection(Pcg32& rng) {
  const float z = 1.0f - 2.0f * rng.NextFloat();
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * rng.NextFloat();
  return {r * std::cos(phi), r * std::sin(phi), z};
}

inline Vec3f UniformInBox(Pcg32& rng, const Vec3f& lo, const Vec3f& hi) {
  return {Uniform(rng, lo.x, hi.x), Uniform(rng, lo.y, hi.y), Uniform(rng, lo.z, hi.z)};
}

/// Icosahedron subdivided `levels` times, projected to a sphere; 20 * 4^levels triangles.
inline IndexedMesh MakeIcosphere(int levels, const Vec3f& center, float radius) {
  const float p = (1.0f + std::sqrt(5.0f)) * 0.5f;
  std::vector<Vec3f> dirs = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0},
                             {0, -1, p}, {0, 1, p}, {0, -1, -p}, {0, 1, -p},
                             {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  std::vector<std::array<uint32_t, 3>> tris = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (Vec3f& d : dirs) d = Normalize(d);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoint;
    auto mid = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      dirs.push_back(Normalize(dirs[a] + dirs[b]));
      const uint32_t id = static_cast<uint32_t>(dirs.size() - 1);
      midpoint.emplace(key, id);
      return id;
    };
    std::vector<std::array<uint32_t, 3>> next;
    for (const auto& t : tris) {
      const uint32_t a = mid(t[0], t[1]), b = mid(t[1], t[2]), c = mid(t[2], t[0]);
      next.push_back({t[0], a, c});
      next.push_back({t[1], b, a});
      next.push_back({t[2], c, b});
      next.push_back({a, b, c});
    }
    tris = std::move(next);
  }
  IndexedMesh m;
  for (const Vec3f& d : dirs) m.vertices.push_back(center + d * radius);
  m.triangles = std::move(tris);
  return m;
}

/// Box [lo, hi] as 12 triangles with shared corners, each face split along a diagonal.
inline IndexedMesh MakeCube(const Vec3f& lo, const Vec3f& hi) {
  IndexedMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  }
  const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

/// Vertices transformed by a rotation about a skew axis (positions stay shared).
inline IndexedMesh Rotated(IndexedMesh m, const Vec3f& axis, float angle) {
  const Vec3f k = Normalize(axis);
  const float c = std::cos(angle), s = std::sin(angle);
  for (Vec3f& v : m.vertices) {
    v = v * c + Cross(k, v) * s + k * (Dot(k, v) * (1.0f - c));
  }
  return m;
}

/// n x n quads over [-1, 1]^2 at z = 0 (grid step 2/n, exact in float for n a power of 2),
/// two triangles per quad, diagonals alternating.
inline IndexedMesh MakeFlatGrid(int n) {
  IndexedMesh m;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      m.vertices.push_back({-1.0f + 2.0f * static_cast<float>(i) / static_cast<float>(n),
                            -1.0f + 2.0f * static_cast<float>(j) / static_cast<float>(n), 0.0f});
    }
  }
  auto id = [n](int i, int j) { return static_cast<uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({a, c, d});
      } else {
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({b, c, d});
      }
    }
  }
  return m;
}

/// n random triangles in [-1, 1]^3 with edge lengths from tiny to about the scene size.
inline TriangleTable MakeRandomSoup(int n, Pcg32& rng) {
  TriangleTable t;
  while (static_cast<int>(t.size()) < n) {
    const Vec3f c = UniformInBox(rng, {-1, -1, -1}, {1, 1, 1});
    const float size = std::pow(10.0f, Uniform(rng, -3.0f, -0.3f));
    const Vec3f a = c + UniformSphereDirection(rng) * size;
    const Vec3f b = c + UniformSphereDirection(rng) * size;
    const Vec3f d = c + UniformSphereDirection(rng) * size;
    if (Length(Cross(b - a, d - a)) <= 1e-12f) continue;
    t.Append(a, b, d);
  }
  return t;
}

/// Closest hit over all triangles in row order with the watertight test; ties on t keep the
/// lowest row. This is the contract Intersect1 must meet exactly.
inline bool BruteForceIntersect(const TriangleTable& t, const Ray& ray, Hit* hit) {
  if (!(ray.t_min < ray.t_max)) return false;
  const WatertightRay wr = MakeWatertightRay(ray.o, ray.d);
  bool found = false;
  for (size_t i = 0; i < t.size(); ++i) {
    TriangleHit th;
    if (!IntersectTriangleWatertight(wr, t.V0(i), t.V1(i), t.V2(i), ray.t_min, ray.t_max, &th)) {
      continue;
    }
    if (!found || th.t < hit->t) {
      found = true;
      hit->t = th.t;
      hit->b1 = th.b1;
      hit->b2 = th.b2;
      hit->prim = static_cast<uint32_t>(i);
    }
  }
  return found;
}

}  // namespace ptlab::bvh_test
