// Per-target 8-wide twin of engine/bsdf/rough_dielectric.h, part of simd/wavefront/bsdf8-inl.h:
// included there, it uses that file's block driver, gathers and Fresnel kernel.

#if defined(PTLAB_SIMD_ROUGH_DIELECTRIC8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_ROUGH_DIELECTRIC8_INL_H_
#undef PTLAB_SIMD_ROUGH_DIELECTRIC8_INL_H_
#else
#define PTLAB_SIMD_ROUGH_DIELECTRIC8_INL_H_
#endif

#include "simd/wavefront/microfacet8-inl.h"
#include "simd/wavefront/rough_conductor8-inl.h"  // GatherDist

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

/// One block's rough dielectric rows.
struct RoughDielectricLanes {
  mf8::Dist8 dist;
  V8 eta;  // int_ior / ext_ior, unclamped (FresnelDielectric clamps)
  V8 r_r, r_g, r_b, t_r, t_g, t_b;
};

HWY_INLINE V8 Dot3(V8 ax, V8 ay, V8 az, V8 bx, V8 by, V8 bz) {
  return hn::Add(hn::Add(hn::Mul(ax, bx), hn::Mul(ay, by)), hn::Mul(az, bz));
}

/// rough_dielectric_internal::SamplingDistribution.
HWY_INLINE mf8::Dist8 SamplingDist(D8 d, const mf8::Dist8& f, V8 cos_o) {
  if (hn::AllTrue(d, f.visible)) return f;
  const V8 s = hn::Sub(hn::Set(d, 1.2f), hn::Mul(hn::Set(d, 0.2f), hn::Sqrt(hn::Abs(cos_o))));
  mf8::Dist8 r = f;
  r.au = hn::IfThenElse(f.visible, f.au, mf8::ClampAlpha(d, hn::Mul(f.au, s)));
  r.av = hn::IfThenElse(f.visible, f.av, mf8::ClampAlpha(d, hn::Mul(f.av, s)));
  return r;
}

/// RoughDielectricEval (into *fr, *fg, *fb) and RoughDielectricPdf (returned); g1o is
/// G1OverCos(wo) of c.dist, computed once per block (the sampling distribution is c.dist where
/// every lane samples visible normals: then the pdf takes g1o and D too).
HWY_INLINE V8 RoughDielectricEvalPdf(D8 d, const RoughDielectricLanes& c, V8 g1o, V8 ox, V8 oy,
                                     V8 oz, V8 ix, V8 iy, V8 iz, V8* fr, V8* fg, V8* fb) {
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  // HalfVector.
  const M8 reflect = hn::Gt(hn::Mul(oz, iz), zero);
  const V8 eta_r = hn::IfThenElse(hn::Gt(oz, zero), c.eta, hn::Div(one, c.eta));
  const V8 k = hn::IfThenElse(reflect, one, eta_r);
  V8 hx = hn::IfThenElse(reflect, hn::Add(ox, ix), hn::Add(ox, hn::Mul(ix, k)));
  V8 hy = hn::IfThenElse(reflect, hn::Add(oy, iy), hn::Add(oy, hn::Mul(iy, k)));
  V8 hz = hn::IfThenElse(reflect, hn::Add(oz, iz), hn::Add(oz, hn::Mul(iz, k)));
  const V8 len2 = Dot3(hx, hy, hz, hx, hy, hz);
  const V8 inv = hn::Div(one, hn::Sqrt(len2));
  hx = hn::Mul(hx, inv), hy = hn::Mul(hy, inv), hz = hn::Mul(hz, inv);
  const M8 flip = hn::Lt(hz, zero);
  hx = hn::IfThenElse(flip, hn::Mul(hx, hn::Set(d, -1.0f)), hx);
  hy = hn::IfThenElse(flip, hn::Mul(hy, hn::Set(d, -1.0f)), hy);
  hz = hn::IfThenElse(flip, hn::Mul(hz, hn::Set(d, -1.0f)), hz);
  const V8 wo_h = Dot3(ox, oy, oz, hx, hy, hz), wi_h = Dot3(ix, iy, iz, hx, hy, hz);
  const M8 valid = hn::And(hn::And(hn::And(hn::Ne(oz, zero), hn::Ne(iz, zero)),
                                   hn::And(hn::Gt(len2, zero), hn::IsFinite(len2))),
                           hn::And(hn::Gt(hz, zero), hn::And(hn::Gt(hn::Mul(wo_h, oz), zero),
                                                             hn::Gt(hn::Mul(wi_h, iz), zero))));
  // Eval.
  const V8 dv = mf8::D(d, c.dist, hx, hy, hz);
  V8 cos_t;
  const V8 f = FresnelDielectric(d, wo_h, c.eta, &cos_t);
  const V8 g = hn::Mul(mf8::G1(d, c.dist, ox, oy, oz, hx, hy, hz, &g1o),
                       mf8::G1(d, c.dist, ix, iy, iz, hx, hy, hz));
  const V8 cos_oi = hn::Abs(hn::Mul(oz, iz));
  const V8 denom = hn::Add(wo_h, hn::Mul(eta_r, wi_h));
  const V8 s_refl = hn::Div(hn::Mul(hn::Mul(f, dv), g), hn::Mul(hn::Set(d, 4.0f), cos_oi));
  const V8 s_refr =
      hn::Div(hn::Mul(hn::Mul(hn::Mul(hn::Sub(one, f), dv), g), hn::Abs(hn::Mul(wo_h, wi_h))),
              hn::Mul(cos_oi, hn::Mul(denom, denom)));
  const V8 s = hn::IfThenElse(reflect, s_refl, s_refr);
  const V8 r = hn::Mul(hn::IfThenElse(reflect, c.r_r, c.t_r), s);
  const V8 gg = hn::Mul(hn::IfThenElse(reflect, c.r_g, c.t_g), s);
  const V8 bb = hn::Mul(hn::IfThenElse(reflect, c.r_b, c.t_b), s);
  const M8 f_ok = hn::And(valid, hn::And(hn::Gt(dv, zero), AllFinite3(d, r, gg, bb)));
  *fr = hn::IfThenElseZero(f_ok, r), *fg = hn::IfThenElseZero(f_ok, gg),
  *fb = hn::IfThenElseZero(f_ok, bb);
  // Pdf.
  const V8 jac_refl = hn::Div(one, hn::Mul(hn::Set(d, 4.0f), hn::Abs(wi_h)));
  const V8 jac_refr = hn::Div(hn::Mul(hn::Mul(eta_r, eta_r), hn::Abs(wi_h)), hn::Mul(denom, denom));
  const M8 below = hn::Lt(oz, zero);
  const V8 ux = hn::IfThenElse(below, hn::Mul(ox, hn::Set(d, -1.0f)), ox);
  const V8 uy = hn::IfThenElse(below, hn::Mul(oy, hn::Set(d, -1.0f)), oy);
  const V8 uz = hn::IfThenElse(below, hn::Mul(oz, hn::Set(d, -1.0f)), oz);
  const bool visible = hn::AllTrue(d, c.dist.visible);
  const V8 pm = visible ? mf8::Pdf(d, c.dist, ux, uy, uz, hx, hy, hz, &g1o, &dv)
                        : mf8::Pdf(d, SamplingDist(d, c.dist, oz), ux, uy, uz, hx, hy, hz);
  const V8 pdf = hn::Mul(hn::Mul(pm, hn::IfThenElse(reflect, f, hn::Sub(one, f))),
                         hn::IfThenElse(reflect, jac_refl, jac_refr));
  return hn::IfThenElseZero(hn::And(valid, hn::IsFinite(pdf)), pdf);
}

/// RoughDielectricEval / RoughDielectricPdf / RoughDielectricSample.
/// `tex` for the textured αu, αv (TexturedFloat8, then clamped as MakeMicrofacet does).
inline HWY_NOINLINE void ShadeRoughDielectric(const RoughDielectricTable& t,
                                              const ShadeInputs::Textures& tex, const ShadeIo& io,
                                              size_t n, bool eval, bool sample) {
  const bool textured = tex.textures != nullptr && t.textured();
  // Rows grouped by distribution and sampling (a block mixing Beckmann and GGX rows runs both).
  const auto key = [&t, &io](size_t r) {
    return uint32_t(t.flags[io.index[r]] & (kMicrofacetGgx | kMicrofacetSampleVisible));
  };
  ForEachBlockGrouped(
      io, n, key, [&t, &tex, textured, eval, sample](const ShadeIo& b, size_t i) HWY_ATTR {
        const D8 d;
        const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f), minus = hn::Set(d, -1.0f);
        RoughDielectricLanes c;
        c.dist = GatherDist(d, t.alpha_u, t.alpha_v, t.flags, b.index, i);
        if (textured) {
          V8 au = Gather(d, t.alpha_u, b.index, i), av = Gather(d, t.alpha_v, b.index, i);
          TexturedFloat8(d, tex, t.alpha_texture, b, i, &au);
          TexturedFloat8(d, tex, t.alpha_v_texture, b, i, &av);
          c.dist.au = mf8::ClampAlpha(d, au), c.dist.av = mf8::ClampAlpha(d, av);
        }
        c.eta = hn::Div(Gather(d, t.int_ior, b.index, i), Gather(d, t.ext_ior, b.index, i));
        c.r_r = Gather(d, t.reflectance_r, b.index, i),
        c.r_g = Gather(d, t.reflectance_g, b.index, i);
        c.r_b = Gather(d, t.reflectance_b, b.index, i);
        c.t_r = Gather(d, t.transmittance_r, b.index, i);
        c.t_g = Gather(d, t.transmittance_g, b.index, i);
        c.t_b = Gather(d, t.transmittance_b, b.index, i);
        const V8 ox = In(d, b, kWoX, i), oy = In(d, b, kWoY, i), oz = In(d, b, kWoZ, i);
        const V8 g1o = mf8::G1OverCos(d, c.dist, ox, oy, oz);
        if (eval) {
          const V8 lx = In(d, b, kWlX, i), ly = In(d, b, kWlY, i), lz = In(d, b, kWlZ, i);
          V8 fr, fg, fb;
          const V8 pdf_l = RoughDielectricEvalPdf(d, c, g1o, ox, oy, oz, lx, ly, lz, &fr, &fg, &fb);
          StoreEval(d, b, i, fr, fg, fb, pdf_l);
        }
        if (!sample) return;
        const M8 below = hn::Lt(oz, zero);
        const V8 ux = hn::IfThenElse(below, hn::Mul(ox, minus), ox);
        const V8 uy = hn::IfThenElse(below, hn::Mul(oy, minus), oy);
        const V8 uz = hn::IfThenElse(below, hn::Mul(oz, minus), oz);
        V8 mx, my, mz, pdf_m;
        const bool visible = hn::AllTrue(d, c.dist.visible);  // then SamplingDist is c.dist
        mf8::Sample(d, SamplingDist(d, c.dist, oz), ux, uy, uz, In(d, b, kUX, i), In(d, b, kUY, i),
                    &mx, &my, &mz, &pdf_m, visible ? &g1o : nullptr);
        const V8 wo_m = Dot3(ox, oy, oz, mx, my, mz);
        V8 cos_t;
        const V8 f = FresnelDielectric(d, wo_m, c.eta, &cos_t);
        const M8 reflect = hn::Lt(In(d, b, kULobe, i), f);
        // Reflection.
        const V8 two_wo_m = hn::Mul(wo_m, hn::Set(d, 2.0f));
        const V8 rx = hn::Sub(hn::Mul(mx, two_wo_m), ox), ry = hn::Sub(hn::Mul(my, two_wo_m), oy),
                 rz = hn::Sub(hn::Mul(mz, two_wo_m), oz);
        // Refraction.
        const M8 front = hn::Gt(wo_m, zero);
        const V8 eta_c = ClampRelIor(d, c.eta);
        const V8 eta_r = hn::IfThenElse(front, eta_c, hn::Div(one, eta_c));
        const V8 inv = hn::Div(one, eta_r);
        const V8 ct = hn::IfThenElse(front, hn::Neg(cos_t), cos_t);
        const V8 k = hn::Add(hn::Mul(wo_m, inv), ct);
        const V8 tx = hn::Sub(hn::Mul(mx, k), hn::Mul(ox, inv)),
                 ty = hn::Sub(hn::Mul(my, k), hn::Mul(oy, inv)),
                 tz = hn::Sub(hn::Mul(mz, k), hn::Mul(oz, inv));
        const V8 ix = hn::IfThenElse(reflect, rx, tx), iy = hn::IfThenElse(reflect, ry, ty),
                 iz = hn::IfThenElse(reflect, rz, tz);
        const V8 wi_m = Dot3(tx, ty, tz, mx, my, mz);
        const V8 denom = hn::Add(wo_m, hn::Mul(eta_r, wi_m));
        const V8 jac_refl = hn::Div(one, hn::Mul(hn::Set(d, 4.0f), hn::Abs(wo_m)));
        const V8 jac_refr =
            hn::Div(hn::Mul(hn::Mul(eta_r, eta_r), hn::Abs(wi_m)), hn::Mul(denom, denom));
        const V8 lobe = hn::IfThenElse(reflect, f, hn::Sub(one, f));
        const V8 pdf = hn::Mul(hn::Mul(pdf_m, lobe), hn::IfThenElse(reflect, jac_refl, jac_refr));
        // Weight.
        V8 g = mf8::G1(d, c.dist, ix, iy, iz, mx, my, mz);
        if (!hn::AllTrue(d, c.dist.visible)) {
          const V8 gg = hn::Mul(mf8::G1(d, c.dist, ox, oy, oz, mx, my, mz, &g1o), g);
          const V8 nv = hn::Div(hn::Mul(hn::Mul(mf8::D(d, c.dist, mx, my, mz), gg), hn::Abs(wo_m)),
                                hn::Mul(pdf_m, hn::Abs(oz)));
          g = hn::IfThenElse(c.dist.visible, g, nv);
        }
        const V8 gt = hn::Div(g, hn::Mul(eta_r, eta_r));
        const V8 wr = hn::IfThenElse(reflect, hn::Mul(c.r_r, g), hn::Mul(c.t_r, gt));
        const V8 wg = hn::IfThenElse(reflect, hn::Mul(c.r_g, g), hn::Mul(c.t_g, gt));
        const V8 wb = hn::IfThenElse(reflect, hn::Mul(c.r_b, g), hn::Mul(c.t_b, gt));
        const V8 side = hn::Mul(iz, oz);
        const M8 side_ok =
            hn::Or(hn::And(reflect, hn::Gt(side, zero)), hn::AndNot(reflect, hn::Lt(side, zero)));
        const M8 ok = hn::And(
            hn::And(hn::And(hn::Ne(oz, zero), hn::IsFinite(oz)),
                    hn::And(hn::Gt(pdf_m, zero), hn::Gt(hn::Mul(wo_m, oz), zero))),
            hn::And(
                hn::And(side_ok, hn::And(hn::Gt(pdf, zero), hn::IsFinite(pdf))),
                hn::And(AllFinite3(d, wr, wg, wb), hn::And(hn::IsFinite(ix), hn::IsFinite(iy)))));
        StoreSample(d, b, i, ok, ix, iy, iz, wr, wg, wb, pdf, hn::IfThenElse(reflect, one, eta_r));
      });
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_ROUGH_DIELECTRIC8_INL_H_
