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

}  // namespace
}  // namespace ptlab::simd
