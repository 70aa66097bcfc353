// Per-target 8-wide twin of engine/bsdf/dielectric.h.
// Part of simd/wavefront/bsdf8-inl.h: included there, it uses that file's block driver and helpers.

#if defined(PTLAB_SIMD_DIELECTRIC8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_DIELECTRIC8_INL_H_
#undef PTLAB_SIMD_DIELECTRIC8_INL_H_
#else
#define PTLAB_SIMD_DIELECTRIC8_INL_H_
#endif

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

/// DielectricSample (engine/bsdf/dielectric.h); Eval and Pdf are 0.
inline HWY_NOINLINE void ShadeDielectric(const DielectricTable& t, const ShadeIo& io, size_t n,
                                         bool eval, bool sample) {
  const bool has_flags = !t.flags.empty();
  ForEachBlock(io, n, [&t, eval, sample, has_flags](const ShadeIo& b, size_t i) HWY_ATTR {
    const D8 d;
    const hn::RebindToSigned<D8> di;
    const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    if (eval) StoreEval(d, b, i, zero, zero, zero, zero);
    if (!sample) return;
    const V8 ox = In(d, b, kWoX, i), oy = In(d, b, kWoY, i), oz = In(d, b, kWoZ, i),
             u_lobe = In(d, b, kULobe, i);
    const V8 eta =
        ClampRelIor(d, hn::Div(Gather(d, t.int_ior, b.index, i), Gather(d, t.ext_ior, b.index, i)));
    V8 cos_t;
    V8 f = FresnelDielectric(d, oz, eta, &cos_t);
    M8 scale = hn::FirstN(d, 0);
    M8 tir_only = hn::FirstN(d, 0);  // refraction-only lanes under total internal reflection
    if (has_flags) {
      HWY_ALIGN int32_t flags[8];
      for (size_t j = 0; j < hn::Lanes(d); ++j) flags[j] = t.flags[b.index[i + j]];
      const auto fl = hn::LoadU(di, flags);
      const M8 schlick = hn::RebindMask(d, hn::TestBit(fl, hn::Set(di, kDielectricSchlick)));
      scale = hn::RebindMask(d, hn::TestBit(fl, hn::Set(di, kDielectricScaleRadiance)));
      f = hn::IfThenElse(hn::And(schlick, hn::Lt(f, one)), FresnelSchlick(d, oz, eta), f);
      const M8 refract_only =
          hn::RebindMask(d, hn::TestBit(fl, hn::Set(di, kDielectricRefractOnly)));
      tir_only = hn::And(refract_only, hn::Ge(f, one));
      f = hn::IfThenElse(refract_only, zero, f);
    }
    const M8 reflect = hn::Lt(u_lobe, f);
    const M8 outside = hn::Gt(oz, zero);
    const V8 rel = hn::IfThenElse(outside, hn::Div(one, eta), eta);
    const V8 ix = hn::IfThenElse(reflect, hn::Neg(ox), hn::Mul(hn::Neg(ox), rel));
    const V8 iy = hn::IfThenElse(reflect, hn::Neg(oy), hn::Mul(hn::Neg(oy), rel));
    const V8 iz = hn::IfThenElse(reflect, oz, hn::IfThenElse(outside, hn::Neg(cos_t), cos_t));
    const V8 pdf = hn::IfThenElse(reflect, f, hn::Sub(one, f));
    const V8 eta_out = hn::IfThenElse(reflect, one, hn::Div(one, rel));
    const V8 w = hn::IfThenElse(hn::AndNot(reflect, scale), hn::Mul(rel, rel), one);
    // A smooth interface always scatters (only a huge non-unit wo can overflow).
    const M8 ok = hn::AndNot(tir_only, hn::And(hn::IsFinite(ix), hn::IsFinite(iy)));
    V8 wr = w, wg = w, wb = w;
    if (t.tinted()) {
      // CS184 glass colors: the reflectance tints reflection, the transmittance refraction.
      wr = hn::Mul(w, hn::IfThenElse(reflect, Gather(d, t.reflectance_r, b.index, i),
                                     Gather(d, t.transmittance_r, b.index, i)));
      wg = hn::Mul(w, hn::IfThenElse(reflect, Gather(d, t.reflectance_g, b.index, i),
                                     Gather(d, t.transmittance_g, b.index, i)));
      wb = hn::Mul(w, hn::IfThenElse(reflect, Gather(d, t.reflectance_b, b.index, i),
                                     Gather(d, t.transmittance_b, b.index, i)));
    }
    StoreSample(d, b, i, ok, ix, iy, iz, wr, wg, wb, pdf, eta_out);
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_DIELECTRIC8_INL_H_ toggle
