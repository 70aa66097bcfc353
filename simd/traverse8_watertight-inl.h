// The vector watertight ray/triangle test of simd/traverse8 (the oracle's test, lane-wise).
// Part of simd/traverse8-inl.h: re-included once per target with it (hwy/foreach_target.h).

#if defined(PTLAB_SIMD_TRAVERSE8_WATERTIGHT_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TRAVERSE8_WATERTIGHT_INL_H_
#undef PTLAB_SIMD_TRAVERSE8_WATERTIGHT_INL_H_
#else
#define PTLAB_SIMD_TRAVERSE8_WATERTIGHT_INL_H_
#endif

#include "hwy/highway.h"
#include "simd/traverse8_common-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

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

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TRAVERSE8_WATERTIGHT_INL_H_ toggle
