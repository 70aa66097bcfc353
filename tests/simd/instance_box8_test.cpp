// simd::InstanceBoxLanes (the packet instance walk's box test, simd/instance_box8.h) against its
// oracle IntersectBox (engine/bvh/box_intersect.h) lane by lane, on every compiled Highway
// target: the same lanes enter, with the same entry distance, bit for bit. Random boxes and
// rays, and the cases where the slab test's details decide: axis-parallel rays (1 / d = ±inf),
// origins on a slab's plane (0 · inf = NaN), rays grazing a face, t_far exactly at the entry
// or the exit (the robust far scale decides), flat boxes, t_min past t_far, inactive lanes.
#include "simd/targets.h"  // first: the target policy (must precede every hwy/ include)
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "engine/bvh/box_intersect.h"
#include "simd/dispatched_target.h"
#include "simd/instance_box8.h"
#include "tests/simd/for_each_target.h"

namespace ptlab {
namespace {

bool SameBits(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }

struct Case {
  BvhNode node;
  RayPacket8 rays;
  Mask8 live;
  alignas(32) float t_far[8];  // InstanceBoxLanes loads it aligned
};

BvhNode Box(const Vec3f& lo, const Vec3f& hi) {
  BvhNode n;
  n.bounds_min = lo, n.bounds_max = hi;
  return n;
}

// Random boxes around the origin and rays from a larger cube towards points near the box (so
// about half enter), with a hard case in every other lane.
std::vector<Case> MakeCases() {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(0.05f, 1.0f);
  std::vector<Case> cases;
  const float inf = std::numeric_limits<float>::infinity();
  for (int k = 0; k < 4000; ++k) {
    Case c;
    const Vec3f lo{u(rng), u(rng), u(rng)};
    Vec3f hi{lo.x + pos(rng), lo.y + pos(rng), lo.z + pos(rng)};
    if (k % 7 == 0) hi.y = lo.y;  // a flat box
    c.node = Box(lo, hi);
    c.live = k % 5 == 0 ? Mask8(rng() & 0xff) : Mask8(0xff);
    for (int j = 0; j < 8; ++j) {
      Vec3f o{3 * u(rng), 3 * u(rng), 3 * u(rng)};
      const Vec3f target{lo.x + (hi.x - lo.x) * (0.5f + 0.8f * u(rng)),
                         lo.y + (hi.y - lo.y) * (0.5f + 0.8f * u(rng)),
                         lo.z + (hi.z - lo.z) * (0.5f + 0.8f * u(rng))};
      Vec3f d = target - o;
      float t_min = 0.0f, t_far = inf;
      switch ((k + j) % 12) {
        case 1: d.x = 0.0f; break;                          // parallel to the x slabs
        case 2: d.y = -0.0f, o.y = lo.y; break;             // on the y plane, parallel: NaN
        case 3: o.z = hi.z, d.z = 0.0f; break;              // grazing the top face
        case 4: d = {0.0f, 0.0f, d.z == 0 ? 1.0f : d.z}; break;  // along z only
        case 5: {                                           // t_far at the entry distance
          SlabRay s = MakeSlabRay({o, d, 0.0f, inf});
          float e;
          IntersectBox(c.node, s, 0.0f, inf, &e);
          t_far = e;
          break;
        }
        case 6: t_min = 5.0f, t_far = 1.0f; break;          // empty interval
        case 7: o = {lo.x, lo.y, lo.z}; break;              // from a corner
        case 8: t_far = 1e-30f; break;                      // tiny interval
        case 9: d = {d.x * 1e-20f, d.y * 1e-20f, d.z * 1e-20f}; break;  // huge 1 / d
        default: break;
      }
      c.rays.org_x[j] = o.x, c.rays.org_y[j] = o.y, c.rays.org_z[j] = o.z;
      c.rays.dir_x[j] = d.x, c.rays.dir_y[j] = d.y, c.rays.dir_z[j] = d.z;
      c.rays.t_min[j] = t_min, c.rays.t_max[j] = t_far;
      // The walk hands a lane without a ray a t_far of 0 (and masks its answer off).
      c.t_far[j] = LaneActive(c.live, j) ? t_far : 0.0f;
    }
    cases.push_back(c);
  }
  return cases;
}

TEST(InstanceBox8, LanesAreTheOraclesIntersectBoxOnEveryTarget) {
  const std::vector<Case> cases = MakeCases();
  size_t entered = 0, checked = 0;
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
    size_t failures = 0;
    for (const Case& c : cases) {
      const simd::InstanceLanes lanes = simd::MakeInstanceLanes(c.rays, c.live);
      alignas(32) float t_entry[8];
      const Mask8 got = simd::InstanceBoxLanes(c.node, lanes, c.t_far, t_entry);
      for (int j = 0; j < 8; ++j) {
        if (!LaneActive(c.live, j)) {
          // A lane not built from a ray (t_far 0) enters no box.
          if (LaneActive(got, j) && ++failures <= 5)
            ADD_FAILURE() << target << ": an inactive lane entered a box";
          continue;
        }
        ++checked;
        float want_entry = 0;
        const bool want = IntersectBox(c.node, MakeSlabRay(GetLaneRay(c.rays, j)),
                                       c.rays.t_min[j], c.t_far[j], &want_entry);
        entered += want;
        if (want != LaneActive(got, j) || !SameBits(want_entry, t_entry[j])) {
          if (++failures <= 5)
            ADD_FAILURE() << target << " lane " << j << ": simd " << LaneActive(got, j) << " at "
                          << t_entry[j] << ", oracle " << want << " at " << want_entry;
        }
      }
    }
    EXPECT_EQ(failures, 0u) << target;
  });
  // Both answers occur often enough to mean something.
  EXPECT_GT(entered, checked / 5);
  EXPECT_LT(entered, checked * 4 / 5);
}

}  // namespace
}  // namespace ptlab
