// Per-target 8-wide twin of engine/bsdf/rough_conductor.h (the conductor table's Mitsuba form),
// part of simd/wavefront/bsdf8-inl.h: included there, it uses that file's block driver,
// gathers and Fresnel kernels.

#if defined(PTLAB_SIMD_ROUGH_CONDUCTOR8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_ROUGH_CONDUCTOR8_INL_H_
#undef PTLAB_SIMD_ROUGH_CONDUCTOR8_INL_H_
#else
#define PTLAB_SIMD_ROUGH_CONDUCTOR8_INL_H_
#endif

#include "simd/wavefront/microfacet8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

/// The distributions of one block from a table's αu, αv and MicrofacetFlags columns.
HWY_INLINE mf8::Dist8 GatherDist(D8 d, const AlignedVector<float>& alpha_u,
                                 const AlignedVector<float>& alpha_v,
                                 const AlignedVector<uint8_t>& flags, const uint32_t* index,
                                 size_t i) {
  const hn::RebindToSigned<D8> di;
  HWY_ALIGN int32_t fl[8] = {};
  for (size_t j = 0; j < hn::Lanes(d); ++j) fl[j] = flags[index[i + j]];
  const auto f = hn::Load(di, fl);
  mf8::Dist8 dist;
  dist.ggx = hn::RebindMask(d, hn::TestBit(f, hn::Set(di, kMicrofacetGgx)));
  dist.visible = hn::RebindMask(d, hn::TestBit(f, hn::Set(di, kMicrofacetSampleVisible)));
  dist.au = mf8::ClampAlpha(d, Gather(d, alpha_u, index, i));
  dist.av = mf8::ClampAlpha(d, Gather(d, alpha_v, index, i));
  return dist;
}

/// One block's rough conductor rows.
struct RoughConductorLanes {
  mf8::Dist8 dist;
  V8 eta_r, eta_g, eta_b, k_r, k_g, k_b, s_r, s_g, s_b;
};

/// specular × FresnelConductor(cos) × scale per channel, as the oracle's (R F) s.
HWY_INLINE void TintedConductorFresnel(D8 d, const RoughConductorLanes& c, V8 cos, V8 scale, V8* r,
                                       V8* g, V8* b) {
  *r = hn::Mul(hn::Mul(c.s_r, FresnelConductor(d, cos, c.eta_r, c.k_r)), scale);
  *g = hn::Mul(hn::Mul(c.s_g, FresnelConductor(d, cos, c.eta_g, c.k_g)), scale);
  *b = hn::Mul(hn::Mul(c.s_b, FresnelConductor(d, cos, c.eta_b, c.k_b)), scale);
}

/// RoughConductorEval (into *fr, *fg, *fb) and RoughConductorPdf (returned) at (wo, wi); g1o is
/// G1OverCos(wo), computed once per block for the evaluation and the sample.
HWY_INLINE V8 RoughConductorEvalPdf(D8 d, const RoughConductorLanes& c, V8 g1o, V8 ox, V8 oy, V8 oz,
                                    V8 ix, V8 iy, V8 iz, V8* fr, V8* fg, V8* fb) {
  const V8 zero = hn::Zero(d);
  V8 hx = hn::Add(ox, ix), hy = hn::Add(oy, iy), hz = hn::Add(oz, iz);
  mf8::Normalize3(d, &hx, &hy, &hz);
  const M8 above = hn::And(hn::Gt(oz, zero), hn::Gt(iz, zero));
  const V8 dv = mf8::D(d, c.dist, hx, hy, hz);
  const V8 g = hn::Mul(g1o, mf8::G1OverCos(d, c.dist, ix, iy, iz));
  const V8 wi_h = hn::Add(hn::Add(hn::Mul(ix, hx), hn::Mul(iy, hy)), hn::Mul(iz, hz));
  const V8 scale = hn::Mul(hn::Mul(hn::Set(d, 0.25f), dv), g);
  V8 r, gg, b;
  TintedConductorFresnel(d, c, wi_h, scale, &r, &gg, &b);
  const M8 ok = hn::And(above, hn::And(hn::Gt(dv, zero), AllFinite3(d, r, gg, b)));
  *fr = hn::IfThenElseZero(ok, r), *fg = hn::IfThenElseZero(ok, gg),
  *fb = hn::IfThenElseZero(ok, b);
  const V8 pdf = hn::Div(mf8::Pdf(d, c.dist, ox, oy, oz, hx, hy, hz, &g1o, &dv),
                         hn::Mul(hn::Set(d, 4.0f), wi_h));
  return hn::IfThenElseZero(hn::And(above, hn::And(hn::Gt(wi_h, zero), hn::IsFinite(pdf))), pdf);
}

/// RoughConductorEval / RoughConductorPdf / RoughConductorSample for a ConductorTable in its
/// Mitsuba form (ConductorTable::microfacet()).
/// mask: `tex` for the textured αu, αv (TexturedFloat8, then clamped as MakeMicrofacet does).
inline HWY_NOINLINE void ShadeRoughConductor(const ConductorTable& t,
                                             const ShadeInputs::Textures& tex, const ShadeIo& io,
                                             size_t n, bool eval, bool sample) {
  const bool textured = tex.textures != nullptr && t.textured();
  ForEachBlock(io, n, [&t, &tex, textured, eval, sample](const ShadeIo& b, size_t i) HWY_ATTR {
    const D8 d;
    const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    RoughConductorLanes c;
    c.dist = GatherDist(d, t.alpha, t.alpha_v, t.flags, b.index, i);
    if (textured) {  // mask
      V8 au = Gather(d, t.alpha, b.index, i), av = Gather(d, t.alpha_v, b.index, i);
      TexturedFloat8(d, tex, t.alpha_texture, b, i, &au);
      TexturedFloat8(d, tex, t.alpha_v_texture, b, i, &av);
      c.dist.au = mf8::ClampAlpha(d, au), c.dist.av = mf8::ClampAlpha(d, av);
    }
    c.eta_r = Gather(d, t.eta_r, b.index, i), c.eta_g = Gather(d, t.eta_g, b.index, i);
    c.eta_b = Gather(d, t.eta_b, b.index, i);
    c.k_r = Gather(d, t.k_r, b.index, i), c.k_g = Gather(d, t.k_g, b.index, i);
    c.k_b = Gather(d, t.k_b, b.index, i);
    c.s_r = Gather(d, t.specular_r, b.index, i), c.s_g = Gather(d, t.specular_g, b.index, i);
    c.s_b = Gather(d, t.specular_b, b.index, i);
    const V8 ox = In(d, b, kWoX, i), oy = In(d, b, kWoY, i), oz = In(d, b, kWoZ, i);
    const V8 g1o = mf8::G1OverCos(d, c.dist, ox, oy, oz);
    if (eval) {
      const V8 lx = In(d, b, kWlX, i), ly = In(d, b, kWlY, i), lz = In(d, b, kWlZ, i);
      V8 fr, fg, fb;
      const V8 pdf_l = RoughConductorEvalPdf(d, c, g1o, ox, oy, oz, lx, ly, lz, &fr, &fg, &fb);
      StoreEval(d, b, i, fr, fg, fb, pdf_l);
    }
    if (!sample) return;
    V8 mx, my, mz, pdf_m;
    mf8::Sample(d, c.dist, ox, oy, oz, In(d, b, kUX, i), In(d, b, kUY, i), &mx, &my, &mz, &pdf_m,
                &g1o);
    const V8 wo_m = hn::Add(hn::Add(hn::Mul(ox, mx), hn::Mul(oy, my)), hn::Mul(oz, mz));
    const V8 two_wo_m = hn::Mul(hn::Set(d, 2.0f), wo_m);
    const V8 ix = hn::Sub(hn::Mul(two_wo_m, mx), ox), iy = hn::Sub(hn::Mul(two_wo_m, my), oy),
             iz = hn::Sub(hn::Mul(two_wo_m, mz), oz);
    V8 fr, fg, fb;
    const V8 pdf = RoughConductorEvalPdf(d, c, g1o, ox, oy, oz, ix, iy, iz, &fr, &fg, &fb);
    V8 hx = hn::Add(ox, ix), hy = hn::Add(oy, iy), hz = hn::Add(oz, iz);
    mf8::Normalize3(d, &hx, &hy, &hz);
    // The weight with D cancelled: G1(wi) with visible normals, G (wo·h)/(cos θo h.z) else.
    const V8 g1_i = mf8::G1(d, c.dist, ix, iy, iz, hx, hy, hz);
    V8 g = g1_i;
    if (!hn::AllTrue(d, c.dist.visible)) {
      const V8 wo_h = hn::Add(hn::Add(hn::Mul(ox, hx), hn::Mul(oy, hy)), hn::Mul(oz, hz));
      const V8 gg = hn::Mul(mf8::G1(d, c.dist, ox, oy, oz, hx, hy, hz, &g1o), g1_i);
      g = hn::IfThenElse(c.dist.visible, g, hn::Div(hn::Mul(gg, wo_h), hn::Mul(oz, hz)));
    }
    const V8 wi_h = hn::Add(hn::Add(hn::Mul(ix, hx), hn::Mul(iy, hy)), hn::Mul(iz, hz));
    V8 wr, wg, wb;
    TintedConductorFresnel(d, c, wi_h, g, &wr, &wg, &wb);
    const M8 ok = hn::And(hn::And(hn::Gt(pdf_m, zero), hn::And(hn::Gt(oz, zero), hn::Gt(iz, zero))),
                          hn::And(hn::Gt(pdf, zero), AllFinite3(d, wr, wg, wb)));
    StoreSample(d, b, i, ok, ix, iy, iz, wr, wg, wb, pdf, one);
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_ROUGH_CONDUCTOR8_INL_H_
