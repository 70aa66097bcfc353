// Leaf tests of simd/traverse8's packet walk: one triangle against all lanes, or lanes alone.
// Part of simd/traverse8-inl.h: re-included once per target with it (hwy/foreach_target.h).

#if defined(PTLAB_SIMD_TRAVERSE8_PACKET_LEAVES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TRAVERSE8_PACKET_LEAVES_INL_H_
#undef PTLAB_SIMD_TRAVERSE8_PACKET_LEAVES_INL_H_
#else
#define PTLAB_SIMD_TRAVERSE8_PACKET_LEAVES_INL_H_
#endif

#include "hwy/highway.h"
#include "simd/traverse8_packet_setup-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Coordinate k of a broadcast point, per lane: x where k = 0 (is0), y where k = 1 (is1), else z.
HWY_INLINE VF LaneAxis(MF is0, MF is1, VF x, VF y, VF z) {
  return hn::IfThenElse(is0, x, hn::IfThenElse(is1, y, z));
}

// Vertex v (0, 1, 2) of leaf triangle j (of n), permuted to each lane's (kx, ky, kz): with
// kMixedK by the lanes' masks (lanes [i, i + Lanes(d)) of s->k_is), else by the packet's
// shared s->uniform_k.
template <bool kMixedK>
HWY_INLINE void PermutedVertex(DF d, const PacketState& s, size_t i, const float* base, uint32_t n,
                               uint32_t j, int v, const uint32_t* k_n, VF* px, VF* py, VF* pz) {
  const float* col = base + 3 * v * n + j;
  if constexpr (!kMixedK) {
    *px = hn::Set(d, col[k_n[0]]), *py = hn::Set(d, col[k_n[1]]), *pz = hn::Set(d, col[k_n[2]]);
  } else {
    const VF x = hn::Set(d, col[0]), y = hn::Set(d, col[n]), z = hn::Set(d, col[2 * n]);
    VF* out[3] = {px, py, pz};
    for (int a = 0; a < 3; ++a) {
      *out[a] = LaneAxis(MaskFromBits(d, s.k_is[a][0] >> i), MaskFromBits(d, s.k_is[a][1] >> i),
                         x, y, z);
    }
  }
}

// One triangle at a time against all lanes of m, each lane with its own axis permutation
// (kMixedK: blended per lane, bit for bit the values a lane's own test would load) or the
// packet's shared one. Closest hit: updates the lanes' best hits. Any hit: returns the lanes
// that hit.
template <bool kAnyHit, bool kMixedK>
HWY_INLINE uint32_t LeafBroadcast(DF d, const Bvh8& bvh, Bvh8Ref leaf, PacketState* s, uint32_t m) {
  const DI di;
  const size_t lanes = hn::Lanes(d);
  const uint32_t half_mask = (1u << lanes) - 1;
  const uint32_t n = LeafCount(leaf);
  const float* base = bvh.Leaf(leaf);
  // The shared permutation's column offsets (unused with kMixedK).
  const uint32_t k_n[3] = {kMixedK ? 0 : s->uniform_k[0] * n, kMixedK ? 0 : s->uniform_k[1] * n,
                           kMixedK ? 0 : s->uniform_k[2] * n};
  uint32_t hit_lanes = 0;
  for (size_t i = 0; i < 8; i += lanes) {
    uint32_t half = (m >> i) & half_mask;
    if (half == 0) continue;
    for (uint32_t j = 0; j < n && half != 0; ++j) {
      const MF act = MaskFromBits(d, half);
      VF ax, ay, az, bx, by, bz, cx, cy, cz;
      PermutedVertex<kMixedK>(d, *s, i, base, n, j, 0, k_n, &ax, &ay, &az);
      PermutedVertex<kMixedK>(d, *s, i, base, n, j, 1, k_n, &bx, &by, &bz);
      PermutedVertex<kMixedK>(d, *s, i, base, n, j, 2, k_n, &cx, &cy, &cz);
      VF t = hn::Zero(d), b1 = t, b2 = t;
      const MF hit =
          WatertightTest(d, s->wt, i, ax, ay, az, bx, by, bz, cx, cy, cz, act, &t, &b1, &b2);
      if (hn::AllFalse(d, hit)) continue;
      if constexpr (kAnyHit) {
        const uint32_t bits = MaskBits(d, hit);
        hit_lanes |= bits << i;
        half &= ~bits;
      } else {
        const VI prim = hn::Set(di, static_cast<int32_t>(bvh.LeafPrim(leaf, j)));
        const VF bt = hn::Load(d, s->best_t + i);
        const VI bp = hn::Load(di, s->best_prim + i);
        // Scene rows are below 2^28, so a signed compare orders them; kNoHit (-1) only
        // appears with best_t = t_max, which any accepted t is below.
        const MF better = hn::And(
            hit,
            hn::Or(hn::Lt(t, bt), hn::And(hn::Eq(t, bt), hn::RebindMask(d, hn::Lt(prim, bp)))));
        hn::Store(hn::IfThenElse(better, t, bt), d, s->best_t + i);
        hn::Store(hn::IfThenElse(better, b1, hn::Load(d, s->best_b1 + i)), d, s->best_b1 + i);
        hn::Store(hn::IfThenElse(better, b2, hn::Load(d, s->best_b2 + i)), d, s->best_b2 + i);
        hn::Store(hn::IfThenElse(hn::RebindMask(di, better), prim, bp), di, s->best_prim + i);
      }
    }
  }
  return hit_lanes;
}

// Out of line: mixed permutations are the incoherent packets' case, so the coherent packets'
// traversal loop keeps only the shared-permutation copy of the leaf loop.
template <bool kAnyHit>
HWY_NOINLINE uint32_t LeafBroadcastMixedK(const Bvh8& bvh, Bvh8Ref leaf, PacketState* s,
                                          uint32_t m) {
  return LeafBroadcast<kAnyHit, true>(DF(), bvh, leaf, s, m);
}

// Each lane of m tests the leaf alone, its constants read from its lane of the packet's.
// Closest hit: updates the lanes' best hits. Any hit: returns the lanes that hit.
template <bool kAnyHit>
HWY_INLINE uint32_t LeafLanes(DF d, const Bvh8& bvh, Bvh8Ref leaf, PacketState* s, uint32_t m) {
  uint32_t hit_lanes = 0;
  for (uint32_t bits = m; bits != 0; bits &= bits - 1) {
    const int j = std::countr_zero(bits);
    const int k[3] = {LaneWatertightAxis(*s, 0, j), LaneWatertightAxis(*s, 1, j),
                      LaneWatertightAxis(*s, 2, j)};
    LaneBest best{s->best_t[j], static_cast<uint32_t>(s->best_prim[j]), s->best_b1[j],
                  s->best_b2[j]};
    if (LeafSingle<kAnyHit>(d, bvh, leaf, k, s->wt, static_cast<size_t>(j), &best)) {
      hit_lanes |= LaneBit(j);
    }
    if constexpr (!kAnyHit) {
      s->best_t[j] = best.t, s->best_prim[j] = static_cast<int32_t>(best.prim);
      s->best_b1[j] = best.b1, s->best_b2[j] = best.b2;
    }
  }
  return hit_lanes;
}

template <bool kAnyHit>
HWY_INLINE uint32_t LeafPacket(DF d, const Bvh8& bvh, Bvh8Ref leaf, PacketState* s, uint32_t m,
                               const Traverse8Options& options) {
  const uint32_t n = LeafCount(leaf);
  if (options.broadcast_leaves && n < static_cast<uint32_t>(std::popcount(m))) {
    if (s->uniform_k[0] >= 0) return LeafBroadcast<kAnyHit, false>(d, bvh, leaf, s, m);
    return LeafBroadcastMixedK<kAnyHit>(bvh, leaf, s, m);
  }
  return LeafLanes<kAnyHit>(d, bvh, leaf, s, m);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TRAVERSE8_PACKET_LEAVES_INL_H_ toggle
