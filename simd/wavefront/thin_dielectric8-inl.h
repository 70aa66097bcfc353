// Per-target SIMD twin of engine/bsdf/thin_dielectric.h (Mitsuba `thindielectric`), included by
// bsdf8-inl.h. Oracle: ThinDielectricSample. IEEE operations only, in the oracle's order:
// bit-identical (wi, weight, pdf).

#if defined(PTLAB_SIMD_THIN_DIELECTRIC8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_THIN_DIELECTRIC8_INL_H_
#undef PTLAB_SIMD_THIN_DIELECTRIC8_INL_H_
#else
#define PTLAB_SIMD_THIN_DIELECTRIC8_INL_H_
#endif

#include "engine/scene/thin_dielectric_table.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

/// ThinDielectricSample for rows of ThinDielectricTable; Eval and Pdf are 0.
inline HWY_NOINLINE void ShadeThinDielectric(const ThinDielectricTable& t, const ShadeIo& io,
                                             size_t n, bool eval, bool sample) {
  ForEachBlock(io, n, [&t, eval, sample](const ShadeIo& b, size_t i) HWY_ATTR {
    const D8 d;
    const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    if (eval) StoreEval(d, b, i, zero, zero, zero, zero);
    if (!sample) return;
    const V8 ox = In(d, b, kWoX, i), oy = In(d, b, kWoY, i), oz = In(d, b, kWoZ, i);
    V8 cos_t;
    const V8 r1 = FresnelDielectric(d, ClampCos(d, oz), Gather(d, t.eta, b.index, i), &cos_t);
    const V8 r = hn::Div(hn::Mul(hn::Set(d, 2.0f), r1), hn::Add(one, r1));
    const M8 reflect = hn::Lt(In(d, b, kULobe, i), r);
    const V8 iz = hn::IfThenElse(reflect, oz, hn::Neg(oz));
    const V8 pdf = hn::IfThenElse(reflect, r, hn::Sub(one, r));
    const V8 wr = hn::IfThenElse(reflect, Gather(d, t.reflectance_r, b.index, i),
                                 Gather(d, t.transmittance_r, b.index, i));
    const V8 wg = hn::IfThenElse(reflect, Gather(d, t.reflectance_g, b.index, i),
                                 Gather(d, t.transmittance_g, b.index, i));
    const V8 wb = hn::IfThenElse(reflect, Gather(d, t.reflectance_b, b.index, i),
                                 Gather(d, t.transmittance_b, b.index, i));
    StoreSample(d, b, i, hn::Gt(pdf, zero), hn::Neg(ox), hn::Neg(oy), iz, wr, wg, wb, pdf, one);
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_THIN_DIELECTRIC8_INL_H_
