// Per-target 8-wide twin of engine/bsdf/rough_plastic.h (Nori `microfacet`, Beckmann plastic).
// Part of simd/wavefront/bsdf8-inl.h: included there, it uses that file's block driver and helpers.

#if defined(PTLAB_SIMD_ROUGH_PLASTIC8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_ROUGH_PLASTIC8_INL_H_
#undef PTLAB_SIMD_ROUGH_PLASTIC8_INL_H_
#else
#define PTLAB_SIMD_ROUGH_PLASTIC8_INL_H_
#endif

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

/// Rough plastic parameters of one block, gathered from RoughPlasticTable
/// (MakeRoughPlasticParams; lanes [0, Lanes(d))).
struct RoughPlasticLanes {
  HWY_ALIGN float alpha[8], eta[8], kd_r[8], kd_g[8], kd_b[8], ks[8];
};

/// RoughPlasticEval and (returned) RoughPlasticPdf (engine/bsdf/rough_plastic.h:
/// RoughPlasticEvalPdf), the Beckmann D of h = wo + wi computed once for both.
HWY_INLINE V8 RoughPlasticEvalPdf(D8 d, const RoughPlasticLanes& p, V8 ox, V8 oy, V8 oz, V8 ix,
                                  V8 iy, V8 iz, V8* fr, V8* fg, V8* fb) {
  const V8 alpha = hn::Load(d, p.alpha), eta = hn::Load(d, p.eta), kd_r = hn::Load(d, p.kd_r),
           kd_g = hn::Load(d, p.kd_g), kd_b = hn::Load(d, p.kd_b), ks = hn::Load(d, p.ks);
  const V8 zero = hn::Zero(d), inv_pi = hn::Set(d, kInvPi);
  const V8 hx = hn::Add(ox, ix), hy = hn::Add(oy, iy), hz = hn::Add(oz, iz);
  const V8 dv = BeckmannD(d, alpha, hx, hy, hz);
  // RoughPlasticPdf: ks BeckmannReflectionPdf + (1 − ks) cos θi / π.
  V8 spec_pdf;
  BeckmannEvalPdfOfD(d, dv, ox, oy, oz, iz, hx, hy, hz, &spec_pdf);
  const V8 pdf =
      hn::Add(hn::Mul(ks, spec_pdf), hn::Mul(hn::Sub(hn::Set(d, 1.0f), ks), hn::Mul(iz, inv_pi)));
  const V8 n2 = hn::Add(hn::Add(hn::Mul(hx, hx), hn::Mul(hy, hy)), hn::Mul(hz, hz));
  V8 cos_t;
  const V8 fres = FresnelDielectric(d, hn::Mul(hn::Set(d, 0.5f), hn::Sqrt(n2)), eta, &cos_t);
  const V8 g =
      hn::Mul(BeckmannG1OverCos(d, alpha, ox, oy, oz), BeckmannG1OverCos(d, alpha, ix, iy, iz));
  V8 spec = hn::Mul(hn::Mul(ks, fres), hn::Mul(hn::Mul(hn::Set(d, 0.25f), dv), g));
  const M8 spec_ok = hn::And(hn::And(hn::Gt(dv, zero), hn::Gt(ks, zero)), hn::IsFinite(spec));
  spec = hn::IfThenElseZero(spec_ok, spec);
  const M8 both = hn::And(hn::Gt(oz, zero), hn::Gt(iz, zero));
  *fr = hn::IfThenElseZero(both, hn::Add(hn::Mul(kd_r, inv_pi), spec));
  *fg = hn::IfThenElseZero(both, hn::Add(hn::Mul(kd_g, inv_pi), spec));
  *fb = hn::IfThenElseZero(both, hn::Add(hn::Mul(kd_b, inv_pi), spec));
  return hn::IfThenElseZero(both, pdf);
}

/// RoughPlasticEval / RoughPlasticPdf / RoughPlasticSample (engine/bsdf/rough_plastic.h).
inline HWY_NOINLINE void ShadeRoughPlastic(const RoughPlasticTable& t, const ShadeIo& io, size_t n,
                                           bool eval, bool sample) {
  ForEachBlock(io, n, [&t, eval, sample](const ShadeIo& b, size_t i) HWY_ATTR {
    const D8 d;
    const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    const V8 kd_r = Gather(d, t.kd_r, b.index, i), kd_g = Gather(d, t.kd_g, b.index, i),
             kd_b = Gather(d, t.kd_b, b.index, i);
    const V8 max_kd = hn::Max(kd_r, hn::Max(kd_g, kd_b));
    const V8 alpha = ClampAlpha(d, Gather(d, t.alpha, b.index, i));
    const V8 ks = hn::Min(hn::Max(hn::Sub(one, max_kd), zero), one);
    RoughPlasticLanes p;
    hn::Store(alpha, d, p.alpha), hn::Store(ks, d, p.ks);
    hn::Store(hn::Div(Gather(d, t.int_ior, b.index, i), Gather(d, t.ext_ior, b.index, i)), d,
              p.eta);
    hn::Store(kd_r, d, p.kd_r), hn::Store(kd_g, d, p.kd_g), hn::Store(kd_b, d, p.kd_b);
    const V8 ox = In(d, b, kWoX, i), oy = In(d, b, kWoY, i), oz = In(d, b, kWoZ, i);
    if (eval) {
      const V8 lx = In(d, b, kWlX, i), ly = In(d, b, kWlY, i), lz = In(d, b, kWlZ, i);
      V8 fr, fg, fb;
      const V8 pdf_l = RoughPlasticEvalPdf(d, p, ox, oy, oz, lx, ly, lz, &fr, &fg, &fb);
      StoreEval(d, b, i, fr, fg, fb, pdf_l);
    }
    if (!sample) return;
    const V8 u_lobe = In(d, b, kULobe, i), ux = In(d, b, kUX, i), uy = In(d, b, kUY, i);
    // Both candidate directions, unless every lane picked the same lobe.
    const M8 spec = hn::Lt(u_lobe, ks);
    V8 ix = zero, iy = zero, iz = zero;
    if (!hn::AllFalse(d, spec)) {
      V8 hx, hy, hz;
      SampleBeckmannNormal(d, alpha, ux, uy, &hx, &hy, &hz);
      Reflect(d, ox, oy, oz, hx, hy, hz, &ix, &iy, &iz);
    }
    if (!hn::AllTrue(d, spec)) {
      V8 cx, cy, cz;
      SampleCosineHemisphere(d, ux, uy, &cx, &cy, &cz);
      ix = hn::IfThenElse(spec, ix, cx), iy = hn::IfThenElse(spec, iy, cy);
      iz = hn::IfThenElse(spec, iz, cz);
    }
    V8 fr, fg, fb;
    const V8 pdf = RoughPlasticEvalPdf(d, p, ox, oy, oz, ix, iy, iz, &fr, &fg, &fb);
    const V8 cos_over_pdf = hn::Div(iz, pdf);
    const V8 wr = hn::Mul(fr, cos_over_pdf), wg = hn::Mul(fg, cos_over_pdf),
             wb = hn::Mul(fb, cos_over_pdf);
    const M8 ok =
        hn::And(hn::And(hn::Gt(oz, zero), hn::Gt(iz, zero)),
                hn::And(hn::And(hn::Gt(pdf, zero), hn::IsFinite(pdf)), AllFinite3(d, wr, wg, wb)));
    StoreSample(d, b, i, ok, ix, iy, iz, wr, wg, wb, pdf, one);
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_ROUGH_PLASTIC8_INL_H_ toggle
