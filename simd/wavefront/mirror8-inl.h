// Per-target 8-wide twin of engine/bsdf/mirror.h.
// Part of simd/wavefront/bsdf8-inl.h: included there, it uses that file's block driver and helpers.

#if defined(PTLAB_SIMD_MIRROR8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_MIRROR8_INL_H_
#undef PTLAB_SIMD_MIRROR8_INL_H_
#else
#define PTLAB_SIMD_MIRROR8_INL_H_
#endif

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

/// MirrorSample (engine/bsdf/mirror.h); Eval and Pdf are 0.
inline HWY_NOINLINE void ShadeMirror(const MirrorTable& t, const ShadeIo& io, size_t n, bool eval,
                                     bool sample) {
  ForEachBlock(io, n, [&t, eval, sample](const ShadeIo& b, size_t i) HWY_ATTR {
    const D8 d;
    const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    if (eval) StoreEval(d, b, i, zero, zero, zero, zero);
    if (!sample) return;
    const V8 ox = In(d, b, kWoX, i), oy = In(d, b, kWoY, i), oz = In(d, b, kWoZ, i);
    V8 rr = Gather(d, t.reflectance_r, b.index, i), rg = Gather(d, t.reflectance_g, b.index, i),
       rb = Gather(d, t.reflectance_b, b.index, i);
    if (t.fresnel()) {  // matA: Mitsuba's smooth conductor (SmoothConductorSample)
      rr = hn::Mul(rr, FresnelConductor(d, oz, Gather(d, t.eta_r, b.index, i),
                                        Gather(d, t.k_r, b.index, i)));
      rg = hn::Mul(rg, FresnelConductor(d, oz, Gather(d, t.eta_g, b.index, i),
                                        Gather(d, t.k_g, b.index, i)));
      rb = hn::Mul(rb, FresnelConductor(d, oz, Gather(d, t.eta_b, b.index, i),
                                        Gather(d, t.k_b, b.index, i)));
    }
    StoreSample(d, b, i, hn::Gt(oz, zero), hn::Neg(ox), hn::Neg(oy), oz, rr, rg, rb, one, one);
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_MIRROR8_INL_H_ toggle
