// Per-target 8-wide twin of engine/bsdf/diffuse.h (textured albedo included).
// Part of simd/wavefront/bsdf8-inl.h: included there, it uses that file's block driver and helpers.

#if defined(PTLAB_SIMD_DIFFUSE8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_DIFFUSE8_INL_H_
#undef PTLAB_SIMD_DIFFUSE8_INL_H_
#else
#define PTLAB_SIMD_DIFFUSE8_INL_H_
#endif

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

inline HWY_NOINLINE void ShadeDiffuse(const DiffuseTable& t, const ShadeInputs::Textures& tex,
                                      const ShadeIo& io, size_t n, bool eval, bool sample) {
  const bool textured = tex.textures != nullptr && t.textured();
  ForEachBlock(io, n, [&t, &tex, textured, eval, sample](const ShadeIo& b, size_t i) HWY_ATTR {
    const D8 d;
    const V8 zero = hn::Zero(d), inv_pi = hn::Set(d, kInvPi);
    V8 ar = Gather(d, t.albedo_r, b.index, i), ag = Gather(d, t.albedo_g, b.index, i),
       ab = Gather(d, t.albedo_b, b.index, i);
    if (textured) TexturedColor8(d, tex, t.albedo_texture, b, i, &ar, &ag, &ab);
    const V8 oz = In(d, b, kWoZ, i);
    if (eval) {
      const V8 lz = In(d, b, kWlZ, i);
      const M8 both = hn::And(hn::Gt(oz, zero), hn::Gt(lz, zero));
      StoreEval(d, b, i, hn::IfThenElseZero(both, hn::Mul(ar, inv_pi)),
                hn::IfThenElseZero(both, hn::Mul(ag, inv_pi)),
                hn::IfThenElseZero(both, hn::Mul(ab, inv_pi)), CosinePdf(d, oz, lz));
    }
    if (!sample) return;
    const V8 ux = In(d, b, kUX, i), uy = In(d, b, kUY, i);
    V8 ix, iy, iz;
    SampleCosineHemisphere(d, ux, uy, &ix, &iy, &iz);
    const V8 pdf = CosinePdf(d, oz, iz);
    StoreSample(d, b, i, hn::Gt(pdf, zero), ix, iy, iz, ar, ag, ab, pdf, hn::Set(d, 1.0f));
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_DIFFUSE8_INL_H_ toggle
