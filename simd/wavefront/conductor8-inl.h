// Per-target 8-wide twin of engine/bsdf/conductor.h (the Beckmann rough conductor).
// Part of simd/wavefront/bsdf8-inl.h: included there, it uses that file's block driver and helpers.

#if defined(PTLAB_SIMD_CONDUCTOR8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_CONDUCTOR8_INL_H_
#undef PTLAB_SIMD_CONDUCTOR8_INL_H_
#else
#define PTLAB_SIMD_CONDUCTOR8_INL_H_
#endif

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

/// Conductor parameters of one block, gathered from ConductorTable (lanes [0, Lanes(d))).
struct ConductorLanes {
  HWY_ALIGN float alpha[8], eta_r[8], eta_g[8], eta_b[8], k_r[8], k_g[8], k_b[8];
};

/// ConductorEval (engine/bsdf/conductor.h) at (wo, wi) and (returned) ConductorPdf, the
/// Beckmann D of h = wo + wi computed once for both; the Fresnel factor is evaluated per
/// channel.
HWY_INLINE V8 ConductorEvalPdf(D8 d, const ConductorLanes& c, V8 ox, V8 oy, V8 oz, V8 ix, V8 iy,
                               V8 iz, V8* fr, V8* fg, V8* fb) {
  const V8 zero = hn::Zero(d), alpha = hn::Load(d, c.alpha);
  const V8 hx = hn::Add(ox, ix), hy = hn::Add(oy, iy), hz = hn::Add(oz, iz);
  const V8 dv = BeckmannD(d, alpha, hx, hy, hz);
  V8 pdf;
  BeckmannEvalPdfOfD(d, dv, ox, oy, oz, iz, hx, hy, hz, &pdf);
  const V8 n2 = hn::Add(hn::Add(hn::Mul(hx, hx), hn::Mul(hy, hy)), hn::Mul(hz, hz));
  const V8 wi_h = hn::Mul(hn::Set(d, 0.5f), hn::Sqrt(n2));
  const V8 g =
      hn::Mul(BeckmannG1OverCos(d, alpha, ox, oy, oz), BeckmannG1OverCos(d, alpha, ix, iy, iz));
  const V8 scale = hn::Mul(hn::Mul(hn::Set(d, 0.25f), dv), g);
  const V8 r = hn::Mul(FresnelConductor(d, wi_h, hn::Load(d, c.eta_r), hn::Load(d, c.k_r)), scale);
  const V8 gg = hn::Mul(FresnelConductor(d, wi_h, hn::Load(d, c.eta_g), hn::Load(d, c.k_g)), scale);
  const V8 bb = hn::Mul(FresnelConductor(d, wi_h, hn::Load(d, c.eta_b), hn::Load(d, c.k_b)), scale);
  const M8 ok = hn::And(hn::And(hn::Gt(oz, zero), hn::Gt(iz, zero)),
                        hn::And(hn::Gt(dv, zero), AllFinite3(d, r, gg, bb)));
  *fr = hn::IfThenElseZero(ok, r);
  *fg = hn::IfThenElseZero(ok, gg);
  *fb = hn::IfThenElseZero(ok, bb);
  return pdf;
}

/// ConductorEval / ConductorPdf / ConductorSample (engine/bsdf/conductor.h).
inline HWY_NOINLINE void ShadeConductor(const ConductorTable& t, const ShadeIo& io, size_t n,
                                        bool eval, bool sample) {
  ForEachBlock(io, n, [&t, eval, sample](const ShadeIo& b, size_t i) HWY_ATTR {
    const D8 d;
    const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    ConductorLanes c;
    hn::Store(ClampAlpha(d, Gather(d, t.alpha, b.index, i)), d, c.alpha);
    hn::Store(Gather(d, t.eta_r, b.index, i), d, c.eta_r);
    hn::Store(Gather(d, t.eta_g, b.index, i), d, c.eta_g);
    hn::Store(Gather(d, t.eta_b, b.index, i), d, c.eta_b);
    hn::Store(Gather(d, t.k_r, b.index, i), d, c.k_r);
    hn::Store(Gather(d, t.k_g, b.index, i), d, c.k_g);
    hn::Store(Gather(d, t.k_b, b.index, i), d, c.k_b);
    const V8 alpha = hn::Load(d, c.alpha);
    const V8 ox = In(d, b, kWoX, i), oy = In(d, b, kWoY, i), oz = In(d, b, kWoZ, i);
    if (eval) {
      const V8 lx = In(d, b, kWlX, i), ly = In(d, b, kWlY, i), lz = In(d, b, kWlZ, i);
      V8 fr, fg, fb;
      const V8 pdf_l = ConductorEvalPdf(d, c, ox, oy, oz, lx, ly, lz, &fr, &fg, &fb);
      StoreEval(d, b, i, fr, fg, fb, pdf_l);
    }
    if (!sample) return;
    const V8 ux = In(d, b, kUX, i), uy = In(d, b, kUY, i);
    V8 hx, hy, hz, ix, iy, iz, pdf;
    SampleBeckmannNormal(d, alpha, ux, uy, &hx, &hy, &hz);
    Reflect(d, ox, oy, oz, hx, hy, hz, &ix, &iy, &iz);
    BeckmannEvalPdf(d, alpha, ox, oy, oz, ix, iy, iz, &pdf);
    // weight = F G1(wi) (G1(wo)/cos θo) (wo·H) / H.z, H = wo + wi (ConductorSample).
    const V8 sx = hn::Add(ox, ix), sy = hn::Add(oy, iy), sz = hn::Add(oz, iz);
    const V8 n2 = hn::Add(hn::Add(hn::Mul(sx, sx), hn::Mul(sy, sy)), hn::Mul(sz, sz));
    const V8 g = hn::Mul(BeckmannG1(d, alpha, ix, iy, iz), BeckmannG1OverCos(d, alpha, ox, oy, oz));
    const V8 wi_h = hn::Mul(hn::Set(d, 0.5f), hn::Sqrt(n2));
    const V8 wo_h = RoundedDot(d, ox, oy, oz, sx, sy, sz);
    const V8 scale = hn::Div(hn::Mul(g, wo_h), sz);
    const V8 wr =
        hn::Mul(FresnelConductor(d, wi_h, hn::Load(d, c.eta_r), hn::Load(d, c.k_r)), scale);
    const V8 wg =
        hn::Mul(FresnelConductor(d, wi_h, hn::Load(d, c.eta_g), hn::Load(d, c.k_g)), scale);
    const V8 wb =
        hn::Mul(FresnelConductor(d, wi_h, hn::Load(d, c.eta_b), hn::Load(d, c.k_b)), scale);
    const M8 ok = hn::And(hn::And(hn::Gt(oz, zero), hn::Gt(iz, zero)),
                          hn::And(hn::Gt(pdf, zero), AllFinite3(d, wr, wg, wb)));
    StoreSample(d, b, i, ok, ix, iy, iz, wr, wg, wb, pdf, one);
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_CONDUCTOR8_INL_H_ toggle
