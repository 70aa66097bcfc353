// Per-target helpers (re-included once per Highway target): the light-sampling densities the
// kernels share, in the scalar code's float operations and order, eight rows per vector.
// AreaToSolidAngle8 for simd/wavefront/area_light8 and simd/wavefront/emission8, MisWeight8 for simd/wavefront/area_request8 and
// simd/wavefront/emission8.

#if defined(PTLAB_SIMD_LIGHT_PDF8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_LIGHT_PDF8_INL_H_
#undef PTLAB_SIMD_LIGHT_PDF8_INL_H_
#else
#define PTLAB_SIMD_LIGHT_PDF8_INL_H_
#endif

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

/// AreaToSolidAngle(inv_area, p, n, ref) with (dx, dy, dz) = p - ref: the area density
/// inv_area turned into solid angle at ref, (inv_area · |d|²) / cos θ with cos θ = -n·d / |d|.
/// *counts: the lanes where it is defined (|d|² > 0 and the light faces ref); elsewhere the
/// returned value is meaningless and the caller's pdf is 0.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V AreaToSolidAngle8(D d, V inv_area, V dx, V dy, V dz, V nx, V ny, V nz,
                               hn::Mask<D>* counts) {
  const V zero = hn::Zero(d);
  const V dist2 = hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz));
  const V n_dot_d = hn::Add(hn::Add(hn::Mul(nx, dx), hn::Mul(ny, dy)), hn::Mul(nz, dz));
  const V cos_l = hn::Div(hn::Neg(n_dot_d), hn::Sqrt(dist2));
  *counts = hn::And(hn::Gt(dist2, zero), hn::Gt(cos_l, zero));
  return hn::Div(hn::Mul(inv_area, dist2), cos_l);
}

/// MisWeight(pdf_a, pdf_b, power): the power heuristic (squares first) or the balance heuristic
/// weight of technique a, 0 where both densities are 0.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V MisWeight8(D d, V pdf_a, V pdf_b, bool power) {
  if (power) pdf_a = hn::Mul(pdf_a, pdf_a), pdf_b = hn::Mul(pdf_b, pdf_b);
  const V sum = hn::Add(pdf_a, pdf_b);
  return hn::IfThenElseZero(hn::Gt(sum, hn::Zero(d)), hn::Div(pdf_a, sum));
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_LIGHT_PDF8_INL_H_
