// Highway dynamic dispatch of the instance tree's packet box test (simd/instance_box8.h).

// Bit-identity with the oracle's slab distances needs every a * b + c as two roundings.
#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

// clang-format off
#include "simd/targets.h"  // first: the target policy
// clang-format on

#include <cstdint>

#include "engine/bvh/box_intersect.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/instance_box8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/instance_box8.h"
#include "simd/traverse8_common-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

// IntersectBox's operations per lane: (near plane - o) * inv_d with the plane chosen by the
// sign of inv_d, the interval folded x, y, z in turn with the same comparisons (a NaN slab
// distance leaves it unchanged), then t0 <= t1 * kRobustFarScale.
Mask8 InstanceBoxLanesImpl(const BvhNode& n, const InstanceLanes& l, const float* t_far,
                           float* t_entry) {
  const DF d;
  const size_t count = hn::Lanes(d);
  const float lo[3] = {n.bounds_min.x, n.bounds_min.y, n.bounds_min.z};
  const float hi[3] = {n.bounds_max.x, n.bounds_max.y, n.bounds_max.z};
  const VF zero = hn::Zero(d), scale = hn::Set(d, kRobustFarScale);
  Mask8 bits = 0;
  for (size_t i = 0; i < 8; i += count) {
    VF t0 = hn::Load(d, l.t_min + i), t1 = hn::Load(d, t_far + i);
    for (int a = 0; a < 3; ++a) {
      const VF o = hn::Load(d, l.o[a] + i), inv = hn::Load(d, l.inv[a] + i);
      const MF neg = hn::Lt(inv, zero);  // the sign bit: inv_d is never -0 (d is finite)
      const VF lo_a = hn::Set(d, lo[a]), hi_a = hn::Set(d, hi[a]);
      const VF near = hn::Mul(hn::Sub(hn::IfThenElse(neg, hi_a, lo_a), o), inv);
      const VF far = hn::Mul(hn::Sub(hn::IfThenElse(neg, lo_a, hi_a), o), inv);
      t0 = hn::IfThenElse(hn::Gt(near, t0), near, t0);
      t1 = hn::IfThenElse(hn::Lt(far, t1), far, t1);
    }
    hn::Store(t0, d, t_entry + i);
    bits |= MaskBits(d, hn::Le(t0, hn::Mul(t1, scale))) << i;
  }
  return bits;
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace ptlab::simd {

HWY_EXPORT(InstanceBoxLanesImpl);

InstanceLanes MakeInstanceLanes(const RayPacket8& rays, Mask8 live) {
  InstanceLanes l;
  const float* org[3] = {rays.org_x, rays.org_y, rays.org_z};
  const float* dir[3] = {rays.dir_x, rays.dir_y, rays.dir_z};
  for (int j = 0; j < 8; ++j) {
    const bool on = LaneActive(live, j);
    for (int a = 0; a < 3; ++a) {
      l.o[a][j] = on ? org[a][j] : 0.0f;
      l.inv[a][j] = on ? 1.0f / dir[a][j] : 1.0f;
    }
    l.t_min[j] = on ? rays.t_min[j] : 1.0f;  // with t_far 0 or any t_far below 1: no box
  }
  return l;
}

Mask8 InstanceBoxLanes(const BvhNode& node, const InstanceLanes& lanes, const float* t_far,
                       float* t_entry) {
  return HWY_DYNAMIC_DISPATCH(InstanceBoxLanesImpl)(node, lanes, t_far, t_entry);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
