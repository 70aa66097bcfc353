// Highway kernels of simd/traverse8: slab tests, the vector watertight test, BVH8 traversal.
// Re-included once per target by simd/traverse8.cpp (hwy/foreach_target.h); no dispatch here.

#if defined(PTLAB_SIMD_TRAVERSE8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TRAVERSE8_INL_H_
#undef PTLAB_SIMD_TRAVERSE8_INL_H_
#else
#define PTLAB_SIMD_TRAVERSE8_INL_H_
#endif

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "engine/bvh/sdf_grid_intersect.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/bvh/watertight_triangle.h"
#include "engine/core/check.h"
#include "hwy/cache_control.h"
#include "hwy/highway.h"
#include "simd/bvh8.h"
#include "simd/packet8.h"
#include "simd/traverse8.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DF = hn::CappedTag<float, 8>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using MF = hn::Mask<DF>;

// Must equal kRobustFarScale of engine/bvh/intersect1.cpp (pbrt-v3 §3.9.2): 1 + 2 gamma(3).
constexpr float kMachineEpsilon = std::numeric_limits<float>::epsilon() * 0.5f;
constexpr float kGamma3 = (3 * kMachineEpsilon) / (1.0f - 3 * kMachineEpsilon);
constexpr float kRobustFarScale = 1.0f + 2.0f * kGamma3;
constexpr float kInf = std::numeric_limits<float>::infinity();

// Float offsets of the six plane columns inside a Bvh8Node.
constexpr uint32_t kLoX = 0, kLoY = 8, kLoZ = 16, kHiX = 24, kHiY = 32, kHiZ = 40;

// Worst case of either traversal stack: a node pushes at most 7 children beyond the one it
// descends into, along a path of fewer than kBvhMaxDepth nodes.
constexpr int kStackSize = 8 * kBvhMaxDepth + 8;

HWY_INLINE uint32_t MaskBits(DF d, MF m) {
  uint8_t bits[8] = {};
  hn::StoreMaskBits(d, m, bits);
  return bits[0];
}

HWY_INLINE MF MaskFromBits(DF d, uint32_t bits) {
  const uint8_t b[8] = {static_cast<uint8_t>(bits), 0, 0, 0, 0, 0, 0, 0};
  return hn::LoadMaskBits(d, b);
}

// The per-ray constants of the watertight test, one lane per ray of a packet (a lone ray
// fills lane 0 only); packet kernels load them as vectors, a single ray's tests broadcast its
// lane (a packet lane that traverses alone reads its own lane of the packet's).
struct WatertightLanes {
  alignas(32) float ox[8], oy[8], oz[8];  // origin permuted to the lane's (kx, ky, kz)
  alignas(32) float sx[8], sy[8], sz[8];  // shear constants
  alignas(32) float t_min[8], t_max[8];
};

// 2-D edge function px * qy - py * qx, lane-wise. WatertightEdgeFunction (engine/bvh/
// watertight_triangle.h) orders the endpoints canonically and negates so that FMA fusion
// cannot break watertightness; without fusion (this file is compiled with contraction off,
// like the oracle) its result equals this plain formula up to the sign of a zero, because
// the two rounded products commute and round-to-nearest is symmetric. A zero sends all three
// edge functions to the double-precision fallback, which recomputes them from the sheared
// coordinates, so the sign of a zero never reaches a decision and the results stay
// bit-identical at a third of the cost.
HWY_INLINE VF EdgeFunction(VF px, VF py, VF qx, VF qy) {
  return hn::Sub(hn::Mul(px, qy), hn::Mul(py, qx));
}

// The paper's double-precision fallback for the lanes in `on_edge`, one lane at a time with
// the oracle's exact operations (the products of floats are exact in double).
HWY_NOINLINE void EdgeFallback(DF d, MF on_edge, VF a_x, VF a_y, VF b_x, VF b_y, VF c_x, VF c_y,
                               VF* u, VF* v, VF* w) {
  alignas(32) float ax[8], ay[8], bx[8], by[8], cx[8], cy[8], uu[8], vv[8], ww[8];
  hn::Store(a_x, d, ax), hn::Store(a_y, d, ay), hn::Store(b_x, d, bx), hn::Store(b_y, d, by);
  hn::Store(c_x, d, cx), hn::Store(c_y, d, cy);
  hn::Store(*u, d, uu), hn::Store(*v, d, vv), hn::Store(*w, d, ww);
  for (uint32_t bits = MaskBits(d, on_edge); bits != 0; bits &= bits - 1) {
    const int j = std::countr_zero(bits);
    const double cx_by = static_cast<double>(cx[j]) * static_cast<double>(by[j]);
    const double cy_bx = static_cast<double>(cy[j]) * static_cast<double>(bx[j]);
    uu[j] = static_cast<float>(cx_by - cy_bx);
    const double ax_cy = static_cast<double>(ax[j]) * static_cast<double>(cy[j]);
    const double ay_cx = static_cast<double>(ay[j]) * static_cast<double>(cx[j]);
    vv[j] = static_cast<float>(ax_cy - ay_cx);
    const double bx_ay = static_cast<double>(bx[j]) * static_cast<double>(ay[j]);
    const double by_ax = static_cast<double>(by[j]) * static_cast<double>(ax[j]);
    ww[j] = static_cast<float>(bx_ay - by_ax);
  }
  *u = hn::Load(d, uu), *v = hn::Load(d, vv), *w = hn::Load(d, ww);
}

// One ray constant for a vector of tests: lanes [i, i + Lanes(d)) of a packet's column, or
// (kOneRay) the single ray's value in lane i, broadcast.
template <bool kOneRay>
HWY_INLINE VF RayConstant(DF d, const float* column, size_t i) {
  if constexpr (kOneRay) return hn::Set(d, column[i]);
  return hn::Load(d, column + i);
}

// IntersectTriangleWatertightPermuted, lane-wise: the same float operations in the same
// order (the including .cpp disables FMA contraction), so every lane's decision and t, b1, b2
// equal the scalar test's bit for bit. Vertices are permuted to (kx, ky, kz) already. Returns
// the lanes of `valid` that hit; *t, *b1, *b2 are meaningful in those lanes only. The rays
// are lanes [i, i + Lanes(d)) of `r`, or with kOneRay the one ray in lane i of `r` against
// a vector of triangles.
template <bool kOneRay = false>
HWY_INLINE MF WatertightTest(DF d, const WatertightLanes& r, size_t i, VF ax, VF ay, VF az, VF bx,
                             VF by, VF bz, VF cx, VF cy, VF cz, MF valid, VF* t_out, VF* b1_out,
                             VF* b2_out) {
  const VF ox = RayConstant<kOneRay>(d, r.ox, i), oy = RayConstant<kOneRay>(d, r.oy, i);
  const VF oz = RayConstant<kOneRay>(d, r.oz, i);
  const VF sx = RayConstant<kOneRay>(d, r.sx, i), sy = RayConstant<kOneRay>(d, r.sy, i);
  const VF a_kx = hn::Sub(ax, ox), a_ky = hn::Sub(ay, oy), a_kz = hn::Sub(az, oz);
  const VF b_kx = hn::Sub(bx, ox), b_ky = hn::Sub(by, oy), b_kz = hn::Sub(bz, oz);
  const VF c_kx = hn::Sub(cx, ox), c_ky = hn::Sub(cy, oy), c_kz = hn::Sub(cz, oz);
  const VF a_x = hn::Sub(a_kx, hn::Mul(sx, a_kz)), a_y = hn::Sub(a_ky, hn::Mul(sy, a_kz));
  const VF b_x = hn::Sub(b_kx, hn::Mul(sx, b_kz)), b_y = hn::Sub(b_ky, hn::Mul(sy, b_kz));
  const VF c_x = hn::Sub(c_kx, hn::Mul(sx, c_kz)), c_y = hn::Sub(c_ky, hn::Mul(sy, c_kz));
  VF u = EdgeFunction(c_x, c_y, b_x, b_y);
  VF v = EdgeFunction(a_x, a_y, c_x, c_y);
  VF w = EdgeFunction(b_x, b_y, a_x, a_y);
  const VF zero = hn::Zero(d);
  // Mixed signs (some < 0 and some > 0): min < 0 and max > 0. For finite u, v, w this is
  // the oracle's test; a NaN among them makes det NaN, which every later test rejects on
  // both paths, so the final answer is the same either way.
  const auto mixed = [&] {
    return hn::And(hn::Lt(hn::Min(hn::Min(u, v), w), zero),
                   hn::Gt(hn::Max(hn::Max(u, v), w), zero));
  };
  MF ok = hn::AndNot(mixed(), valid);
  // Most tests end here, before the zero check: the fallback keeps every non-zero value's
  // sign (a float difference of rounded products is non-zero only with the exact sign, which
  // the exact double products keep), so a lane with mixed non-zero signs misses either way,
  // and with a NaN the min/max above see mixed signs only between two non-NaN values.
  if (hn::AllFalse(d, ok)) return ok;
  const MF on_edge = hn::And(ok, hn::Or(hn::Or(hn::Eq(u, zero), hn::Eq(v, zero)), hn::Eq(w, zero)));
  if (HWY_UNLIKELY(!hn::AllFalse(d, on_edge))) {
    EdgeFallback(d, on_edge, a_x, a_y, b_x, b_y, c_x, c_y, &u, &v, &w);
    ok = hn::AndNot(mixed(), ok);
  }
  const VF det = hn::Add(hn::Add(u, v), w);
  ok = hn::AndNot(hn::Eq(det, zero), ok);
  if (hn::AllFalse(d, ok)) return ok;
  const VF sz = RayConstant<kOneRay>(d, r.sz, i);
  const VF s_az = hn::Mul(sz, a_kz), s_bz = hn::Mul(sz, b_kz), s_cz = hn::Mul(sz, c_kz);
  const VF t_scaled = hn::Add(hn::Add(hn::Mul(u, s_az), hn::Mul(v, s_bz)), hn::Mul(w, s_cz));
  const VF abs_det = hn::Abs(det);
  const VF signed_t = hn::IfThenElse(hn::Lt(det, zero), hn::Neg(t_scaled), t_scaled);
  const VF t_min = RayConstant<kOneRay>(d, r.t_min, i);
  const VF t_max = RayConstant<kOneRay>(d, r.t_max, i);
  ok = hn::And(ok, hn::And(hn::Gt(signed_t, hn::Mul(t_min, abs_det)),
                           hn::Lt(signed_t, hn::Mul(t_max, abs_det))));
  if (hn::AllFalse(d, ok)) return ok;
  const VF rcp_det = hn::Div(hn::Set(d, 1.0f), det);
  const VF t = hn::Mul(t_scaled, rcp_det);
  ok = hn::And(ok, hn::And(hn::Gt(t, t_min), hn::Lt(t, t_max)));
  *t_out = t;
  *b1_out = hn::Mul(v, rcp_det);
  *b2_out = hn::Mul(w, rcp_det);
  return ok;
}

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

// Out of line, so that the single-ray loop is compiled as tightly as simd::Intersect1 and not
// inside the much larger packet function (measured: ~15% faster on incoherent packets). The
// loop over the lanes is inside: one call and one stack frame for the lanes of a subtree.
template <bool kAnyHit>
HWY_NOINLINE uint32_t TraverseLanesAlone(const Bvh8& bvh, Bvh8Ref ref, PacketState* s, uint32_t m) {
  uint32_t hit_lanes = 0;
  for (; m != 0; m &= m - 1) {
    const int j = std::countr_zero(m);
    LaneBest best{s->best_t[j], static_cast<uint32_t>(s->best_prim[j]), s->best_b1[j],
                  s->best_b2[j]};
    if (TraverseSingle<kAnyHit>(bvh, ref, LaneSingleRay(*s, j), s->wt, static_cast<size_t>(j),
                                &best)) {
      hit_lanes |= LaneBit(j);
    }
    if constexpr (!kAnyHit) {
      s->best_t[j] = best.t, s->best_prim[j] = static_cast<int32_t>(best.prim);
      s->best_b1[j] = best.b1, s->best_b2[j] = best.b2;
    }
  }
  return hit_lanes;
}

// Each lane of m traverses the subtree `ref` alone. Returns the lanes that hit (any hit).
template <bool kAnyHit>
HWY_INLINE uint32_t SingleRayLanes(const Bvh8& bvh, Bvh8Ref ref, PacketState* s, uint32_t m) {
  // Any hit: a leaf needs none of the traversal's setup, each lane tests it from its lane of
  // the packet. Measured (Occluded8, same run): shadow rays table +7 %, terrain +3 %,
  // bounce rays terrain +7 %. Closest hit lost 3 % on camera rays that way (table, terrain),
  // so it keeps the traversal. In the renders, of the lanes that go single, those at a leaf
  // are any hit: table 32 %, veach 6 %; closest hit: table 44 %, veach 66 %.
  if (kAnyHit && IsLeaf(ref)) return LeafLanes<kAnyHit>(DF(), bvh, ref, s, m);
  return TraverseLanesAlone<kAnyHit>(bvh, ref, s, m);
}

// Largest closest-hit distance among the lanes of m (the frustum's far end).
HWY_INLINE float MaxBestT(DF d, const PacketState& s, uint32_t m) {
  const size_t lanes = hn::Lanes(d);
  const uint32_t half_mask = (1u << lanes) - 1;
  float t = -kInf;
  for (size_t i = 0; i < 8; i += lanes) {
    const uint32_t half = (m >> i) & half_mask;
    if (half == 0) continue;
    const float b = ReduceLive<true>(d, hn::Load(d, s.best_t + i), MaskFromBits(d, half));
    t = b > t ? b : t;
  }
  return t;
}

// Any hit: the lanes of each leaf child of `node` in `candidates` (cbits[c]) that are not
// `done` yet test it now; the leaf children's cbits are cleared, and the lanes that hit are
// cleared from the inner children's. Returns the lanes that hit.
HWY_INLINE uint32_t PacketLeafChildren(DF d, const Bvh8& bvh, const Bvh8Node& node, PacketState* s,
                                       uint32_t candidates, uint32_t done,
                                       uint32_t single_ray_lanes, const Traverse8Options& options,
                                       uint32_t* cbits) {
  uint32_t hit_lanes = 0;
  for (uint32_t todo = candidates & node.leaf_children; todo != 0; todo &= todo - 1) {
    const int c = std::countr_zero(todo);
    const uint32_t m = cbits[c] & ~(done | hit_lanes);
    cbits[c] = 0;
    if (m == 0) continue;
    hit_lanes |= static_cast<uint32_t>(std::popcount(m)) <= single_ray_lanes
                     ? SingleRayLanes<true>(bvh, node.child[c], s, m)
                     : LeafPacket<true>(d, bvh, node.child[c], s, m, options);
  }
  if (hit_lanes != 0) {
    for (uint32_t todo = candidates; todo != 0; todo &= todo - 1) {
      cbits[std::countr_zero(todo)] &= ~hit_lanes;
    }
  }
  return hit_lanes;
}

// Packet traversal with the hybrid switch to single rays. Closest hit: fills s->best_*;
// any hit: returns the lanes that hit.
// Out of line: its 33 KB stack frame is only set up for packets that traverse as packets.
template <bool kAnyHit>
HWY_NOINLINE uint32_t TraversePacket(const Bvh8& bvh, PacketState* s, uint32_t live,
                                     const Traverse8Options& options) {
  const DF d;
  struct alignas(32) Entry {
    float t_entry[8];
    Bvh8Ref ref;
    uint32_t mask;
  };
  Entry stack[kStackSize];
  int sp = 0;
  uint32_t done = 0;  // any hit: lanes already occluded
  const uint32_t single_ray_lanes =
      s->shared_origin && options.shared_origin_single_ray_lanes >= 0
          ? static_cast<uint32_t>(options.shared_origin_single_ray_lanes)
          : options.single_ray_lanes;
  // The subtree being visited and its lanes. The nearest child hit is visited next without a
  // round trip through the stack: its lanes were just tested against their closest hits.
  Bvh8Ref ref = 0;
  uint32_t m = live;
  for (;;) {
    bool descend = false;
    if (static_cast<uint32_t>(std::popcount(m)) <= single_ray_lanes) {
      // Too few rays left to fill a vector: each finishes this subtree alone.
      done |= SingleRayLanes<kAnyHit>(bvh, ref, s, m);
      if (kAnyHit && done == live) return done;
    } else if (IsLeaf(ref)) {
      done |= LeafPacket<kAnyHit>(d, bvh, ref, s, m, options);
      if (kAnyHit && done == live) return done;
    } else {
      const Bvh8Node& node = bvh.Node(ref);
      uint32_t candidates = (1u << node.num_children) - 1;
      if (s->frustum) {
        candidates = FrustumChildren(d, *s, node, MaxBestT(d, *s, m));
      }
      if (candidates != 0) {
        uint32_t cbits[8];
        alignas(32) float t_near[8][8];
        float key[8];
        PacketChildren<kAnyHit>(d, *s, node, m, candidates, cbits, t_near, key);
        // Packets from one origin (camera rays) test their leaf children at once under any
        // hit, as TraverseSingle does, in trees below options.leaves_first_max_triangles.
        // Other packets were slower that way (veach bounce rays 42 -> 30 M rays/s, table
        // shadow rays -6 %).
        if (kAnyHit && s->shared_origin &&
            bvh.num_triangles < options.leaves_first_max_triangles) {
          done |= PacketLeafChildren(d, bvh, node, s, candidates, done, single_ray_lanes, options,
                                     cbits);
          if (done == live) return done;
        }
        // The children hit by any lane, farthest (by the key) first; any hit keeps the
        // children's order.
        int order[8], n = 0;
        for (uint32_t todo = candidates; todo != 0; todo &= todo - 1) {
          const int c = std::countr_zero(todo);
          if (cbits[c] == 0) continue;
          int k = n++;
          if constexpr (!kAnyHit)
            for (; k > 0 && key[order[k - 1]] < key[c]; --k) order[k] = order[k - 1];
          order[k] = c;
        }
        if (n > 0) {
          PTLAB_DCHECK(sp + n - 1 <= kStackSize);
          for (int k = 0; k < n - 1; ++k) {
            const int c = order[k];
            Entry& out = stack[sp++];
            out.ref = node.child[c];
            out.mask = cbits[c];
            // Large scenes wait on memory: start loading the subtrees visited later.
            PrefetchChild(bvh, out.ref);
            if constexpr (!kAnyHit)
              for (int j = 0; j < 8; ++j) out.t_entry[j] = t_near[c][j];
          }
          ref = node.child[order[n - 1]];
          m = cbits[order[n - 1]];
          descend = true;
        }
      }
    }
    if (descend) continue;
    // Pop the next subtree that still has lanes whose closest hit may lie inside it.
    for (;;) {
      if (sp == 0) return done;
      const Entry& e = stack[--sp];
      m = kAnyHit ? (e.mask & ~done) : LanesBeforeClosest(d, *s, e.t_entry, e.mask);
      if (m != 0) {
        ref = e.ref;
        break;
      }
    }
  }
  return done;
}

// An incoherent packet (lanes in several direction octants) in a large BVH would test every
// child box for lanes that mostly miss it, so each lane traverses alone from the root; a
// coherent one, or any in a small BVH, traverses as a packet (with the hybrid switch below
// single_ray_lanes).
template <bool kAnyHit>
HWY_INLINE uint32_t TraverseLanes(const Bvh8& bvh, PacketState* s, uint32_t live,
                                  const Traverse8Options& options) {
  if (options.octant_fallback && !s->coherent &&
      bvh.num_triangles >= options.octant_fallback_min_triangles) {
    return SingleRayLanes<kAnyHit>(bvh, 0, s, live);
  }
  return TraversePacket<kAnyHit>(bvh, s, live, options);
}

// ---------------------------------------------------------------------------------------------
// Spheres beside the BVH (a scene holds a handful): every sphere against every live lane.

// IntersectSphere1 (engine/bvh/sphere_intersect.h) on one vector of rays, operation for
// operation (contraction off: bit-identical), with c = SphereOriginC given per lane. Returns the
// lanes with a root in (t_min, t_max) and that root in *t.
HWY_INLINE MF IntersectSphereLanes(DF d, VF cx, VF cy, VF cz, VF r, VF c, VF ox, VF oy, VF oz,
                                   VF dx, VF dy, VF dz, VF t_min, VF t_max, VF* t) {
  const VF zero = hn::Zero(d);
  const VF fx = hn::Sub(ox, cx), fy = hn::Sub(oy, cy), fz = hn::Sub(oz, cz);
  const VF a = hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz));
  const VF b = hn::Add(hn::Add(hn::Mul(fx, dx), hn::Mul(fy, dy)), hn::Mul(fz, dz));
  const VF r2 = hn::Mul(r, r);
  const VF s = hn::Div(b, a);
  const VF vx = hn::Sub(fx, hn::Mul(s, dx)), vy = hn::Sub(fy, hn::Mul(s, dy)),
           vz = hn::Sub(fz, hn::Mul(s, dz));
  const VF disc = hn::Sub(r2, hn::Add(hn::Add(hn::Mul(vx, vx), hn::Mul(vy, vy)), hn::Mul(vz, vz)));
  const MF real = hn::Ge(disc, zero);
  // Lanes without real roots take the square root of 0 (no NaN); they are masked out below.
  const VF root = hn::Sqrt(hn::Mul(a, hn::IfThenElseZero(real, disc)));
  const VF q = hn::IfThenElse(hn::Lt(b, zero), hn::Sub(root, b), hn::Neg(hn::Add(b, root)));
  const VF q_a = hn::Div(q, a), c_q = hn::Div(c, q);
  const MF swap = hn::Gt(q_a, c_q);
  const VF t0 = hn::IfThenElse(swap, c_q, q_a), t1 = hn::IfThenElse(swap, q_a, c_q);
  const MF in0 = hn::And(hn::Gt(t0, t_min), hn::Lt(t0, t_max));
  const MF in1 = hn::And(hn::Gt(t1, t_min), hn::Lt(t1, t_max));
  *t = hn::IfThenElse(in0, t0, t1);
  return hn::And(real, hn::Or(in0, in1));
}

// Closest hit: the live lanes' best hits so far (triangles, or t_max) updated with the
// spheres', in row order as IntersectSpheres1 does (b1 = b2 = 0 for a sphere).
// Any hit: returns the lanes of `live` that meet a sphere before their t_max.
template <bool kAnyHit>
HWY_INLINE uint32_t SphereLanes(const Bvh8& bvh, const RayPacket8& rays, PacketState* s,
                                uint32_t live) {
  const DF d;
  const DI di;
  const size_t lanes = hn::Lanes(d);
  const uint32_t half_mask = (1u << lanes) - 1;
  const SphereTable& sp = bvh.spheres;
  uint32_t hit_lanes = 0;
  for (size_t i = 0; i < 8; i += lanes) {
    const uint32_t on_bits = (live >> i) & half_mask;
    if (on_bits == 0) continue;
    const MF on = MaskFromBits(d, on_bits);
    const VF one = hn::Set(d, 1.0f);
    // Dead lanes compute with o = 0, d = (1, 1, 1) (no NaN) and are masked out.
    const VF ox = hn::Load(d, s->o_x + i), oy = hn::Load(d, s->o_y + i),
             oz = hn::Load(d, s->o_z + i);
    const VF dx = hn::IfThenElse(on, hn::Load(d, rays.dir_x + i), one);
    const VF dy = hn::IfThenElse(on, hn::Load(d, rays.dir_y + i), one);
    const VF dz = hn::IfThenElse(on, hn::Load(d, rays.dir_z + i), one);
    const VF t_min = hn::Load(d, s->wt.t_min + i);
    VF best = kAnyHit ? hn::Load(d, s->wt.t_max + i) : hn::Load(d, s->best_t + i);
    VI prim = hn::Load(di, s->best_prim + i);
    MF any = hn::FirstN(d, 0);  // no lane
    for (uint32_t k = 0; k < sp.size(); ++k) {
      // c in double, lane by lane, with the oracle's own function.
      alignas(32) float c[8];
      for (size_t j = 0; j < lanes; ++j)
        c[j] = SphereOriginC(s->o_x[i + j], s->o_y[i + j], s->o_z[i + j], sp.center_x[k],
                             sp.center_y[k], sp.center_z[k], sp.radius[k]);
      VF t;
      const MF hit = hn::And(
          on, IntersectSphereLanes(d, hn::Set(d, sp.center_x[k]), hn::Set(d, sp.center_y[k]),
                                   hn::Set(d, sp.center_z[k]), hn::Set(d, sp.radius[k]),
                                   hn::Load(d, c), ox, oy, oz, dx, dy, dz, t_min, best, &t));
      any = hn::Or(any, hit);
      if (kAnyHit) continue;
      best = hn::IfThenElse(hit, t, best);
      prim = hn::IfThenElse(hn::RebindMask(di, hit),
                            hn::Set(di, static_cast<int32_t>(kSphereHitBit | k)), prim);
    }
    hit_lanes |= MaskBits(d, any) << i;
    if (kAnyHit) continue;
    hn::Store(best, d, s->best_t + i);
    hn::Store(prim, di, s->best_prim + i);
    hn::Store(hn::IfThenElseZero(hn::Not(any), hn::Load(d, s->best_b1 + i)), d, s->best_b1 + i);
    hn::Store(hn::IfThenElseZero(hn::Not(any), hn::Load(d, s->best_b2 + i)), d, s->best_b2 + i);
  }
  return hit_lanes;
}

// Sdfgrids beside the BVH: each live lane's ray through the oracle's own scalar code
// (IntersectSdfGrids1 / OccludedSdfGrids1, engine/bvh/sdf_grid_intersect.h), so the packet's
// hits are the oracle's bit for bit on every target. Closest hit: the lane's best so far
// (triangles, spheres) is the grid's t_max, b1 = b2 = 0 on a grid hit. Any hit: the lanes of
// `live` that meet a grid before their t_max. The cell walk branches per ray; a vector walk is
// not done (docs/sdfgrid.md).
template <bool kAnyHit>
HWY_INLINE uint32_t SdfGridLanes(const Bvh8& bvh, const RayPacket8& rays, PacketState* s,
                                 uint32_t live) {
  uint32_t hit_lanes = 0;
  for (uint32_t todo = live; todo != 0; todo &= todo - 1) {
    const int j = std::countr_zero(todo);
    Ray ray = GetLaneRay(rays, j);
    ray.t_min = s->wt.t_min[j];
    ray.t_max = s->wt.t_max[j];
    if (kAnyHit) {
      if (OccludedSdfGrids1(bvh.sdf_grids, ray)) hit_lanes |= 1u << j;
      continue;
    }
    float t = s->best_t[j];
    uint32_t prim = kNoHit;
    if (IntersectSdfGrids1(bvh.sdf_grids, ray, &t, &prim)) {
      s->best_t[j] = t;
      s->best_prim[j] = static_cast<int32_t>(prim);
      s->best_b1[j] = s->best_b2[j] = 0.0f;
      hit_lanes |= 1u << j;
    }
  }
  return hit_lanes;
}

// ---------------------------------------------------------------------------------------------
// Entry points (dispatched from simd/traverse8.cpp).

HWY_INLINE Mask8 Intersect8Kernel(const Bvh8& bvh, const RayPacket8& rays, Mask8 active,
                                  HitPacket8* hits, const Traverse8Options& options) {
  const bool spheres = bvh.spheres.size() != 0;
  const bool grids = bvh.sdf_grids.size() != 0;
  if (bvh.empty() && !spheres && !grids) return 0;
  PacketState s;
  const Mask8 live = SetupPacket(rays, active & kAllLanes, &s);
  if (live == 0) return 0;
  if (!bvh.empty()) TraverseLanes<false>(bvh, &s, live, options);
  if (spheres) SphereLanes<false>(bvh, rays, &s, live);
  if (grids) SdfGridLanes<false>(bvh, rays, &s, live);
  // The live lanes that hit, copied out with masked stores (lanes that miss keep what *hits
  // held): the lane-by-lane copy this replaces cost table's packet render 2 % (1.72 -> 1.68 s).
  const DF d;
  const DI di;
  const size_t lanes = hn::Lanes(d);
  const uint32_t half_mask = (1u << lanes) - 1;
  Mask8 result = 0;
  for (size_t i = 0; i < 8; i += lanes) {
    const VI prim = hn::Load(di, s.best_prim + i);
    const MF hit =
        hn::AndNot(hn::RebindMask(d, hn::Eq(prim, hn::Set(di, static_cast<int32_t>(kNoHit)))),
                   MaskFromBits(d, (live >> i) & half_mask));
    hn::BlendedStore(hn::Load(d, s.best_t + i), hit, d, hits->t + i);
    hn::BlendedStore(hn::Load(d, s.best_b1 + i), hit, d, hits->b1 + i);
    hn::BlendedStore(hn::Load(d, s.best_b2 + i), hit, d, hits->b2 + i);
    hn::BlendedStore(prim, hn::RebindMask(di, hit), di, reinterpret_cast<int32_t*>(hits->prim) + i);
    result |= MaskBits(d, hit) << i;
  }
  return result;
}

HWY_INLINE Mask8 Occluded8Kernel(const Bvh8& bvh, const RayPacket8& rays, Mask8 active,
                                 const Traverse8Options& options) {
  const bool spheres = bvh.spheres.size() != 0;
  const bool grids = bvh.sdf_grids.size() != 0;
  if (bvh.empty() && !spheres && !grids) return 0;
  PacketState s;
  const Mask8 live = SetupPacket(rays, active & kAllLanes, &s);
  if (live == 0) return 0;
  Mask8 done = bvh.empty() ? 0 : TraverseLanes<true>(bvh, &s, live, options);
  if (spheres && done != live) done |= SphereLanes<true>(bvh, rays, &s, live & ~done);
  if (grids && done != live) done |= SdfGridLanes<true>(bvh, rays, &s, live & ~done);
  return done;
}

// The single-ray kernels test the spheres with the oracle's own scalar code (bit-identical by
// construction); only the packet kernels need the vector twin.
HWY_INLINE bool Intersect1Kernel(const Bvh8& bvh, const Ray& ray, Hit* hit) {
  if (!(ray.t_min < ray.t_max)) return false;
  LaneBest best{ray.t_max, kNoHit, 0.0f, 0.0f};
  if (!bvh.empty()) {
    WatertightLanes rv;
    const SingleRay r = MakeSingleRay(ray.o, ray.d, ray.t_min, ray.t_max, &rv);
    TraverseSingle<false>(bvh, 0, r, rv, 0, &best);
  }
  if (IntersectSpheres1(bvh.spheres, ray, &best.t, &best.prim)) best.b1 = best.b2 = 0.0f;
  if (bvh.sdf_grids.size() != 0 && IntersectSdfGrids1(bvh.sdf_grids, ray, &best.t, &best.prim))
    best.b1 = best.b2 = 0.0f;
  if (best.prim == kNoHit) return false;
  hit->t = best.t;
  hit->b1 = best.b1;
  hit->b2 = best.b2;
  hit->prim = best.prim;
  return true;
}

HWY_INLINE bool Occluded1Kernel(const Bvh8& bvh, const Ray& ray) {
  if (!(ray.t_min < ray.t_max)) return false;
  if (!bvh.empty()) {
    LaneBest best{ray.t_max, kNoHit, 0.0f, 0.0f};
    WatertightLanes rv;
    const SingleRay r = MakeSingleRay(ray.o, ray.d, ray.t_min, ray.t_max, &rv);
    if (TraverseSingle<true>(bvh, 0, r, rv, 0, &best)) return true;
  }
  return OccludedSpheres1(bvh.spheres, ray) ||
         (bvh.sdf_grids.size() != 0 && OccludedSdfGrids1(bvh.sdf_grids, ray));
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TRAVERSE8_INL_H_ toggle
