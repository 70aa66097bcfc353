// simd/traverse8 on a two-level BVH (instancing) against the scalar oracle, on every compiled
// Highway target: Intersect8 / Occluded8 per lane and the single-ray Intersect1 / Occluded1
// give the oracle's hit, id, and t, b1, b2 bit for bit.
// clang-format off
#include "simd/targets.h"  // first: the same target policy as simd/
// clang-format on

#include "simd/dispatched_target.h"
#include "simd/traverse8.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include "engine/bvh/intersect1.h"
#include "engine/bvh/scene_bvh.h"
#include "simd/bvh8.h"
#include "tests/engine/bvh/instance_scene.h"
#include "tests/simd/for_each_target.h"

namespace ptlab::simd {
namespace {

constexpr uint32_t kSentinel = 0x7fc0dead;

uint32_t Bits(float f) {
  uint32_t b;
  std::memcpy(&b, &f, sizeof(b));
  return b;
}

TEST(Traverse8Instances, MatchesOracleOnEveryTarget) {
  const Scene s = bvh_test::MakeInstancedScene();
  const Bvh bvh = BuildSceneBvh(s);
  const Bvh8 bvh8 = BuildBvh8(bvh);
  ASSERT_EQ(bvh8.groups.size(), 2u);
  const std::vector<Ray> rays = bvh_test::InstancedSceneRays(s, 11, 8 * 1500);
  test::ForEachTarget(DispatchedTargetName, [&](const char*) {
    int failures = 0, instanced_hits = 0;
    Pcg32 rng(3, 4);
    for (size_t base = 0; base < rays.size(); base += 8) {
      RayPacket8 p;
      for (int j = 0; j < 8; ++j) SetLaneRay(&p, j, rays[base + size_t(j)]);
      // Every fourth packet shares one origin (camera-like); some lanes inactive.
      if ((base / 8) % 4 == 0)
        for (int j = 1; j < 8; ++j) p.org_x[j] = p.org_x[0], p.org_y[j] = p.org_y[0],
                                    p.org_z[j] = p.org_z[0];
      // Every other packet points all lanes into lane 0's octant (the instance level's packet
      // walk; the others take the lane-by-lane walk).
      if ((base / 8) % 2 == 1)
        for (int j = 1; j < 8; ++j) {
          p.dir_x[j] = std::copysign(p.dir_x[j], p.dir_x[0]);
          p.dir_y[j] = std::copysign(p.dir_y[j], p.dir_y[0]);
          p.dir_z[j] = std::copysign(p.dir_z[j], p.dir_z[0]);
        }
      const Mask8 active = (base / 8) % 3 == 0 ? kAllLanes : (rng.NextUint() & kAllLanes);
      HitPacket8 h;
      for (int j = 0; j < 8; ++j) {
        std::memcpy(&h.t[j], &kSentinel, 4);
        h.b1[j] = h.b2[j] = h.t[j];
        h.prim[j] = kSentinel;
      }
      const Mask8 hit = Intersect8(bvh8, p, active, &h);
      const Mask8 occluded = Occluded8(bvh8, p, active);
      for (int j = 0; j < 8; ++j) {
        const Ray ray = GetLaneRay(p, j);
        Hit want, single;
        const bool w = LaneActive(active, j) && ptlab::Intersect1(bvh, ray, &want);
        const bool got = LaneActive(hit, j);
        bool ok = w == got && LaneActive(occluded, j) == w;
        if (ok && w) {
          ok = Bits(want.t) == Bits(h.t[j]) && Bits(want.b1) == Bits(h.b1[j]) &&
               Bits(want.b2) == Bits(h.b2[j]) && want.prim == h.prim[j];
          instanced_hits += !IsSphereHit(want.prim) && want.prim >= s.triangles.size();
        }
        if (ok && !got) ok = h.prim[j] == kSentinel && Bits(h.t[j]) == kSentinel;
        if (LaneActive(active, j)) {
          const bool w1 = ptlab::Intersect1(bvh, ray, &want);
          const bool g1 = Intersect1(bvh8, ray, &single);
          ok = ok && w1 == g1 && Occluded1(bvh8, ray) == w1;
          if (ok && w1)
            ok = Bits(want.t) == Bits(single.t) && Bits(want.b1) == Bits(single.b1) &&
                 Bits(want.b2) == Bits(single.b2) && want.prim == single.prim;
        }
        if (!ok && ++failures <= 5) ADD_FAILURE() << "packet " << base / 8 << " lane " << j;
      }
    }
    EXPECT_EQ(failures, 0);
    EXPECT_GT(instanced_hits, 1000);
  });
}

// Adversarial rays for the packet instance walk (every packet takes it, whatever its octants),
// mixed into packets of random lanes: rays grazing along group triangles' edges (in world space
// through the instance transform), rays aimed at shared vertices (equal t on several triangles,
// and on instance A's identity duplicate: ties between instances broken by id), rays that start
// inside instance boxes or exactly on an instance box's face with a direction parallel to it
// (the slab test's 0 * inf), and rays whose t_max ends exactly at their hit. Every lane of
// Intersect8 / Occluded8 must be the oracle's bit for bit on every compiled target.
std::vector<Ray> AdversarialInstanceRays(const Scene& s, const Bvh& bvh, uint64_t seed, int n) {
  Pcg32 rng(seed, 13);
  const InstanceTable& in = s.instances;
  std::vector<Ray> rays;
  const auto world_vertex = [&](uint32_t k, uint32_t row, int v) {
    const Vec3f p = v == 0   ? s.triangles.V0(row)
                    : v == 1 ? s.triangles.V1(row)
                             : s.triangles.V2(row);
    return in.to_world[k].ApplyPoint(p);
  };
  while (int(rays.size()) < n) {
    const uint32_t k = rng.NextUint() % uint32_t(in.size());
    const uint32_t g = in.group[k];
    const uint32_t row = in.group_first_row[g] + rng.NextUint() % in.group_row_count[g];
    const Vec3f a = world_vertex(k, row, 0), b = world_vertex(k, row, 1);
    Ray r;
    switch (rays.size() % 5) {
      case 0: {  // grazing: along the edge a -> b, from before a
        r.d = b - a;
        r.o = a - r.d * (0.5f + rng.NextFloat());
        break;
      }
      case 1: {  // at a shared vertex from a random origin
        r.o = bvh_test::UniformInBox(rng, {-3, -3, -3}, {3, 3, 3});
        r.d = a - r.o;
        if (rng.NextFloat() < 0.5f) {
          Hit h;
          if (ptlab::Intersect1(bvh, r, &h)) r.t_max = h.t;  // ends exactly at its hit
        }
        break;
      }
      case 2: {  // from inside the instance's box (near its triangle) in a random direction
        r.o = (a + b) * 0.5f + bvh_test::UniformSphereDirection(rng) * (0.01f * rng.NextFloat());
        r.d = bvh_test::UniformSphereDirection(rng);
        break;
      }
      case 3: {  // from a face of an instance's world box, parallel to it
        const BvhNode& leaf = [&]() -> const BvhNode& {
          for (;;) {
            const BvhNode& node = bvh.instances.nodes[rng.NextUint() % bvh.instances.nodes.size()];
            if (node.IsLeaf()) return node;
          }
        }();
        const int axis = int(rng.NextUint() % 3);
        r.o = bvh_test::UniformInBox(rng, leaf.bounds_min, leaf.bounds_max);
        const float face = rng.NextFloat() < 0.5f ? leaf.bounds_min[axis] : leaf.bounds_max[axis];
        r.o[axis] = face;
        r.d = bvh_test::UniformSphereDirection(rng);
        r.d[axis] = 0.0f;
        break;
      }
      default: {  // through the identity duplicates' shared triangles, t_min past the origin
        r.o = bvh_test::UniformInBox(rng, {-1, -1, -1}, {1, 1, 1});
        r.d = (a + b) * 0.5f - r.o;
        r.t_min = 0.25f * rng.NextFloat();
        break;
      }
    }
    if (!(Length(r.d) > 0)) continue;
    rays.push_back(r);
  }
  return rays;
}

TEST(Traverse8Instances, AdversarialPacketsMatchOracleOnEveryTarget) {
  const Scene s = bvh_test::MakeInstancedScene();
  const Bvh bvh = BuildSceneBvh(s);
  const Bvh8 bvh8 = BuildBvh8(bvh);
  const std::vector<Ray> rays = AdversarialInstanceRays(s, bvh, 5, 8 * 1500);
  // Instance 0 (A, identity) has an exact duplicate, instance 4: each of its hits ties at equal t
  // with a hit of instance 4 and must keep instance 0's (lower) id.
  const uint32_t tie_lo = uint32_t(s.triangles.size()) + s.instances.first_prim[0];
  const uint32_t tie_hi = uint32_t(s.triangles.size()) + s.instances.first_prim[1];
  test::ForEachTarget(DispatchedTargetName, [&](const char*) {
    int failures = 0, instanced_hits = 0, tied_hits = 0;
    Pcg32 rng(8, 1);
    std::vector<size_t> shuffled(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) shuffled[i] = i;
    for (size_t i = rays.size(); i > 1; --i)
      std::swap(shuffled[i - 1], shuffled[rng.NextUint() % i]);
    for (size_t base = 0; base < rays.size(); base += 8) {
      RayPacket8 p;
      for (int j = 0; j < 8; ++j) SetLaneRay(&p, j, rays[shuffled[base + size_t(j)]]);
      const Mask8 active = (base / 8) % 2 == 0 ? kAllLanes : (rng.NextUint() & kAllLanes);
      HitPacket8 h;
      for (int j = 0; j < 8; ++j) {
        std::memcpy(&h.t[j], &kSentinel, 4);
        h.b1[j] = h.b2[j] = h.t[j];
        h.prim[j] = kSentinel;
      }
      const Mask8 hit = Intersect8(bvh8, p, active, &h);
      const Mask8 occluded = Occluded8(bvh8, p, active);
      for (int j = 0; j < 8; ++j) {
        const Ray ray = GetLaneRay(p, j);
        Hit want;
        const bool w = LaneActive(active, j) && ptlab::Intersect1(bvh, ray, &want);
        bool ok = w == LaneActive(hit, j) &&
                  LaneActive(occluded, j) == (LaneActive(active, j) && ptlab::Occluded1(bvh, ray));
        if (ok && w) {
          ok = Bits(want.t) == Bits(h.t[j]) && Bits(want.b1) == Bits(h.b1[j]) &&
               Bits(want.b2) == Bits(h.b2[j]) && want.prim == h.prim[j];
          instanced_hits += !IsSphereHit(want.prim) && want.prim >= s.triangles.size();
          tied_hits += want.prim >= tie_lo && want.prim < tie_hi;
        }
        if (ok && !w) ok = h.prim[j] == kSentinel && Bits(h.t[j]) == kSentinel;
        if (!ok && ++failures <= 5) ADD_FAILURE() << "packet " << base / 8 << " lane " << j;
      }
    }
    EXPECT_EQ(failures, 0);
    EXPECT_GT(instanced_hits, 1500);
    EXPECT_GT(tied_hits, 200);
  });
}

}  // namespace
}  // namespace ptlab::simd
