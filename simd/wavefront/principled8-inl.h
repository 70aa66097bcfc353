// The principled and principledthin tags' batches in the SIMD shading stage (re-included once
// per Highway target): their 8-wide twins, ShadePrincipled and ShadePrincipledThin (eval, pdf
// and sample of every lobe; the lobes in principled_lobes8-inl.h and principled_thin8-inl.h;
// textured parameters gathered as TexturedColor8 / TexturedFloat8, then PrincipledAt's clamps).
//
// How close the twins are to the oracle (tests/simd/wavefront/principled8_test.cpp holds every
// target to it): f and pdf(wo, wl) repeat the oracle's IEEE operations in its order, so
// principledthin's are bit-identical and principled's differ only through hwy's Log in the
// clearcoat's GTR1 D (an ulp of log α²; measured ≤ 2.3e-7 relative). A sample's direction
// goes through hwy's Sin/Cos (the GGX visible normal, the cosine warp, GTR1's azimuth) and
// Exp·Log for GTR1's std::pow: wi within 5e-5, more where those samplers cancel (u_x → 1,
// u_y → 1, the concentric disk's rim), and the sample's pdf and weight are the oracle's at
// that wi within 2e-5 relative.

#if defined(PTLAB_SIMD_PRINCIPLED8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_PRINCIPLED8_INL_H_
#undef PTLAB_SIMD_PRINCIPLED8_INL_H_
#else
#define PTLAB_SIMD_PRINCIPLED8_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include "engine/scene/material_tables.h"
#include "engine/scene/principled_table.h"
#include "engine/wavefront/bsdf.h"
#include "hwy/highway.h"
#include "simd/wavefront/principled_lobes8-inl.h"
#include "simd/wavefront/principled_thin8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {
namespace pr8 {

/// PrincipledAt for rows [i, i + Lanes): each parameter its constant or (the rows whose texture
/// column names one) its texture at the row's shading point, then PrincipledAt's clamps.
/// `thin`: also diff_trans (principledthin's only).
HWY_INLINE PrincipledLanes GatherPrincipled(D8 d, const PrincipledTable& t,
                                            const ShadeInputs::Textures& tex, const ShadeIo& b,
                                            size_t i, bool thin = false) {
  const bool textures = tex.textures != nullptr;
  const V8 zero = hn::Zero(d);
  PrincipledLanes p;
  V8 r = Gather(d, t.base_r, b.index, i), g = Gather(d, t.base_g, b.index, i),
     bl = Gather(d, t.base_b, b.index, i);
  if (textures && !t.base_color_texture.empty())
    TexturedColor8(d, tex, t.base_color_texture, b, i, &r, &g, &bl);
  // std::max(c, 0).
  p.base_r = hn::IfThenZeroElse(hn::Lt(r, zero), r);
  p.base_g = hn::IfThenZeroElse(hn::Lt(g, zero), g);
  p.base_b = hn::IfThenZeroElse(hn::Lt(bl, zero), bl);
  const auto value = [&](PrincipledParam k) HWY_ATTR {
    V8 v = Gather(d, t.value[k], b.index, i);
    if (textures && !t.texture[k].empty()) TexturedFloat8(d, tex, t.texture[k], b, i, &v);
    return v;
  };
  const auto unit = [&](PrincipledParam k) HWY_ATTR { return Clamp(d, value(k), 0.0f, 1.0f); };
  p.roughness = unit(kPrincipledRoughness);
  p.anisotropic = unit(kPrincipledAnisotropic);
  p.metallic = unit(kPrincipledMetallic);
  p.spec_tint = unit(kPrincipledSpecTint);
  p.sheen = unit(kPrincipledSheen);
  p.sheen_tint = unit(kPrincipledSheenTint);
  p.clearcoat = unit(kPrincipledClearcoat);
  p.clearcoat_gloss = unit(kPrincipledClearcoatGloss);
  p.spec_trans = unit(kPrincipledSpecTrans);
  p.flatness = unit(kPrincipledFlatness);
  p.diff_trans =
      thin ? hn::Mul(hn::Set(d, 0.5f), Clamp(d, value(kPrincipledDiffTrans), 0.0f, 2.0f)) : zero;
  p.eta = Clamp(d, value(kPrincipledEta), 1e-4f, 1e4f);
  p.dist = Distribution(d, p.roughness, p.anisotropic);
  return p;
}

}  // namespace pr8

/// Both models' sample store: weight f·|cos θi| / pdf, valid where the direction was, pdf > 0
/// and the weight finite (the oracles' checks, in their order).
template <class D>
HWY_INLINE void StoreWeightedSample(D d, const ShadeIo& b, size_t i, hn::Mask<D> ok, hn::Vec<D> ix,
                                    hn::Vec<D> iy, hn::Vec<D> iz, hn::Vec<D> fr, hn::Vec<D> fg,
                                    hn::Vec<D> fb, hn::Vec<D> pdf, hn::Vec<D> eta) {
  const auto cos_over_pdf = hn::Div(hn::Abs(iz), pdf);
  const auto wr = hn::Mul(fr, cos_over_pdf), wg = hn::Mul(fg, cos_over_pdf),
             wb = hn::Mul(fb, cos_over_pdf);
  ok = hn::And(ok, hn::And(hn::Gt(pdf, hn::Zero(d)), AllFinite3(d, wr, wg, wb)));
  StoreSample(d, b, i, ok, ix, iy, iz, wr, wg, wb, pdf, eta);
}

/// PrincipledThinEvalPdf / PrincipledThinSample for rows of MaterialTables::principled_thin.
inline HWY_NOINLINE void ShadePrincipledThin(const PrincipledTable& t,
                                             const ShadeInputs::Textures& tex, const ShadeIo& io,
                                             size_t n, bool eval, bool sample) {
  ForEachBlock(io, n, [&t, &tex, eval, sample](const ShadeIo& b, size_t i) HWY_ATTR {
    const D8 d;
    const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    const pr8::PrincipledLanes p = pr8::GatherPrincipled(d, t, tex, b, i, /*thin=*/true);
    const V8 ox = In(d, b, kWoX, i), oy = In(d, b, kWoY, i), oz = In(d, b, kWoZ, i);
    if (eval) {
      const V8 lx = In(d, b, kWlX, i), ly = In(d, b, kWlY, i), lz = In(d, b, kWlZ, i);
      V8 fr, fg, fb;
      const V8 pdf_l = pr8::ThinEvalPdf(d, p, ox, oy, oz, lx, ly, lz, &fr, &fg, &fb);
      StoreEval(d, b, i, fr, fg, fb, pdf_l);
    }
    if (!sample) return;
    V8 ix, iy, iz;
    M8 ok = pr8::ThinSampleDirection(d, p, ox, oy, oz, In(d, b, kULobe, i), In(d, b, kUX, i),
                                     In(d, b, kUY, i), &ix, &iy, &iz);
    ix = hn::IfThenElseZero(ok, ix), iy = hn::IfThenElseZero(ok, iy);
    iz = hn::IfThenElse(ok, iz, one);
    V8 fr, fg, fb;
    const V8 pdf = pr8::ThinEvalPdf(d, p, ox, oy, oz, ix, iy, iz, &fr, &fg, &fb);
    StoreWeightedSample(d, b, i, ok, ix, iy, iz, fr, fg, fb, pdf, one);
  });
}

/// PrincipledEvalPdf / PrincipledSample for rows of MaterialTables::principled.
inline HWY_NOINLINE void ShadePrincipled(const PrincipledTable& t, const ShadeInputs::Textures& tex,
                                         const ShadeIo& io, size_t n, bool eval, bool sample) {
  ForEachBlock(io, n, [&t, &tex, eval, sample](const ShadeIo& b, size_t i) HWY_ATTR {
    const D8 d;
    const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f), minus = hn::Set(d, -1.0f);
    const pr8::PrincipledLanes p = pr8::GatherPrincipled(d, t, tex, b, i);
    const V8 ox = In(d, b, kWoX, i), oy = In(d, b, kWoY, i), oz = In(d, b, kWoZ, i);
    if (eval) {
      const V8 lx = In(d, b, kWlX, i), ly = In(d, b, kWlY, i), lz = In(d, b, kWlZ, i);
      V8 fr, fg, fb;
      const V8 pdf_l = pr8::EvalPdf(d, p, ox, oy, oz, lx, ly, lz, &fr, &fg, &fb);
      StoreEval(d, b, i, fr, fg, fb, pdf_l);
    }
    if (!sample) return;
    const V8 u_lobe = In(d, b, kULobe, i), ux = In(d, b, kUX, i), uy = In(d, b, kUY, i);
    const V8 cos_o = oz;
    const M8 front = hn::Gt(cos_o, zero);
    const V8 bsdf = hn::Mul(hn::Sub(one, p.metallic), p.spec_trans);
    M8 ok = hn::And(hn::And(hn::Ne(cos_o, zero), hn::IsFinite(cos_o)),
                    hn::Or(front, hn::Gt(bsdf, zero)));
    // A visible GGX normal for wo turned up; the dielectric F(wo·m) sets the lobes.
    const V8 wux = hn::IfThenElse(front, ox, hn::Mul(ox, minus)),
             wuy = hn::IfThenElse(front, oy, hn::Mul(oy, minus)),
             wuz = hn::IfThenElse(front, oz, hn::Mul(oz, minus));
    V8 mx, my, mz, pm;
    mf8::Sample(d, p.dist, wux, wuy, wuz, ux, uy, &mx, &my, &mz, &pm);
    const V8 wo_m = pr8::Dot(ox, oy, oz, mx, my, mz);
    V8 cos_t;
    const V8 fd = FresnelDielectric(d, wo_m, p.eta, &cos_t);
    const pr8::Lobes8 lobes = pr8::LobeProbabilities(d, p, front, fd);
    const V8 c1 = lobes.diffuse, c2 = hn::Add(c1, lobes.clearcoat),
             c3 = hn::Add(c2, lobes.transmission);
    const M8 is_diffuse = hn::Lt(u_lobe, c1);
    const M8 is_coat = hn::AndNot(is_diffuse, hn::Lt(u_lobe, c2));
    const M8 is_trans = hn::AndNot(hn::Lt(u_lobe, c2), hn::Lt(u_lobe, c3));
    const M8 is_refl = hn::Not(hn::Lt(u_lobe, c3));
    // The reflection about m (the reflection lobe's direction).
    const V8 two_wo_m = hn::Mul(hn::Set(d, 2.0f), wo_m);
    V8 ix = hn::Sub(hn::Mul(mx, two_wo_m), ox), iy = hn::Sub(hn::Mul(my, two_wo_m), oy),
       iz = hn::Sub(hn::Mul(mz, two_wo_m), oz);
    const M8 side_r = hn::Gt(hn::Mul(iz, cos_o), zero);
    ok = hn::And(
        ok, hn::Or(hn::Not(is_refl), hn::And(hn::And(hn::Gt(pm, zero), side_r),
                                             pr8::MicroMacroCompatible(d, mx, my, mz, ox, oy, oz,
                                                                       ix, iy, iz, cos_o, true))));
    if (!hn::AllFalse(d, is_diffuse)) {  // the cosine hemisphere
      V8 cx, cy, cz;
      SampleCosineHemisphere(d, ux, uy, &cx, &cy, &cz);
      ix = hn::IfThenElse(is_diffuse, cx, ix), iy = hn::IfThenElse(is_diffuse, cy, iy);
      iz = hn::IfThenElse(is_diffuse, cz, iz);
      ok = hn::And(ok, hn::Or(hn::Not(is_diffuse), hn::Gt(cz, zero)));
    }
    if (!hn::AllFalse(d, is_coat)) {  // a GTR1 normal, the reflection about it
      V8 nx, ny, nz;
      pr8::SampleGtr1(d, pr8::ClearcoatAlpha(d, p.clearcoat_gloss), ux, uy, &nx, &ny, &nz);
      const V8 two_wo_n = hn::Mul(hn::Set(d, 2.0f), pr8::Dot(ox, oy, oz, nx, ny, nz));
      const V8 cx = hn::Sub(hn::Mul(nx, two_wo_n), ox), cy = hn::Sub(hn::Mul(ny, two_wo_n), oy),
               cz = hn::Sub(hn::Mul(nz, two_wo_n), oz);
      const M8 coat_ok =
          hn::And(hn::Gt(hn::Mul(cz, cos_o), zero),
                  pr8::MicroMacroCompatible(d, nx, ny, nz, ox, oy, oz, cx, cy, cz, cos_o, true));
      ix = hn::IfThenElse(is_coat, cx, ix), iy = hn::IfThenElse(is_coat, cy, iy);
      iz = hn::IfThenElse(is_coat, cz, iz);
      ok = hn::And(ok, hn::Or(hn::Not(is_coat), coat_ok));
    }
    V8 eta_out = one;
    if (!hn::AllFalse(d, is_trans)) {  // the refraction about m
      const M8 m_front = hn::Gt(wo_m, zero);
      const V8 eta_r = hn::IfThenElse(m_front, p.eta, hn::Div(one, p.eta));
      const V8 inv = hn::Div(one, eta_r);
      const V8 ct = hn::IfThenElse(m_front, hn::Neg(cos_t), cos_t);
      const V8 k = hn::Add(hn::Mul(wo_m, inv), ct);
      const V8 tx = hn::Sub(hn::Mul(mx, k), hn::Mul(ox, inv)),
               ty = hn::Sub(hn::Mul(my, k), hn::Mul(oy, inv)),
               tz = hn::Sub(hn::Mul(mz, k), hn::Mul(oz, inv));
      const M8 trans_ok =
          hn::And(hn::And(hn::Gt(pm, zero), hn::Lt(hn::Mul(tz, cos_o), zero)),
                  pr8::MicroMacroCompatible(d, mx, my, mz, ox, oy, oz, tx, ty, tz, cos_o, false));
      ix = hn::IfThenElse(is_trans, tx, ix), iy = hn::IfThenElse(is_trans, ty, iy);
      iz = hn::IfThenElse(is_trans, tz, iz);
      ok = hn::And(ok, hn::Or(hn::Not(is_trans), trans_ok));
      eta_out = hn::IfThenElse(is_trans, eta_r, one);
    }
    ok = hn::And(ok, AllFinite3(d, ix, iy, iz));
    // Lanes that failed get a harmless direction for the evaluation (their output is zeroed).
    ix = hn::IfThenElseZero(ok, ix), iy = hn::IfThenElseZero(ok, iy);
    iz = hn::IfThenElse(ok, iz, one);
    V8 fr, fg, fb;
    const V8 pdf = pr8::EvalPdf(d, p, ox, oy, oz, ix, iy, iz, &fr, &fg, &fb);
    StoreWeightedSample(d, b, i, ok, ix, iy, iz, fr, fg, fb, pdf, eta_out);
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_PRINCIPLED8_INL_H_
