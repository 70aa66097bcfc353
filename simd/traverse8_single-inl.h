// Single-ray BVH8 traversal of simd/traverse8: eight child boxes, a leaf's triangles per vector.
// Part of simd/traverse8-inl.h: re-included once per target with it (hwy/foreach_target.h).

#if defined(PTLAB_SIMD_TRAVERSE8_SINGLE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TRAVERSE8_SINGLE_INL_H_
#undef PTLAB_SIMD_TRAVERSE8_SINGLE_INL_H_
#else
#define PTLAB_SIMD_TRAVERSE8_SINGLE_INL_H_
#endif

#include "hwy/highway.h"
#include "simd/traverse8_watertight-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// ---------------------------------------------------------------------------------------------
// Single ray: eight child boxes per vector, up to eight leaf triangles per vector.

// A ray's box-test constants and watertight axes; its other watertight constants are one lane
// of a WatertightLanes (LeafSingle).
struct SingleRay {
  float o[3], inv_d[3];
  uint32_t near[3], far[3];  // plane column offsets chosen by the sign of 1/d (as the oracle)
  int k[3];                  // the watertight axes (kx, ky, kz)
  float t_min, t_max;
};

struct LaneBest {
  float t;
  uint32_t prim;
  float b1, b2;
};

// A lone ray, its watertight constants in lane 0 of *rv.
HWY_INLINE SingleRay MakeSingleRay(const Vec3f& o, const Vec3f& d, float t_min, float t_max,
                                   WatertightLanes* rv) {
  SingleRay r;
  const uint32_t lo[3] = {kLoX, kLoY, kLoZ}, hi[3] = {kHiX, kHiY, kHiZ};
  for (int a = 0; a < 3; ++a) {
    r.o[a] = o[a];
    r.inv_d[a] = 1.0f / d[a];
    const bool neg = std::signbit(r.inv_d[a]);
    r.near[a] = neg ? hi[a] : lo[a];
    r.far[a] = neg ? lo[a] : hi[a];
  }
  const WatertightRay wt = MakeWatertightRay(o, d);
  r.k[0] = wt.kx, r.k[1] = wt.ky, r.k[2] = wt.kz;
  r.t_min = t_min;
  r.t_max = t_max;
  // Eight scalar stores instead of 64: WatertightTest<true> broadcasts lane 0.
  rv->ox[0] = wt.ox, rv->oy[0] = wt.oy, rv->oz[0] = wt.oz;
  rv->sx[0] = wt.sx, rv->sy[0] = wt.sy, rv->sz[0] = wt.sz;
  rv->t_min[0] = t_min, rv->t_max[0] = t_max;
  return r;
}

// Starts loading a child before it is visited: traversal of large scenes waits on memory.
HWY_INLINE void PrefetchChild(const Bvh8& bvh, Bvh8Ref ref) {
  if (IsLeaf(ref)) {
    // The leaf's cache lines (kBvh8LeafColumns floats a triangle), and no line past it.
    const float* p = bvh.Leaf(ref);
    const uint32_t floats = kBvh8LeafColumns * LeafCount(ref);
    for (uint32_t f = 0; f < floats; f += 16) hwy::Prefetch(p + f);
  } else {
    const char* p = reinterpret_cast<const char*>(&bvh.Node(ref));
    hwy::Prefetch(p), hwy::Prefetch(p + 64), hwy::Prefetch(p + 128), hwy::Prefetch(p + 192);
  }
}

// One ray (watertight axes k, its other constants in lane `lane` of rv) against the (up to
// eight) triangles of a leaf, all in one vector (two on 128-bit targets). Closest hit: updates
// *best with the oracle's rule (smaller t, then lower scene row). Any hit: returns true at the
// first hit.
template <bool kAnyHit>
HWY_INLINE bool LeafSingle(DF d, const Bvh8& bvh, Bvh8Ref leaf, const int* k,
                           const WatertightLanes& rv, size_t lane, LaneBest* best) {
  const uint32_t n = LeafCount(leaf);
  const float* base = bvh.Leaf(leaf);
  const float* ax = base + k[0] * n;
  const float* ay = base + k[1] * n;
  const float* az = base + k[2] * n;
  const float* bx = base + (3 + k[0]) * n;
  const float* by = base + (3 + k[1]) * n;
  const float* bz = base + (3 + k[2]) * n;
  const float* cx = base + (6 + k[0]) * n;
  const float* cy = base + (6 + k[1]) * n;
  const float* cz = base + (6 + k[2]) * n;
  const uint32_t lanes = static_cast<uint32_t>(hn::Lanes(d));
  for (uint32_t i = 0; i < n; i += lanes) {
    VF t = hn::Zero(d), b1 = t, b2 = t;
    const MF hit = WatertightTest<true>(
        d, rv, lane, hn::LoadU(d, ax + i), hn::LoadU(d, ay + i), hn::LoadU(d, az + i),
        hn::LoadU(d, bx + i), hn::LoadU(d, by + i), hn::LoadU(d, bz + i), hn::LoadU(d, cx + i),
        hn::LoadU(d, cy + i), hn::LoadU(d, cz + i), hn::FirstN(d, n - i), &t, &b1, &b2);
    uint32_t bits = MaskBits(d, hit);
    if (bits == 0) continue;
    if constexpr (kAnyHit) {
      return true;
    } else {
      alignas(32) float tt[8], bb1[8], bb2[8];
      hn::Store(t, d, tt), hn::Store(b1, d, bb1), hn::Store(b2, d, bb2);
      for (; bits != 0; bits &= bits - 1) {
        const int j = std::countr_zero(bits);
        const uint32_t prim = bvh.LeafPrim(leaf, i + j);
        if (tt[j] < best->t || (tt[j] == best->t && prim < best->prim)) {
          *best = {tt[j], prim, bb1[j], bb2[j]};
        }
      }
    }
  }
  return false;
}

// The children whose entry distance (dist, one per child) is within the closest hit at
// best_t: the pop test of TraverseSingle's stack, for eight children at once.
HWY_INLINE uint32_t ChildrenBefore(DF d, const float* dist, float best_t) {
  const VF far = hn::Set(d, best_t * kRobustFarScale);
  uint32_t bits = 0;
  for (size_t i = 0; i < 8; i += hn::Lanes(d)) {
    bits |= MaskBits(d, hn::Le(hn::Load(d, dist + i), far)) << i;
  }
  return bits;
}

// Single-ray traversal of the subtree `start` (the oracle's order-independent closest-hit
// rule, so the result does not depend on the visiting order), the ray's watertight constants
// in lane `lane` of ray_wt. Closest hit: *best starts as {t_max, kNoHit} (or a packet lane's
// hit so far) and is updated. Any hit: returns whether something was hit.
template <bool kAnyHit>
HWY_INLINE bool TraverseSingle(const Bvh8& bvh, Bvh8Ref start, const SingleRay& r,
                               const WatertightLanes& ray_wt, size_t lane, LaneBest* best_io) {
  const DF d;
  const size_t lanes = hn::Lanes(d);
  // A local copy of the ray's constants (lane 0): the leaf tests' broadcasts stay in
  // registers, which they did not when read from the packet (measured: Intersect8 terrain
  // bounce rays -5 %).
  WatertightLanes rv;
  rv.ox[0] = ray_wt.ox[lane], rv.oy[0] = ray_wt.oy[lane], rv.oz[0] = ray_wt.oz[lane];
  rv.sx[0] = ray_wt.sx[lane], rv.sy[0] = ray_wt.sy[lane], rv.sz[0] = ray_wt.sz[lane];
  rv.t_min[0] = ray_wt.t_min[lane], rv.t_max[0] = ray_wt.t_max[lane];
  // The closest hit so far lives in locals (registers) until the end: through the pointer,
  // every store to it would force the next node's far end to be reloaded from memory.
  LaneBest best = *best_io;
  const VF ox = hn::Set(d, r.o[0]), oy = hn::Set(d, r.o[1]), oz = hn::Set(d, r.o[2]);
  const VF ix = hn::Set(d, r.inv_d[0]), iy = hn::Set(d, r.inv_d[1]), iz = hn::Set(d, r.inv_d[2]);
  const VF t_min = hn::Set(d, r.t_min), scale = hn::Set(d, kRobustFarScale);
  const VF inf = hn::Set(d, kInf);
  // Any hit: a segment that ends inside the scene (a shadow ray) visits the nearest child
  // first, the ones around its origin last: its occluders lie between its ends, while the
  // surface it starts on rarely occludes it. Measured on traverse_bench's shadow rays
  // (Occluded1): veach +20 %, table -1 %, terrain -2 %; renders unchanged within 2 %.
  // A longer ray keeps the children's order: nearest first measured 30 % slower for table
  // bounce rays, whose nearest boxes ahead hold geometry the ray only grazes.
  const float min_inv =
      std::min(std::abs(r.inv_d[0]), std::min(std::abs(r.inv_d[1]), std::abs(r.inv_d[2])));
  const bool nearest_first = !kAnyHit || r.t_max < bvh.extent * min_inv;
  struct Entry {
    Bvh8Ref ref;
    float t_entry;
  };
  Entry stack[kStackSize];
  int sp = 0;
  Bvh8Ref cur = start;
  bool any = false;
  for (;;) {
    if (!IsLeaf(cur)) {
      const Bvh8Node& node = bvh.Node(cur);
      const float* planes = reinterpret_cast<const float*>(&node);
      const VF t_max = hn::Set(d, kAnyHit ? r.t_max : best.t);
      alignas(32) float dist[8];
      uint32_t bits = 0;
      for (size_t i = 0; i < 8; i += lanes) {
        // The oracle's IntersectBox for eight boxes: (plane - o) * (1/d), the near planes
        // folded into [t_min, t_max] with x, y, z in turn; x86 max/min return their second
        // operand on NaN, which is the oracle's "leave the interval unchanged".
        const VF nx = hn::Mul(hn::Sub(hn::Load(d, planes + r.near[0] + i), ox), ix);
        const VF ny = hn::Mul(hn::Sub(hn::Load(d, planes + r.near[1] + i), oy), iy);
        const VF nz = hn::Mul(hn::Sub(hn::Load(d, planes + r.near[2] + i), oz), iz);
        const VF fx = hn::Mul(hn::Sub(hn::Load(d, planes + r.far[0] + i), ox), ix);
        const VF fy = hn::Mul(hn::Sub(hn::Load(d, planes + r.far[1] + i), oy), iy);
        const VF fz = hn::Mul(hn::Sub(hn::Load(d, planes + r.far[2] + i), oz), iz);
        const VF t0 = hn::Max(nz, hn::Max(ny, hn::Max(nx, t_min)));
        const VF t1 = hn::Min(fz, hn::Min(fy, hn::Min(fx, t_max)));
        bits |= MaskBits(d, hn::Le(t0, hn::Mul(t1, scale))) << i;
        // Any hit sorts by entry with the children around the origin last (key +inf).
        hn::Store(kAnyHit ? hn::IfThenElse(hn::Gt(t0, t_min), t0, inf) : t0, d, dist + i);
      }
      // The leaf children hit are tested at once, before any inner child is pushed: a hit
      // there ends an any-hit ray, and culls the inner children of a closest-hit one.
      // Measured: Occluded1 table bounce rays +5 %; closest hit Intersect8 table bounce rays
      // +7 %, but Intersect1 veach camera rays -8 % (Intersect8 there unchanged).
      if (const uint32_t leaves = bits & node.leaf_children; leaves != 0) {
        bool hit = false;
        for (uint32_t l = leaves; l != 0 && !hit; l &= l - 1) {
          hit = LeafSingle<kAnyHit>(d, bvh, node.child[std::countr_zero(l)], r.k, rv, 0, &best);
        }
        if (kAnyHit && hit) {
          any = true;
          break;
        }
        bits &= ~leaves;
        if constexpr (!kAnyHit) bits &= ChildrenBefore(d, dist, best.t);
      }
      if (bits != 0) {
        const int c0 = std::countr_zero(bits);
        bits &= bits - 1;
        if (bits == 0) {
          cur = node.child[c0];
          continue;
        }
        if (kAnyHit && !nearest_first) {
          // The last one is visited next, the others pushed in the node's order.
          PTLAB_DCHECK(sp + std::popcount(bits) <= kStackSize);
          stack[sp++] = {node.child[c0], 0.0f};
          PrefetchChild(bvh, node.child[c0]);
          for (; (bits & (bits - 1)) != 0; bits &= bits - 1) {
            const Bvh8Ref ref = node.child[std::countr_zero(bits)];
            PrefetchChild(bvh, ref);
            stack[sp++] = {ref, 0.0f};
          }
          cur = node.child[std::countr_zero(bits)];
          continue;
        }
        const int c1 = std::countr_zero(bits);
        bits &= bits - 1;
        if (bits == 0) {
          // Two children (the common case): the farther one is pushed, the nearer visited.
          // Equal entries keep the insertion sort's order below (the later child is nearer).
          const bool first_near = dist[c0] < dist[c1];
          const int near = first_near ? c0 : c1, far = first_near ? c1 : c0;
          const Entry e{node.child[far], dist[far]};
          PrefetchChild(bvh, e.ref);
          PTLAB_DCHECK(sp < kStackSize);
          stack[sp++] = e;
          cur = node.child[near];
          continue;
        }
        if constexpr (kAnyHit) {
          // Three or more: the nearest next, the others pushed in the node's order (a full
          // sort measured 2-4 % slower on the shadow rays of table, veach and terrain).
          bits |= (1u << c0) | (1u << c1);
          PTLAB_DCHECK(sp + std::popcount(bits) - 1 <= kStackSize);
          int best_c = c0;
          for (uint32_t b = bits & (bits - 1); b != 0; b &= b - 1) {
            const int c = std::countr_zero(b);
            if (dist[c] < dist[best_c]) best_c = c;
          }
          bits &= ~(1u << best_c);
          for (; bits != 0; bits &= bits - 1) {
            const Bvh8Ref ref = node.child[std::countr_zero(bits)];
            PrefetchChild(bvh, ref);
            stack[sp++] = {ref, 0.0f};
          }
          cur = node.child[best_c];
          continue;
        }
        // Three or more: nearest child next, the others pushed farthest first.
        Entry hit[8];
        hit[0] = {node.child[c0], dist[c0]};
        int n = 1;
        for (bits |= 1u << c1; bits != 0; bits &= bits - 1) {
          const int c = std::countr_zero(bits);
          const Entry e{node.child[c], dist[c]};
          int k = n++;
          for (; k > 0 && hit[k - 1].t_entry < e.t_entry; --k) hit[k] = hit[k - 1];
          hit[k] = e;
        }
        PTLAB_DCHECK(sp + n - 1 <= kStackSize);
        for (int k = 0; k < n - 1; ++k) {
          PrefetchChild(bvh, hit[k].ref);
          stack[sp++] = hit[k];
        }
        cur = hit[n - 1].ref;
        continue;
      }
    } else if (LeafSingle<kAnyHit>(d, bvh, cur, r.k, rv, 0, &best)) {
      any = true;
      break;
    }
    // Pop the next subtree that may still hold a hit at or before the closest one.
    bool popped = false;
    while (sp != 0) {
      const Entry& e = stack[--sp];
      if (kAnyHit || e.t_entry <= best.t * kRobustFarScale) {
        cur = e.ref;
        popped = true;
        break;
      }
    }
    if (!popped) break;
  }
  if constexpr (!kAnyHit) *best_io = best;
  return any;
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TRAVERSE8_SINGLE_INL_H_ toggle
