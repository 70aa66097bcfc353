// Packet state of simd/traverse8: per-lane setup, lane reductions and the packet's frustum.
// Part of simd/traverse8-inl.h: re-included once per target with it (hwy/foreach_target.h).

#if defined(PTLAB_SIMD_TRAVERSE8_PACKET_SETUP_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TRAVERSE8_PACKET_SETUP_INL_H_
#undef PTLAB_SIMD_TRAVERSE8_PACKET_SETUP_INL_H_
#else
#define PTLAB_SIMD_TRAVERSE8_PACKET_SETUP_INL_H_
#endif

#include "hwy/highway.h"
#include "simd/traverse8_single-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// ---------------------------------------------------------------------------------------------
// Packets: one child box or one triangle against eight rays per vector.

struct PacketState {
  alignas(32) float o_x[8], o_y[8], o_z[8];
  alignas(32) float inv_x[8], inv_y[8], inv_z[8];
  WatertightLanes wt;  // and the lanes' t_min, t_max
  alignas(32) float best_t[8], best_b1[8], best_b2[8];
  alignas(32) int32_t best_prim[8];
  uint32_t neg_bits[3];           // lanes whose 1/d is negative, per axis
  int uniform_neg[3];             // -1 mixed, else 0/1 shared by all live lanes
  int uniform_k[3];               // the (kx, ky, kz) shared by all live lanes; kx = -1 if mixed
  uint32_t k_is[3][2];            // lanes whose kx (ky, kz) is axis 0 / axis 1 (else axis 2):
                                  // the lanes' watertight axes (LaneWatertightAxis)
  bool coherent;                  // all live lanes share the sign of 1/d on every axis (one octant)
  bool frustum;                   // coherent, and every 1/d finite
  bool shared_origin;             // frustum, and all live lanes start at one point
  // Interval bounds of the live lanes (the packet's frustum), valid when `frustum` is set.
  float o_lo[3], o_hi[3], inv_lo[3], inv_hi[3], t_min_lo;
};

// Watertight axis a (0 = kx, 1 = ky, 2 = kz) of lane j, from the lane masks: only lanes that
// go single or test a leaf alone need it, so the packet's setup stores no per-lane axes.
HWY_INLINE int LaneWatertightAxis(const PacketState& s, int a, int j) {
  // Branch-free (the masks are exclusive: 0, 1 or neither = 2): the lanes' axes vary
  // unpredictably in incoherent packets.
  const int is0 = static_cast<int>((s.k_is[a][0] >> j) & 1u);
  const int is1 = static_cast<int>((s.k_is[a][1] >> j) & 1u);
  return 2 - 2 * is0 - is1;
}

// Lane j as a single ray (for the single-ray switch); the same values MakeSingleRay computes
// from the lane's ray, whose other watertight constants are lane j of s.wt.
HWY_INLINE SingleRay LaneSingleRay(const PacketState& s, int j) {
  SingleRay r;
  r.o[0] = s.o_x[j], r.o[1] = s.o_y[j], r.o[2] = s.o_z[j];
  r.inv_d[0] = s.inv_x[j], r.inv_d[1] = s.inv_y[j], r.inv_d[2] = s.inv_z[j];
  const uint32_t lo[3] = {kLoX, kLoY, kLoZ}, hi[3] = {kHiX, kHiY, kHiZ};
  for (int a = 0; a < 3; ++a) {
    const bool neg = LaneActive(s.neg_bits[a], j);
    r.near[a] = neg ? hi[a] : lo[a];
    r.far[a] = neg ? lo[a] : hi[a];
  }
  for (int a = 0; a < 3; ++a) r.k[a] = LaneWatertightAxis(s, a, j);
  r.t_min = s.wt.t_min[j];
  r.t_max = s.wt.t_max[j];
  return r;
}

// Smallest (kMax: largest) lane of v among `live`.
template <bool kMax>
HWY_INLINE float ReduceLive(DF d, VF v, MF live) {
  const VF fill = hn::Set(d, kMax ? -kInf : kInf);
  const VF x = hn::IfThenElse(live, v, fill);
  return hn::GetLane(kMax ? hn::MaxOfLanes(d, x) : hn::MinOfLanes(d, x));
}

// Smallest (kMax: largest) value of a packet column among the lanes of `live`: the vectors
// are folded lane-wise first, so there is one reduction per column.
template <bool kMax>
HWY_INLINE float FoldLive(DF d, const float* column, uint32_t live) {
  const size_t lanes = hn::Lanes(d);
  const uint32_t half_mask = (1u << lanes) - 1;
  const VF fill = hn::Set(d, kMax ? -kInf : kInf);
  VF acc = fill;
  for (size_t i = 0; i < 8; i += lanes) {
    const VF v = hn::IfThenElse(MaskFromBits(d, (live >> i) & half_mask), hn::Load(d, column + i),
                                fill);
    acc = kMax ? hn::Max(acc, v) : hn::Min(acc, v);
  }
  return hn::GetLane(kMax ? hn::MaxOfLanes(d, acc) : hn::MinOfLanes(d, acc));
}

#if HWY_TARGET != HWY_SCALAR && HWY_TARGET != HWY_EMU128
// The smallest lane of each of eight 8-lane vectors, in one vector (lane c = column c): a
// transposing tree of interleaves and minima, 14 shuffles instead of 8 separate reductions'
// 24 (only where a vector holds all eight lanes; the caller checks).
HWY_INLINE VF MinOfColumns8(DF d, const VF* v) {
  const hn::Repartition<double, DF> d64;
  VF m[4];
  for (int k = 0; k < 4; ++k) {
    // [a0 b0 a1 b1 | a4 b4 a5 b5] against [a2 b2 a3 b3 | a6 b6 a7 b7].
    m[k] = hn::Min(hn::InterleaveLower(d, v[2 * k], v[2 * k + 1]),
                   hn::InterleaveUpper(d, v[2 * k], v[2 * k + 1]));
  }
  VF n[2];
  for (int k = 0; k < 2; ++k) {
    // Pairs of columns as 64-bit lanes: four columns' minima over lanes {0..3} | {4..7}.
    const auto lo = hn::BitCast(d64, m[2 * k]), hi = hn::BitCast(d64, m[2 * k + 1]);
    n[k] = hn::Min(hn::BitCast(d, hn::InterleaveLower(d64, lo, hi)),
                   hn::BitCast(d, hn::InterleaveUpper(d64, lo, hi)));
  }
  return hn::Min(hn::ConcatLowerLower(d, n[1], n[0]), hn::ConcatUpperUpper(d, n[1], n[0]));
}
#endif

// The packet's frustum (interval bounds of origins, 1/d and t_min over the live lanes),
// written straight into *s: scalar results gathered in locals and copied as pairs stalled on
// store forwarding (measured, 14 % of Occluded8's setup on coherent rays).
HWY_INLINE void SetupFrustum(DF d, uint32_t live, PacketState* s) {
#if HWY_TARGET != HWY_SCALAR && HWY_TARGET != HWY_EMU128
  if constexpr (hn::MaxLanes(DF()) == 8) {
    // Thirteen reductions as two transposed batches of eight: maxima as minima of the
    // negated columns (negation is exact; the sign of a zero bound changes no comparison).
    const MF on = MaskFromBits(d, live);
    const VF fill = hn::Set(d, kInf);
    const float* cols[7] = {s->o_x, s->o_y, s->o_z, s->inv_x, s->inv_y, s->inv_z, s->wt.t_min};
    VF lo[8], hi[8];
    for (int c = 0; c < 7; ++c) lo[c] = hn::IfThenElse(on, hn::Load(d, cols[c]), fill);
    for (int c = 0; c < 6; ++c) hi[c] = hn::IfThenElse(on, hn::Neg(hn::Load(d, cols[c])), fill);
    lo[7] = hi[6] = hi[7] = fill;
    alignas(32) float l[8], h[8];
    hn::Store(MinOfColumns8(d, lo), d, l);
    hn::Store(MinOfColumns8(d, hi), d, h);
    for (int a = 0; a < 3; ++a) {
      s->o_lo[a] = l[a], s->o_hi[a] = -h[a];
      s->inv_lo[a] = l[3 + a], s->inv_hi[a] = -h[3 + a];
    }
    s->t_min_lo = l[6];
    return;
  }
#endif
  const float* o[3] = {s->o_x, s->o_y, s->o_z};
  const float* inv[3] = {s->inv_x, s->inv_y, s->inv_z};
  for (int a = 0; a < 3; ++a) {
    s->o_lo[a] = FoldLive<false>(d, o[a], live), s->o_hi[a] = FoldLive<true>(d, o[a], live);
    s->inv_lo[a] = FoldLive<false>(d, inv[a], live);
    s->inv_hi[a] = FoldLive<true>(d, inv[a], live);
  }
  s->t_min_lo = FoldLive<false>(d, s->wt.t_min, live);
}

// Per-lane setup, vectorised: the oracle's per-ray precomputation (1/d, the watertight axes
// kx, ky, kz by MakeWatertightRay's rule, the shear constants and the permuted origin) with
// the same IEEE divisions, so every value equals the scalar one. Returns the lanes that can
// hit at all (active and t_min < t_max); dead lanes get benign values.
HWY_INLINE Mask8 SetupPacket(const RayPacket8& rays, Mask8 active, PacketState* s) {
  const DF d;
  const size_t lanes = hn::Lanes(d);
  const uint32_t half_mask = (1u << lanes) - 1;
  const VF zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  Mask8 live = 0;
  uint32_t kz0_bits = 0, kz1_bits = 0, swap_bits = 0, finite_bits = 0;
  // The packet's lines requested at once, in address order, before the loads below (which
  // start at t_min, the packet's last line but one): a caller streaming packets from memory
  // otherwise stalled on the first load (perf: 58 % of Intersect8Impl's samples there; read
  // out of address order, the lines perhaps also escaped the hardware prefetcher). Measured
  // (traverse_bench, AMD EPYC Zen 5, two alternated runs): Intersect8 camera rays veach 41-47
  // -> 72-74 M rays/s, table 25 -> 30-31 M; shadow rays table 15-16 -> 19 M; Occluded8 bounce
  // rays table 25 -> 28-29 M; the rest within the runs' noise. (A packet is 32-byte aligned:
  // it may span five lines.)
  const uintptr_t first_byte = reinterpret_cast<uintptr_t>(&rays);
  for (uintptr_t line = first_byte & ~uintptr_t{63}; line < first_byte + sizeof(RayPacket8);
       line += 64) {
    hwy::Prefetch(reinterpret_cast<const char*>(line));
  }
  s->neg_bits[0] = s->neg_bits[1] = s->neg_bits[2] = 0;
  for (size_t i = 0; i < 8; i += lanes) {
    const VF t_min = hn::Load(d, rays.t_min + i), t_max = hn::Load(d, rays.t_max + i);
    const MF on = hn::And(MaskFromBits(d, (active >> i) & half_mask), hn::Lt(t_min, t_max));
    const uint32_t on_bits = MaskBits(d, on);
    live |= on_bits << i;
    // Dead lanes compute with o = 0, d = (1, 1, 1), t = 0: no NaN, never read.
    const VF ox = hn::IfThenElseZero(on, hn::Load(d, rays.org_x + i));
    const VF oy = hn::IfThenElseZero(on, hn::Load(d, rays.org_y + i));
    const VF oz = hn::IfThenElseZero(on, hn::Load(d, rays.org_z + i));
    const VF dx = hn::IfThenElse(on, hn::Load(d, rays.dir_x + i), one);
    const VF dy = hn::IfThenElse(on, hn::Load(d, rays.dir_y + i), one);
    const VF dz = hn::IfThenElse(on, hn::Load(d, rays.dir_z + i), one);
    const VF ix = hn::Div(one, dx), iy = hn::Div(one, dy), iz = hn::Div(one, dz);
    const VF tn = hn::IfThenElseZero(on, t_min), tx = hn::IfThenElseZero(on, t_max);
    hn::Store(ox, d, s->o_x + i), hn::Store(oy, d, s->o_y + i), hn::Store(oz, d, s->o_z + i);
    hn::Store(ix, d, s->inv_x + i), hn::Store(iy, d, s->inv_y + i), hn::Store(iz, d, s->inv_z + i);
    hn::Store(tn, d, s->wt.t_min + i), hn::Store(tx, d, s->wt.t_max + i);
    hn::Store(tx, d, s->best_t + i);
    hn::Store(hn::Set(DI(), static_cast<int32_t>(kNoHit)), DI(), s->best_prim + i);
    hn::Store(zero, d, s->best_b1 + i), hn::Store(zero, d, s->best_b2 + i);
    s->neg_bits[0] |= MaskBits(d, hn::Lt(ix, zero)) << i;
    s->neg_bits[1] |= MaskBits(d, hn::Lt(iy, zero)) << i;
    s->neg_bits[2] |= MaskBits(d, hn::Lt(iz, zero)) << i;
    // kz = MaxDimension(|d|): (x > y) ? (x > z ? 0 : 2) : (y > z ? 1 : 2).
    const VF ax = hn::Abs(dx), ay = hn::Abs(dy), az = hn::Abs(dz);
    const MF x_gt_y = hn::Gt(ax, ay);
    const MF kz0 = hn::And(x_gt_y, hn::Gt(ax, az));
    const MF kz1 = hn::AndNot(x_gt_y, hn::Gt(ay, az));
    // (kx, ky) = (y, z) for kz = x, (z, x) for kz = y, (x, y) for kz = z; swapped when
    // d[kz] < 0 (keeps the winding).
    const VF d_kz = hn::IfThenElse(kz0, dx, hn::IfThenElse(kz1, dy, dz));
    const MF swap = hn::Lt(d_kz, zero);
    const VF d_a = hn::IfThenElse(kz0, dy, hn::IfThenElse(kz1, dz, dx));
    const VF d_b = hn::IfThenElse(kz0, dz, hn::IfThenElse(kz1, dx, dy));
    const VF o_a = hn::IfThenElse(kz0, oy, hn::IfThenElse(kz1, oz, ox));
    const VF o_b = hn::IfThenElse(kz0, oz, hn::IfThenElse(kz1, ox, oy));
    const VF o_kz = hn::IfThenElse(kz0, ox, hn::IfThenElse(kz1, oy, oz));
    const VF d_kx = hn::IfThenElse(swap, d_b, d_a), d_ky = hn::IfThenElse(swap, d_a, d_b);
    hn::Store(hn::Div(d_kx, d_kz), d, s->wt.sx + i);
    hn::Store(hn::Div(d_ky, d_kz), d, s->wt.sy + i);
    // 1 / d[kz] is that axis's 1/d, the same IEEE division: one division fewer.
    hn::Store(hn::IfThenElse(kz0, ix, hn::IfThenElse(kz1, iy, iz)), d, s->wt.sz + i);
    hn::Store(hn::IfThenElse(swap, o_b, o_a), d, s->wt.ox + i);
    hn::Store(hn::IfThenElse(swap, o_a, o_b), d, s->wt.oy + i);
    hn::Store(o_kz, d, s->wt.oz + i);
    kz0_bits |= MaskBits(d, kz0) << i;
    kz1_bits |= MaskBits(d, kz1) << i;
    swap_bits |= MaskBits(d, swap) << i;
    // The frustum needs finite 1/d (d = 0, or so small that 1/d overflows, gives +-inf).
    const VF inf = hn::Set(d, kInf);
    const MF fin_inv = hn::And(hn::And(hn::Lt(hn::Abs(ix), inf), hn::Lt(hn::Abs(iy), inf)),
                               hn::Lt(hn::Abs(iz), inf));
    finite_bits |= MaskBits(d, fin_inv) << i;
  }
  // The same axes as lane masks: kz = 0 (kz0), 1 (kz1) or 2; (kx, ky) = (kz + 1, kz + 2)
  // mod 3, exchanged where swap is set.
  const uint32_t z0 = kz0_bits, z1 = kz1_bits, z2 = ~(kz0_bits | kz1_bits), sw = swap_bits;
  s->k_is[0][0] = (~sw & z2) | (sw & z1), s->k_is[0][1] = (~sw & z0) | (sw & z2);
  s->k_is[1][0] = (~sw & z1) | (sw & z2), s->k_is[1][1] = (~sw & z2) | (sw & z0);
  s->k_is[2][0] = z0, s->k_is[2][1] = z1;
  bool uniform = true;
  for (int a = 0; a < 3; ++a) {
    const uint32_t neg = s->neg_bits[a] & live;
    s->uniform_neg[a] = neg == 0 ? 0 : (neg == live ? 1 : -1);
    uniform &= s->uniform_neg[a] >= 0;
  }
  // Shared watertight axes: kz from the masks, then the swap.
  const bool same_kz =
      (kz0_bits & live) == live || (kz1_bits & live) == live || ((kz0_bits | kz1_bits) & live) == 0;
  const bool same_swap = (swap_bits & live) == 0 || (swap_bits & live) == live;
  s->uniform_k[0] = -1;
  if (live != 0 && same_kz && same_swap) {
    const int j = std::countr_zero(live);
    for (int a = 0; a < 3; ++a) s->uniform_k[a] = LaneWatertightAxis(*s, a, j);
  }
  s->coherent = live != 0 && uniform;
  s->frustum = s->coherent && (finite_bits & live) == live;
  // The frustum's bounds only for packets that will use them (incoherent packets skip these
  // thirteen reductions).
  s->shared_origin = false;
  if (s->frustum) {
    SetupFrustum(d, live, s);
    s->shared_origin = s->o_lo[0] == s->o_hi[0] && s->o_lo[1] == s->o_hi[1] &&
                       s->o_lo[2] == s->o_hi[2];
  }
  return live;
}

// Lanes of `m` whose stacked entry distance is within the closest hit so far.
HWY_INLINE uint32_t LanesBeforeClosest(DF d, const PacketState& s, const float* t_entry,
                                       uint32_t m) {
  const size_t lanes = hn::Lanes(d);
  const VF scale = hn::Set(d, kRobustFarScale);
  uint32_t bits = 0;
  for (size_t i = 0; i < 8; i += lanes) {
    const VF best = hn::Load(d, s.best_t + i);
    bits |= MaskBits(d, hn::Le(hn::Load(d, t_entry + i), hn::Mul(best, scale))) << i;
  }
  return bits & m;
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TRAVERSE8_PACKET_SETUP_INL_H_ toggle
