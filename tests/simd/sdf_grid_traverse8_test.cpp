// Sdfgrids beside the BVH in simd/traverse8 against the scalar oracle (Intersect1 / Occluded1),
// lane by lane, on every compiled Highway target: same hit, same id, bit-identical t and
// barycentrics, with triangles and a sphere in front of, inside and behind two grids (one
// rotated), and rays at the grids, grazing their surface, along grid planes, leaving it, and cut
// short by t_max.
// clang-format off
#include "simd/targets.h"  // first: the same target policy as simd/
// clang-format on

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "engine/bvh/intersect1.h"
#include "engine/bvh/ray_offset.h"
#include "engine/bvh/sdf_grid_intersect.h"
#include "engine/core/packet8.h"
#include "engine/core/rng.h"
#include "engine/render/sdf_grid_normal.h"
#include "simd/bvh8.h"
#include "simd/dispatched_target.h"
#include "simd/traverse8.h"
#include "tests/engine/bvh/test_meshes.h"
#include "tests/simd/for_each_target.h"

namespace ptlab::simd {
namespace {

using bvh_test::UniformInBox;
using bvh_test::UniformSphereDirection;

const MaterialRef kMat = MaterialRef::Make(MaterialTag::kDiffuse, 0);

// A torus-like field (a ring of radius 0.3, tube 0.12) on an n³ grid, placed by to_world.
void AddTorus(uint32_t n, const Transform& to_world, SdfGridTable* g) {
  std::vector<float> v;
  for (uint32_t k = 0; k < n; ++k)
    for (uint32_t j = 0; j < n; ++j)
      for (uint32_t i = 0; i < n; ++i) {
        const double x = double(i) / (n - 1) - 0.5, y = double(j) / (n - 1) - 0.5,
                     z = double(k) / (n - 1) - 0.5;
        const double q = std::sqrt(x * x + y * y) - 0.3;
        v.push_back(float(std::sqrt(q * q + z * z) - 0.12));
      }
  g->Append(n, n, n, v, to_world, kMat, SdfNormals::kSmooth);
}

struct Scenario {
  Bvh bvh;
  Bvh8 bvh8;
  std::vector<Ray> rays;
};

Scenario Make() {
  Scenario s;
  TriangleTable tri;
  // A floor under everything, a wall cutting through the first grid, a small triangle inside it.
  tri.Append({-5, -5, -0.2f}, {5, -5, -0.2f}, {5, 5, -0.2f});
  tri.Append({-5, -5, -0.2f}, {5, 5, -0.2f}, {-5, 5, -0.2f});
  tri.Append({0.5f, -2, -2}, {0.5f, 2, -2}, {0.5f, 0, 3});
  tri.Append({0.4f, 0.4f, 0.5f}, {0.6f, 0.4f, 0.5f}, {0.5f, 0.6f, 0.5f});
  SphereTable spheres;
  spheres.Append({0.5f, 0.5f, 0.5f}, 0.1f, kMat);  // in the torus' hole
  s.bvh = BuildBvh(tri, spheres);
  AddTorus(16, Transform(), &s.bvh.sdf_grids);
  AddTorus(9, Transform::Translate({3, 1, 0}) * Transform::Rotate({1, 2, 0.5f}, 40) *
                  Transform::Scale({1.5f, 1, 0.7f}),
           &s.bvh.sdf_grids);
  s.bvh8 = BuildBvh8(s.bvh);
  Pcg32 rng(77, 21);
  for (int i = 0; i < 6000; ++i) {
    Ray ray;
    const int kind = i % 6;
    if (kind == 0) {  // at the first grid from anywhere
      ray.o = UniformInBox(rng, {-2, -2, -2}, {3, 3, 3});
      ray.d = UniformInBox(rng, {0, 0, 0}, {1, 1, 1}) - ray.o;
    } else if (kind == 1) {  // at the second grid
      ray.o = UniformInBox(rng, {0, -2, -2}, {6, 4, 3});
      ray.d = UniformInBox(rng, {2.5f, 0.5f, -0.5f}, {3.8f, 1.8f, 0.5f}) - ray.o;
    } else if (kind == 2) {  // along grid planes of the first grid (x = i / 15 or y = j / 15)
      const float u = float(rng.NextUint() % 16) / 15.0f, w = rng.NextFloat();
      ray.o = rng.NextFloat() < 0.5f ? Vec3f{u, -1, w} : Vec3f{-1, u, w};
      ray.d = ray.o.x == -1 ? Vec3f{1, 0, 0} : Vec3f{0, 1, 0};
    } else if (kind == 3) {  // grazing the ring's top (z = 0.5 + 0.12) at 1 ± 2^-e
      const float e = std::ldexp(1.0f, -int(rng.NextUint() % 20));
      const float z = 0.5f + 0.12f * (rng.NextFloat() < 0.5f ? 1 - e : 1 + e);
      const Vec3f d = UniformSphereDirection(rng);
      ray.o = Vec3f{0.5f, 0.5f, z} - Vec3f{d.x, d.y, 0} * 2.0f;
      ray.d = {d.x, d.y, 0};
      if (!(Length(ray.d) > 0)) ray.d = {1, 0, 0};
    } else if (kind == 4) {  // leaving the surface of the first grid at an oracle hit
      Ray in{UniformInBox(rng, {-2, -2, -2}, {3, 3, 3}), {}};
      in.d = UniformInBox(rng, {0.2f, 0.2f, 0.4f}, {0.8f, 0.8f, 0.6f}) - in.o;
      float t = 0;
      if (IntersectSdfGrid1(s.bvh.sdf_grids, 0, in, in.t_max, &t)) {
        Vec3f ng, ns;
        SdfGridNormals(s.bvh.sdf_grids, 0, in.At(t), &ng, &ns);
        Vec3f w = UniformSphereDirection(rng);
        if (rng.NextFloat() < 0.5f) w = Dot(w, ng) < 0 ? -w : w;  // out, or any way
        ray.o = OffsetRayOrigin(in.At(t), Dot(w, ng) >= 0 ? ng : -ng);
        ray.d = w;
      } else {
        ray = in;
      }
    } else {  // random, some cut short
      ray.o = UniformInBox(rng, {-1, -1, -1}, {4, 3, 2});
      ray.d = UniformSphereDirection(rng);
      ray.t_max = rng.NextFloat() * 2.0f;
    }
    s.rays.push_back(ray);
  }
  return s;
}

TEST(SdfGridTraverse8, MatchesOracleOnEveryTarget) {
  const Scenario s = Make();
  struct Expected {
    bool hit, occluded;
    Hit h;
  };
  std::vector<Expected> expected;
  size_t grid_hits = 0;
  for (const Ray& r : s.rays) {
    Expected e{};
    e.hit = Intersect1(s.bvh, r, &e.h);
    e.occluded = Occluded1(s.bvh, r);
    grid_hits += e.hit && IsSdfGridHit(e.h.prim);
    expected.push_back(e);
  }
  EXPECT_GT(grid_hits, s.rays.size() / 10);
  test::ForEachTarget(DispatchedTargetName, [&](const char*) {
    int mismatches = 0;
    for (size_t base = 0; base < s.rays.size(); base += 8) {
      RayPacket8 p{};
      HitPacket8 h{};
      for (int j = 0; j < 8; ++j) {
        SetLaneRay(&p, j, s.rays[(base + j) % s.rays.size()]);
        h.prim[j] = 0x12345678u;
      }
      const Mask8 hit = Intersect8(s.bvh8, p, kAllLanes, &h);
      const Mask8 occ = Occluded8(s.bvh8, p, kAllLanes);
      for (int j = 0; j < 8; ++j) {
        const size_t i = (base + j) % s.rays.size();
        const Expected& e = expected[i];
        const bool got = (hit >> j) & 1;
        bool same = got == e.hit && (((occ >> j) & 1) != 0) == e.occluded;
        if (same && got)
          same = std::bit_cast<uint32_t>(h.t[j]) == std::bit_cast<uint32_t>(e.h.t) &&
                 std::bit_cast<uint32_t>(h.b1[j]) == std::bit_cast<uint32_t>(e.h.b1) &&
                 std::bit_cast<uint32_t>(h.b2[j]) == std::bit_cast<uint32_t>(e.h.b2) &&
                 h.prim[j] == e.h.prim;
        if (same && !got) same = h.prim[j] == 0x12345678u;  // a miss writes nothing
        Hit h1;
        const bool got1 = simd::Intersect1(s.bvh8, s.rays[i], &h1);
        if (same)
          same = got1 == e.hit && simd::Occluded1(s.bvh8, s.rays[i]) == e.occluded &&
                 (!got1 || (std::bit_cast<uint32_t>(h1.t) == std::bit_cast<uint32_t>(e.h.t) &&
                            h1.prim == e.h.prim));
        if (!same && ++mismatches <= 5) ADD_FAILURE() << "ray " << i << " differs";
      }
    }
    EXPECT_EQ(mismatches, 0);
  });
  // Grids alone (no triangle, no sphere): the kernels still test them.
  Bvh only = BuildBvh(TriangleTable{});
  only.sdf_grids = s.bvh.sdf_grids;
  const Bvh8 only8 = BuildBvh8(only);
  ASSERT_TRUE(only8.empty());
  test::ForEachTarget(DispatchedTargetName, [&](const char*) {
    int mismatches = 0;
    for (size_t i = 0; i < 800; ++i) {
      Hit e, g;
      const bool he = Intersect1(only, s.rays[i], &e);
      RayPacket8 p{};
      HitPacket8 h{};
      SetLaneRay(&p, 0, s.rays[i]);
      const bool hg = Intersect8(only8, p, 1, &h) == 1;
      g = {h.t[0], h.b1[0], h.b2[0], h.prim[0]};
      if (he != hg || (he && (std::bit_cast<uint32_t>(e.t) != std::bit_cast<uint32_t>(g.t) ||
                              e.prim != g.prim)))
        ++mismatches;
      if ((Occluded8(only8, p, 1) == 1) != Occluded1(only, s.rays[i])) ++mismatches;
    }
    EXPECT_EQ(mismatches, 0);
  });
}

}  // namespace
}  // namespace ptlab::simd
