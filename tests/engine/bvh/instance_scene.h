// A scene with instancing and every kind of trouble for the two-level BVH tests (oracle against
// brute force, simd/ against the oracle), and the brute-force closest hit over it.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/bvh/instance_level.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/bvh/watertight_triangle.h"
#include "engine/core/rng.h"
#include "engine/scene/scene.h"
#include "tests/engine/bvh/test_meshes.h"

namespace ptlab::bvh_test {

inline void AppendRows(const IndexedMesh& m, TriangleTable* t) {
  for (const auto& tri : m.triangles)
    t->Append(m.vertices[tri[0]], m.vertices[tri[1]], m.vertices[tri[2]]);
}

/// Top-level triangles (a grid and a soup) and two spheres, and two groups: A (an icosphere, an
/// axis-aligned cube, a grid with duplicated triangles: ties inside a group) and B (a random
/// soup), between the top rows. Instances of A: identity, rotated with uniform scale, mirrored
/// (negative determinant), non-uniformly scaled and sheared, and the identity again (an exact
/// overlap: every hit ties with the first instance's), one far away and tiny; of B: two
/// overlapping rotations. Group A's identity instance overlaps top-level triangles too.
inline Scene MakeInstancedScene() {
  Scene s;
  Pcg32 rng(77, 5);
  AppendRows(MakeFlatGrid(8), &s.triangles);
  const uint32_t a_first = uint32_t(s.triangles.size());
  AppendRows(MakeIcosphere(2, {0.2f, 0.1f, 0.3f}, 0.4f), &s.triangles);
  AppendRows(MakeCube({-0.6f, -0.6f, -0.6f}, {-0.2f, -0.2f, -0.2f}), &s.triangles);
  AppendRows(MakeFlatGrid(4), &s.triangles);
  const uint32_t grid_first = uint32_t(s.triangles.size()) - 32;  // the last 32 rows: grid
  for (uint32_t r = grid_first; r < grid_first + 8; ++r)
    s.triangles.Append(s.triangles.V0(r), s.triangles.V1(r), s.triangles.V2(r));
  const uint32_t a_rows = uint32_t(s.triangles.size()) - a_first;
  const TriangleTable soup = MakeRandomSoup(300, rng);
  for (size_t i = 0; i < 100; ++i) s.triangles.Append(soup.V0(i), soup.V1(i), soup.V2(i));
  const uint32_t b_first = uint32_t(s.triangles.size());
  for (size_t i = 100; i < 300; ++i) s.triangles.Append(soup.V0(i), soup.V1(i), soup.V2(i));
  const uint32_t b_rows = uint32_t(s.triangles.size()) - b_first;
  s.spheres.Append({0.9f, 0.9f, 0.2f}, 0.3f, MaterialRef{});
  s.spheres.Append({-1.5f, 0.5f, -0.3f}, 0.25f, MaterialRef{});
  const uint32_t a = s.instances.AddGroup(a_first, a_rows);
  const uint32_t b = s.instances.AddGroup(b_first, b_rows);
  s.instances.AddInstance(a, Transform());
  s.instances.AddInstance(a, Transform::Translate({1.5f, -0.3f, 0.4f}) *
                                 Transform::Rotate({1, 2, 3}, 40.0f) *
                                 Transform::Scale({1.7f, 1.7f, 1.7f}));
  s.instances.AddInstance(a, Transform::Translate({-1.2f, 1.1f, 0.0f}) *
                                 Transform::Scale({-1.0f, 0.8f, 0.8f}));
  Matrix4 shear;
  shear.m[0][1] = 0.5f, shear.m[2][0] = -0.3f, shear.m[1][1] = 0.4f, shear.m[0][3] = 0.3f,
  shear.m[1][3] = -1.4f;
  s.instances.AddInstance(a, Transform(shear));
  s.instances.AddInstance(a, Transform());
  s.instances.AddInstance(a, Transform::Translate({40.0f, 0.0f, 0.0f}) *
                                 Transform::Scale({0.01f, 0.01f, 0.01f}));
  s.instances.AddInstance(b, Transform::Rotate({0, 0, 1}, 30.0f));
  s.instances.AddInstance(b, Transform::Rotate({0, 1, 1}, -50.0f) *
                                 Transform::Scale({1.2f, 0.9f, 1.1f}));
  return s;
}

/// The least (t, id) over every candidate with the ray's own interval: top-level triangle rows,
/// spheres (kSphereHitBit | row), and each instance's group triangles met by the ray in group
/// space (RayToInstance; id = the instanced hit id). Intersect1's contract.
inline bool BruteForceInstanced(const Scene& s, const InstanceLevel& level, const Ray& ray,
                                Hit* hit) {
  if (!(ray.t_min < ray.t_max)) return false;
  bool found = false;
  const auto offer = [&](float t, float b1, float b2, uint32_t prim) {
    if (!found || t < hit->t || (t == hit->t && prim < hit->prim)) *hit = {t, b1, b2, prim};
    found = true;
  };
  const InstanceTable& in = s.instances;
  std::vector<uint8_t> grouped(s.triangles.size(), 0);
  for (size_t g = 0; g < in.groups(); ++g)
    for (uint32_t r = 0; r < in.group_row_count[g]; ++r) grouped[in.group_first_row[g] + r] = 1;
  const WatertightRay wr = MakeWatertightRay(ray.o, ray.d);
  for (uint32_t i = 0; i < s.triangles.size(); ++i) {
    TriangleHit th;
    if (!grouped[i] && IntersectTriangleWatertight(wr, s.triangles.V0(i), s.triangles.V1(i),
                                                   s.triangles.V2(i), ray.t_min, ray.t_max, &th))
      offer(th.t, th.b1, th.b2, i);
  }
  for (uint32_t i = 0; i < s.spheres.size(); ++i) {
    float t = ray.t_max;
    uint32_t prim = kNoHit;
    SphereTable one;
    one.Append(s.spheres.Center(i), s.spheres.radius[i], MaterialRef{});
    if (IntersectSpheres1(one, ray, &t, &prim)) offer(t, 0.0f, 0.0f, kSphereHitBit | i);
  }
  for (uint32_t k = 0; k < in.size(); ++k) {
    const Ray local = RayToInstance(level, k, ray);
    const WatertightRay lr = MakeWatertightRay(local.o, local.d);
    const uint32_t g = in.group[k];
    for (uint32_t j = 0; j < in.group_row_count[g]; ++j) {
      const uint32_t r = in.group_first_row[g] + j;
      TriangleHit th;
      if (IntersectTriangleWatertight(lr, s.triangles.V0(r), s.triangles.V1(r), s.triangles.V2(r),
                                      local.t_min, local.t_max, &th))
        offer(th.t, th.b1, th.b2, uint32_t(s.triangles.size()) + in.first_prim[k] + j);
    }
  }
  return found;
}

/// Rays for the tests: random origins in and around the scene towards random directions,
/// rays aimed at random points of instanced triangles (through their world positions), and
/// rays along the axes (zero direction components).
inline std::vector<Ray> InstancedSceneRays(const Scene& s, uint64_t seed, int count) {
  Pcg32 rng(seed, 9);
  std::vector<Ray> rays;
  const InstanceTable& in = s.instances;
  for (int i = 0; i < count; ++i) {
    Ray r;
    r.o = UniformInBox(rng, {-3, -3, -3}, {3, 3, 3});
    const int kind = i % 4;
    if (kind == 0) {
      r.d = UniformSphereDirection(rng);
    } else if (kind == 1 || kind == 2) {
      const uint32_t k = rng.NextUint() % uint32_t(in.size());
      const uint32_t g = in.group[k];
      const uint32_t row = in.group_first_row[g] + rng.NextUint() % in.group_row_count[g];
      const float b1 = rng.NextFloat(), b2 = (1.0f - b1) * rng.NextFloat();
      const Vec3f p = s.triangles.V0(row) * (1.0f - b1 - b2) + s.triangles.V1(row) * b1 +
                      s.triangles.V2(row) * b2;
      r.d = in.to_world[k].ApplyPoint(p) - r.o;
      if (kind == 2) r.t_max = 1.0f;  // ends on the surface: hit or not, both sides agree
    } else {
      const int axis = int(rng.NextUint() % 3);
      const float sign = rng.NextFloat() < 0.5f ? -1.0f : 1.0f;
      r.d = {axis == 0 ? sign : 0.0f, axis == 1 ? sign : 0.0f, axis == 2 ? sign : 0.0f};
    }
    if (!(Length(r.d) > 0)) r.d = {0, 0, 1};
    rays.push_back(r);
  }
  return rays;
}

}  // namespace ptlab::bvh_test
