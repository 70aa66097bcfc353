// Node tests of simd/traverse8's packet walk: the frustum pre-test and the per-lane slab tests.
// Part of simd/traverse8-inl.h: re-included once per target with it (hwy/foreach_target.h).

#if defined(PTLAB_SIMD_TRAVERSE8_PACKET_NODES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TRAVERSE8_PACKET_NODES_INL_H_
#undef PTLAB_SIMD_TRAVERSE8_PACKET_NODES_INL_H_
#else
#define PTLAB_SIMD_TRAVERSE8_PACKET_NODES_INL_H_
#endif

#include "hwy/highway.h"
#include "simd/traverse8_packet_setup-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Lower end of the interval {(p - o) * inv : o in [o_lo, o_hi], inv in [inv_lo, inv_hi]}
// over the four corners (rounding is monotone, so every lane's rounded distance lies within
// the rounded corners), or the upper end with kUpper.
template <bool kUpper>
HWY_INLINE VF IntervalSlab(VF plane, VF o_lo, VF o_hi, VF inv_lo, VF inv_hi) {
  const VF a = hn::Sub(plane, o_hi), b = hn::Sub(plane, o_lo);
  const VF p0 = hn::Mul(a, inv_lo), p1 = hn::Mul(a, inv_hi);
  const VF p2 = hn::Mul(b, inv_lo), p3 = hn::Mul(b, inv_hi);
  if constexpr (kUpper) return hn::Max(hn::Max(p0, p1), hn::Max(p2, p3));
  return hn::Min(hn::Min(p0, p1), hn::Min(p2, p3));
}

// Frustum pre-test of all children of `node` at once (interval arithmetic over the packet's
// lanes, Wald et al. 2007 "Ray tracing animated scenes using coherent grid traversal" style):
// a child it rejects is rejected by the exact slab test of every lane (no NaN can occur: all
// 1/d are finite). Returns the children that need the per-lane test.
HWY_INLINE uint32_t FrustumChildren(DF d, const PacketState& s, const Bvh8Node& node,
                                    float t_far_hi) {
  const size_t lanes = hn::Lanes(d);
  const float* planes = reinterpret_cast<const float*>(&node);
  const uint32_t lo_col[3] = {kLoX, kLoY, kLoZ}, hi_col[3] = {kHiX, kHiY, kHiZ};
  uint32_t near_col[3], far_col[3];
  for (int a = 0; a < 3; ++a) {
    near_col[a] = s.uniform_neg[a] ? hi_col[a] : lo_col[a];
    far_col[a] = s.uniform_neg[a] ? lo_col[a] : hi_col[a];
  }
  const VF t_min = hn::Set(d, s.t_min_lo), t_far = hn::Set(d, t_far_hi);
  const VF scale = hn::Set(d, kRobustFarScale);
  uint32_t bits = 0;
  for (size_t i = 0; i < 8; i += lanes) {
    VF t0 = t_min, t1 = t_far;
    for (int a = 0; a < 3; ++a) {
      const VF o_lo = hn::Set(d, s.o_lo[a]), o_hi = hn::Set(d, s.o_hi[a]);
      const VF inv_lo = hn::Set(d, s.inv_lo[a]), inv_hi = hn::Set(d, s.inv_hi[a]);
      const VF near = hn::Load(d, planes + near_col[a] + i);
      const VF far = hn::Load(d, planes + far_col[a] + i);
      t0 = hn::Max(IntervalSlab<false>(near, o_lo, o_hi, inv_lo, inv_hi), t0);
      t1 = hn::Min(IntervalSlab<true>(far, o_lo, o_hi, inv_lo, inv_hi), t1);
    }
    bits |= MaskBits(d, hn::Le(t0, hn::Mul(t1, scale))) << i;
  }
  return bits & ((1u << node.num_children) - 1);
}

// Tests the children in `candidates` against the lanes in m. cbits[c] receives the lanes
// that hit child c, t_near[c] their entry distances, key[c] the entry distance of the first
// of them (a cheap ordering key).
template <bool kAnyHit>
HWY_INLINE void PacketChildren(DF d, const PacketState& s, const Bvh8Node& node, uint32_t m,
                               uint32_t candidates, uint32_t* cbits, float (*t_near)[8],
                               float* key) {
  const size_t lanes = hn::Lanes(d);
  const uint32_t half_mask = (1u << lanes) - 1;
  const VF scale = hn::Set(d, kRobustFarScale);
  for (uint32_t c = 0; c < 8; ++c) cbits[c] = 0;
  for (size_t i = 0; i < 8; i += lanes) {
    const uint32_t half = (m >> i) & half_mask;
    if (half == 0) continue;
    const MF act = MaskFromBits(d, half);
    const VF ox = hn::Load(d, s.o_x + i), oy = hn::Load(d, s.o_y + i), oz = hn::Load(d, s.o_z + i);
    const VF ix = hn::Load(d, s.inv_x + i), iy = hn::Load(d, s.inv_y + i),
             iz = hn::Load(d, s.inv_z + i);
    const VF t_min = hn::Load(d, s.wt.t_min + i);
    const VF t_far = hn::Load(d, (kAnyHit ? s.wt.t_max : s.best_t) + i);
    const MF neg_x = MaskFromBits(d, s.neg_bits[0] >> i);
    const MF neg_y = MaskFromBits(d, s.neg_bits[1] >> i);
    const MF neg_z = MaskFromBits(d, s.neg_bits[2] >> i);
    for (uint32_t todo = candidates; todo != 0; todo &= todo - 1) {
      const int c = std::countr_zero(todo);
      // Near and far planes by the sign of each lane's 1/d, exactly as the oracle picks them;
      // a shared sign (the usual case for coherent packets) needs no blend.
      VF near_x, far_x, near_y, far_y, near_z, far_z;
      const VF lo_x = hn::Set(d, node.lo_x[c]), hi_x = hn::Set(d, node.hi_x[c]);
      const VF lo_y = hn::Set(d, node.lo_y[c]), hi_y = hn::Set(d, node.hi_y[c]);
      const VF lo_z = hn::Set(d, node.lo_z[c]), hi_z = hn::Set(d, node.hi_z[c]);
      if (s.uniform_neg[0] >= 0) {
        near_x = s.uniform_neg[0] ? hi_x : lo_x, far_x = s.uniform_neg[0] ? lo_x : hi_x;
      } else {
        near_x = hn::IfThenElse(neg_x, hi_x, lo_x), far_x = hn::IfThenElse(neg_x, lo_x, hi_x);
      }
      if (s.uniform_neg[1] >= 0) {
        near_y = s.uniform_neg[1] ? hi_y : lo_y, far_y = s.uniform_neg[1] ? lo_y : hi_y;
      } else {
        near_y = hn::IfThenElse(neg_y, hi_y, lo_y), far_y = hn::IfThenElse(neg_y, lo_y, hi_y);
      }
      if (s.uniform_neg[2] >= 0) {
        near_z = s.uniform_neg[2] ? hi_z : lo_z, far_z = s.uniform_neg[2] ? lo_z : hi_z;
      } else {
        near_z = hn::IfThenElse(neg_z, hi_z, lo_z), far_z = hn::IfThenElse(neg_z, lo_z, hi_z);
      }
      const VF nx = hn::Mul(hn::Sub(near_x, ox), ix), fx = hn::Mul(hn::Sub(far_x, ox), ix);
      const VF ny = hn::Mul(hn::Sub(near_y, oy), iy), fy = hn::Mul(hn::Sub(far_y, oy), iy);
      const VF nz = hn::Mul(hn::Sub(near_z, oz), iz), fz = hn::Mul(hn::Sub(far_z, oz), iz);
      const VF t0 = hn::Max(nz, hn::Max(ny, hn::Max(nx, t_min)));
      const VF t1 = hn::Min(fz, hn::Min(fy, hn::Min(fx, t_far)));
      const uint32_t bits = MaskBits(d, hn::And(act, hn::Le(t0, hn::Mul(t1, scale))));
      if (bits == 0) continue;
      if constexpr (!kAnyHit) {
        // Any hit needs neither entry distances (pops test only the lanes still open) nor
        // an order: any hit ends a lane, wherever it is.
        hn::Store(t0, d, t_near[c] + i);
        if (s.coherent) {
          if (cbits[c] == 0) key[c] = t_near[c][i + std::countr_zero(bits)];
        } else {
          // Lanes of several octants enter a child at unrelated distances: the nearest
          // entry orders the children (the first lane's would be arbitrary).
          const float k = ReduceLive<false>(d, t0, MaskFromBits(d, bits));
          key[c] = cbits[c] == 0 || k < key[c] ? k : key[c];
        }
      }
      cbits[c] |= bits << i;
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TRAVERSE8_PACKET_NODES_INL_H_ toggle
