// Per-target 8-wide twins of the lobes of Mitsuba's `principled` (engine/bsdf/principled.h and
// engine/bsdf/principled_lobes.h), part of simd/wavefront/bsdf8-inl.h: included there (through
// principled8-inl.h), it uses that file's Fresnel kernel, cosine warp and the GGX kernels of
// microfacet8-inl.h. Every function repeats its oracle's operations in the oracle's order (the
// project builds with -ffp-contract=off), branches become selects; only hwy's Log (GTR1's D),
// Exp·Log (GTR1's α^(2(1 − u)), the oracle's std::pow) and Sin/Cos (the samplers) round
// differently from libm.

#if defined(PTLAB_SIMD_PRINCIPLED_LOBES8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_PRINCIPLED_LOBES8_INL_H_
#undef PTLAB_SIMD_PRINCIPLED_LOBES8_INL_H_
#else
#define PTLAB_SIMD_PRINCIPLED_LOBES8_INL_H_
#endif

#include "engine/bsdf/principled_lobes.h"
#include "hwy/contrib/math/math-inl.h"
#include "hwy/highway.h"
#include "simd/wavefront/microfacet8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {
namespace pr8 {

/// One block's principled parameters (PrincipledParams after PrincipledAt's clamps) and the
/// GGX distribution PrincipledDistribution makes of them.
struct PrincipledLanes {
  V8 base_r, base_g, base_b;
  V8 roughness, anisotropic, metallic, spec_tint, sheen, sheen_tint, clearcoat, clearcoat_gloss,
      spec_trans, flatness, diff_trans, eta;
  mf8::Dist8 dist;
};

/// Dot (engine/core/vec.h): (ax bx + ay by) + az bz.
HWY_INLINE V8 Dot(V8 ax, V8 ay, V8 az, V8 bx, V8 by, V8 bz) {
  return hn::Add(hn::Add(hn::Mul(ax, bx), hn::Mul(ay, by)), hn::Mul(az, bz));
}

/// r + x where m, r elsewhere (the oracle's `if (m) r += x`).
HWY_INLINE V8 AddIf(M8 m, V8 r, V8 x) { return hn::IfThenElse(m, hn::Add(r, x), r); }

/// std::clamp(v, lo, hi).
HWY_INLINE V8 Clamp(D8 d, V8 v, float lo, float hi) {
  const V8 l = hn::Set(d, lo), h = hn::Set(d, hi);
  return hn::IfThenElse(hn::Lt(v, l), l, hn::IfThenElse(hn::Lt(h, v), h, v));
}

/// SchlickWeight: (1 − c)⁵ with 1 − c clamped into [0, 1].
HWY_INLINE V8 SchlickWeight(D8 d, V8 c) {
  const V8 m = Clamp(d, hn::Sub(hn::Set(d, 1.0f), c), 0.0f, 1.0f);
  const V8 m2 = hn::Mul(m, m);
  return hn::Mul(hn::Mul(m2, m2), m);
}

/// The Schlick weight of principled_internal::SchlickFresnel(r0, cos_i, eta) (it does not
/// depend on r0): w such that the Fresnel term is r0 + (1 − r0) w.
HWY_INLINE V8 SchlickFresnelWeight(D8 d, V8 cos_i, V8 eta) {
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const M8 outside = hn::Ge(cos_i, zero);
  const V8 inv_eta = hn::Div(one, eta);
  const V8 eta_it = hn::IfThenElse(outside, eta, inv_eta);
  const V8 eta_ti = hn::IfThenElse(outside, inv_eta, eta);
  const V8 ct2 = hn::Sub(one, hn::Mul(hn::Sub(one, hn::Mul(cos_i, cos_i)), hn::Mul(eta_ti, eta_ti)));
  const V8 w_out = SchlickWeight(d, hn::Abs(cos_i));
  const V8 w_in = SchlickWeight(d, hn::Sqrt(hn::Max(ct2, zero)));
  return hn::IfThenElse(hn::Gt(eta_it, one), w_out, w_in);
}
/// r0 + (1 − r0) w (SchlickFresnel with w = SchlickFresnelWeight).
HWY_INLINE V8 Schlick(D8 d, V8 r0, V8 w) {
  return hn::Add(r0, hn::Mul(hn::Sub(hn::Set(d, 1.0f), r0), w));
}

/// SchlickR0: ((η − 1)/(η + 1))².
HWY_INLINE V8 SchlickR0(D8 d, V8 eta) {
  const V8 one = hn::Set(d, 1.0f);
  const V8 r = hn::Div(hn::Sub(eta, one), hn::Add(eta, one));
  return hn::Mul(r, r);
}

/// TintColor: base / Luminance(base) (base (1/lum), as Color3f's operator/), white where the
/// luminance is not > 0.
HWY_INLINE void TintColor(D8 d, const PrincipledLanes& p, V8* r, V8* g, V8* b) {
  const V8 one = hn::Set(d, 1.0f);
  const V8 lum = hn::Add(hn::Add(hn::Mul(hn::Set(d, 0.212671f), p.base_r),
                                 hn::Mul(hn::Set(d, 0.715160f), p.base_g)),
                         hn::Mul(hn::Set(d, 0.072169f), p.base_b));
  const M8 pos = hn::Gt(lum, hn::Zero(d));
  const V8 inv = hn::Div(one, lum);
  *r = hn::IfThenElse(pos, hn::Mul(p.base_r, inv), one);
  *g = hn::IfThenElse(pos, hn::Mul(p.base_g, inv), one);
  *b = hn::IfThenElse(pos, hn::Mul(p.base_b, inv), one);
}

/// Lerp: a + (b − a) t.
HWY_INLINE V8 Lerp(V8 a, V8 b, V8 t) { return hn::Add(a, hn::Mul(hn::Sub(b, a), t)); }

/// PrincipledDistribution: GGX with visible normals, αu = max(0.001, r²/√(1 − 0.9 a)),
/// αv = max(0.001, r² √(1 − 0.9 a)), then MakeMicrofacet's clamp.
HWY_INLINE mf8::Dist8 Distribution(D8 d, V8 roughness, V8 anisotropic) {
  const V8 r2 = hn::Mul(roughness, roughness);
  const V8 aspect =
      hn::Sqrt(hn::Sub(hn::Set(d, 1.0f), hn::Mul(hn::Set(d, 0.9f), anisotropic)));
  const V8 lo = hn::Set(d, 0.001f);
  const auto max_lo = [&](V8 x) HWY_ATTR { return hn::IfThenElse(hn::Lt(lo, x), x, lo); };  // std::max
  mf8::Dist8 f;
  f.ggx = hn::FirstN(d, 8), f.visible = f.ggx;
  f.au = mf8::ClampAlpha(d, max_lo(hn::Div(r2, aspect)));
  f.av = mf8::ClampAlpha(d, max_lo(hn::Mul(r2, aspect)));
  return f;
}

/// ClearcoatAlpha: 0.1 + (0.001 − 0.1) gloss.
HWY_INLINE V8 ClearcoatAlpha(D8 d, V8 gloss) {
  return Lerp(hn::Set(d, 0.1f), hn::Set(d, 0.001f), gloss);
}

/// Gtr1D for unit m: (α² − 1) / (π log α² (1 + (α² − 1) cos²θm)), 0 unless r cos θm > 1e-20
/// and r is finite. α ∈ [0.001, 0.1], so log's argument is a normal positive float.
HWY_INLINE V8 Gtr1D(D8 d, V8 alpha, V8 mz) {
  const V8 one = hn::Set(d, 1.0f);
  const V8 a2 = hn::Mul(alpha, alpha), a2m1 = hn::Sub(a2, one);
  const V8 den = hn::Mul(hn::Mul(hn::Set(d, kPi), hn::Log(d, a2)),
                         hn::Add(one, hn::Mul(a2m1, hn::Mul(mz, mz))));
  const V8 r = hn::Div(a2m1, den);
  const M8 ok = hn::And(hn::Gt(hn::Mul(r, mz), hn::Set(d, 1e-20f)), hn::IsFinite(r));
  return hn::IfThenElseZero(ok, r);
}
/// Gtr1Pdf: cos θm D(m), 0 below the surface.
HWY_INLINE V8 Gtr1Pdf(D8 d, V8 alpha, V8 mz) {
  return hn::IfThenZeroElse(hn::Lt(mz, hn::Zero(d)), hn::Mul(mz, Gtr1D(d, alpha, mz)));
}
/// SampleGtr1: φ = 2π u.x, cos²θ = (1 − α^(2(1 − u.y))) / (1 − α²), the power as
/// exp((1 − u.y) log α²).
HWY_INLINE void SampleGtr1(D8 d, V8 alpha, V8 ux, V8 uy, V8* mx, V8* my, V8* mz) {
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V8 phi = hn::Mul(hn::Set(d, 2.0f * kPi), ux), a2 = hn::Mul(alpha, alpha);
  const V8 pw = hn::Exp(d, mf8::ExpArg(d, hn::Mul(hn::Sub(one, uy), hn::Log(d, a2))));
  const V8 c2 = hn::Div(hn::Sub(one, pw), hn::Sub(one, a2));
  const V8 s = hn::Sqrt(hn::Max(zero, hn::Sub(one, c2))), c = hn::Sqrt(hn::Max(zero, c2));
  // hwy's Sin/Cos convert their argument to an integer: φ must be finite (u is).
  const V8 phi_ok = hn::IfThenElseZero(hn::IsFinite(phi), phi);
  *mx = hn::Mul(hn::Cos(d, phi_ok), s);
  *my = hn::Mul(hn::Sin(d, phi_ok), s);
  *mz = c;
}

/// ClearcoatG: Smith GGX with α = 0.25, G1(wo, m) G1(wi, m).
HWY_INLINE V8 ClearcoatG(D8 d, V8 ox, V8 oy, V8 oz, V8 ix, V8 iy, V8 iz, V8 mx, V8 my, V8 mz) {
  mf8::Dist8 f;
  f.ggx = hn::FirstN(d, 8), f.visible = f.ggx;
  f.au = f.av = hn::Set(d, 0.25f);
  return hn::Mul(mf8::G1(d, f, ox, oy, oz, mx, my, mz), mf8::G1(d, f, ix, iy, iz, mx, my, mz));
}

/// DiffuseFactor: Burley's diffuse + retro-reflection, lerped towards the fake subsurface by
/// flatness (where flatness > 0).
HWY_INLINE V8 DiffuseFactor(D8 d, V8 roughness, V8 flatness, V8 cos_o, V8 cos_i, V8 cos_d) {
  const V8 one = hn::Set(d, 1.0f), half = hn::Set(d, 0.5f);
  const V8 fl = SchlickWeight(d, cos_i), fv = SchlickWeight(d, cos_o);
  const V8 f_diff = hn::Mul(hn::Sub(one, hn::Mul(half, fv)), hn::Sub(one, hn::Mul(half, fl)));
  const V8 rr = hn::Mul(hn::Mul(hn::Set(d, 2.0f), roughness), hn::Mul(cos_d, cos_d));
  const V8 f_retro =
      hn::Mul(rr, hn::Add(hn::Add(fl, fv), hn::Mul(hn::Mul(fl, fv), hn::Sub(rr, one))));
  const V8 base = hn::Add(f_diff, f_retro);
  const M8 flat = hn::Gt(flatness, hn::Zero(d));
  if (hn::AllFalse(d, flat)) return base;
  const V8 fss90 = hn::Mul(half, rr);
  const V8 fss = hn::Mul(Lerp(one, fss90, fl), Lerp(one, fss90, fv));
  const V8 f_ss = hn::Mul(
      hn::Set(d, 1.25f),
      hn::Add(hn::Mul(fss, hn::Sub(hn::Div(one, hn::Add(cos_i, cos_o)), half)), half));
  return hn::IfThenElse(flat, Lerp(base, f_ss, flatness), base);
}

/// MicroMacroCompatible: m turned to wo's side of the macro surface (cos_o < 0: −m) has
/// wo·m > 0 and wi·m > 0 (reflect) or < 0 (refraction).
HWY_INLINE M8 MicroMacroCompatible(D8 d, V8 mx, V8 my, V8 mz, V8 ox, V8 oy, V8 oz, V8 ix, V8 iy,
                                   V8 iz, V8 cos_o, bool reflect) {
  const V8 zero = hn::Zero(d), minus = hn::Set(d, -1.0f);
  const M8 below = hn::Lt(cos_o, zero);
  const V8 sx = hn::IfThenElse(below, hn::Mul(mx, minus), mx);
  const V8 sy = hn::IfThenElse(below, hn::Mul(my, minus), my);
  const V8 sz = hn::IfThenElse(below, hn::Mul(mz, minus), mz);
  const V8 wi_m = Dot(ix, iy, iz, sx, sy, sz);
  return hn::And(hn::Gt(Dot(ox, oy, oz, sx, sy, sz), zero),
                 reflect ? hn::Gt(wi_m, zero) : hn::Lt(wi_m, zero));
}

/// PrincipledLobeProbabilities: [diffuse, clearcoat, transmission, reflection], normalised
/// (all 0 where their sum is not > 0).
struct Lobes8 {
  V8 diffuse, clearcoat, transmission, reflection;
};
HWY_INLINE Lobes8 LobeProbabilities(D8 d, const PrincipledLanes& p, M8 front, V8 f) {
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V8 one_m = hn::Sub(one, p.metallic);
  const V8 brdf = hn::Mul(one_m, hn::Sub(one, p.spec_trans));
  const V8 bsdf = hn::Mul(one_m, p.spec_trans);
  const V8 bsdf_t = hn::Mul(bsdf, hn::Sub(one, f));
  Lobes8 l;
  l.reflection = hn::IfThenElse(front, hn::Sub(one, bsdf_t), f);
  l.transmission = hn::IfThenElse(
      front, bsdf_t, hn::IfThenElseZero(hn::Gt(bsdf, zero), hn::Sub(one, f)));
  l.clearcoat = hn::IfThenElseZero(front, hn::Mul(hn::Set(d, 0.25f), p.clearcoat));
  l.diffuse = hn::IfThenElseZero(front, brdf);
  const V8 total =
      hn::Add(hn::Add(hn::Add(l.diffuse, l.clearcoat), l.transmission), l.reflection);
  const M8 pos = hn::Gt(total, zero);
  const V8 inv = hn::Div(one, total);
  l.diffuse = hn::IfThenElseZero(pos, hn::Mul(l.diffuse, inv));
  l.clearcoat = hn::IfThenElseZero(pos, hn::Mul(l.clearcoat, inv));
  l.transmission = hn::IfThenElseZero(pos, hn::Mul(l.transmission, inv));
  l.reflection = hn::IfThenElseZero(pos, hn::Mul(l.reflection, inv));
  return l;
}

/// PrincipledFresnel: the specular lobe's Fresnel colour for the dielectric term f at cos_i.
HWY_INLINE void SpecularFresnel(D8 d, const PrincipledLanes& p, V8 f, V8 cos_i, M8 front, V8* r,
                                V8* g, V8* b) {
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V8 one_m = hn::Sub(one, p.metallic);
  const V8 back = hn::Mul(f, hn::Mul(one_m, p.spec_trans));
  const V8 k = hn::Mul(f, hn::Mul(one_m, hn::Sub(one, p.spec_tint)));
  V8 rr = k, rg = k, rb = k;
  const V8 w = SchlickFresnelWeight(d, cos_i, p.eta);
  const M8 metal = hn::Gt(p.metallic, zero);
  if (!hn::AllFalse(d, metal)) {
    rr = AddIf(metal, rr, hn::Mul(Schlick(d, p.base_r, w), p.metallic));
    rg = AddIf(metal, rg, hn::Mul(Schlick(d, p.base_g, w), p.metallic));
    rb = AddIf(metal, rb, hn::Mul(Schlick(d, p.base_b, w), p.metallic));
  }
  const M8 tint = hn::Gt(p.spec_tint, zero);
  if (!hn::AllFalse(d, tint)) {
    const V8 eta_it = hn::IfThenElse(hn::Ge(cos_i, zero), p.eta, hn::Div(one, p.eta));
    const V8 r0 = SchlickR0(d, eta_it);
    V8 tr, tg, tb;
    TintColor(d, p, &tr, &tg, &tb);
    const V8 s = hn::Mul(one_m, p.spec_tint);
    rr = AddIf(tint, rr, hn::Mul(Schlick(d, hn::Mul(tr, r0), w), s));
    rg = AddIf(tint, rg, hn::Mul(Schlick(d, hn::Mul(tg, r0), w), s));
    rb = AddIf(tint, rb, hn::Mul(Schlick(d, hn::Mul(tb, r0), w), s));
  }
  *r = hn::IfThenElse(front, rr, back);
  *g = hn::IfThenElse(front, rg, back);
  *b = hn::IfThenElse(front, rb, back);
}

/// PrincipledEvalPdf: f(wo, wi) into *fr, *fg, *fb and the density of Sample (returned); both
/// 0 where the oracle returns 0.
HWY_INLINE V8 EvalPdf(D8 d, const PrincipledLanes& p, V8 ox, V8 oy, V8 oz, V8 ix, V8 iy, V8 iz,
                      V8* fr, V8* fg, V8* fb) {
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f), minus = hn::Set(d, -1.0f);
  const V8 cos_o = oz, cos_i = iz;
  const V8 oi = hn::Mul(cos_o, cos_i);
  const M8 reflect = hn::Gt(oi, zero), refract = hn::Lt(oi, zero);
  const M8 front = hn::Gt(cos_o, zero);
  const V8 eta_path = hn::IfThenElse(front, p.eta, hn::Div(one, p.eta));
  const V8 one_m = hn::Sub(one, p.metallic);
  const V8 brdf = hn::Mul(one_m, hn::Sub(one, p.spec_trans));
  const V8 bsdf = hn::Mul(one_m, p.spec_trans);
  const V8 abs_o = hn::Abs(cos_o), abs_i = hn::Abs(cos_i);
  // PrincipledHalfVector.
  const V8 k = hn::IfThenElse(reflect, one, eta_path);
  const V8 kx = hn::IfThenElse(reflect, ix, hn::Mul(ix, k)),
           ky = hn::IfThenElse(reflect, iy, hn::Mul(iy, k)),
           kz = hn::IfThenElse(reflect, iz, hn::Mul(iz, k));
  V8 hx = hn::Add(ox, kx), hy = hn::Add(oy, ky), hz = hn::Add(oz, kz);
  const V8 len2 = Dot(hx, hy, hz, hx, hy, hz);
  const M8 has_h = hn::And(hn::Or(reflect, refract),
                           hn::And(hn::Gt(len2, zero), hn::IsFinite(len2)));
  const V8 inv_len = hn::Div(one, hn::Sqrt(hn::IfThenElse(has_h, len2, one)));
  hx = hn::Mul(hx, inv_len), hy = hn::Mul(hy, inv_len), hz = hn::Mul(hz, inv_len);
  const M8 flip = hn::Lt(hz, zero);
  hx = hn::IfThenElse(flip, hn::Mul(hx, minus), hx);
  hy = hn::IfThenElse(flip, hn::Mul(hy, minus), hy);
  hz = hn::IfThenElse(flip, hn::Mul(hz, minus), hz);
  // Lanes without a half vector: a harmless +z (their results are zeroed below).
  hx = hn::IfThenElseZero(has_h, hx), hy = hn::IfThenElseZero(has_h, hy);
  hz = hn::IfThenElse(has_h, hz, one);
  const V8 wo_h = Dot(ox, oy, oz, hx, hy, hz), wi_h = Dot(ix, iy, iz, hx, hy, hz);
  V8 cos_t;
  const V8 fd = FresnelDielectric(d, wo_h, p.eta, &cos_t);
  const Lobes8 lobes = LobeProbabilities(d, p, front, fd);
  const M8 reflect_ok = hn::And(
      has_h,
      hn::And(reflect, MicroMacroCompatible(d, hx, hy, hz, ox, oy, oz, ix, iy, iz, cos_o, true)));
  const M8 refract_ok = hn::And(
      has_h,
      hn::And(refract, MicroMacroCompatible(d, hx, hy, hz, ox, oy, oz, ix, iy, iz, cos_o, false)));
  const V8 wux = hn::IfThenElse(front, ox, hn::Mul(ox, minus)),
           wuy = hn::IfThenElse(front, oy, hn::Mul(oy, minus)),
           wuz = hn::IfThenElse(front, oz, hn::Mul(oz, minus));
  const V8 denom = hn::Add(wo_h, hn::Mul(eta_path, wi_h));
  const V8 denom2 = hn::Mul(denom, denom);
  const V8 jacobian = hn::IfThenElse(
      reflect, hn::Abs(hn::Div(one, hn::Mul(hn::Set(d, 4.0f), wi_h))),
      hn::Abs(hn::Div(hn::Mul(hn::Mul(eta_path, eta_path), wi_h), denom2)));
  V8 r = zero, g = zero, b = zero, density = zero;
  const M8 micro = hn::Or(reflect_ok, refract_ok);
  const V8 dv = mf8::D(d, p.dist, hx, hy, hz);
  const V8 gv = hn::Mul(mf8::G1(d, p.dist, ox, oy, oz, hx, hy, hz),
                        mf8::G1(d, p.dist, ix, iy, iz, hx, hy, hz));
  const V8 pm = mf8::Pdf(d, p.dist, wux, wuy, wuz, hx, hy, hz);
  // The specular reflection.
  const M8 spec = hn::And(reflect_ok, hn::Gt(fd, zero));
  if (!hn::AllFalse(d, spec)) {
    V8 sr, sg, sb;
    SpecularFresnel(d, p, fd, wo_h, front, &sr, &sg, &sb);
    const V8 s = hn::Div(hn::Mul(dv, gv), hn::Mul(hn::Mul(hn::Set(d, 4.0f), abs_o), abs_i));
    r = AddIf(spec, r, hn::Mul(sr, s)), g = AddIf(spec, g, hn::Mul(sg, s));
    b = AddIf(spec, b, hn::Mul(sb, s));
  }
  // The specular transmission, tinted by √base.
  const M8 trans =
      hn::And(refract_ok, hn::And(hn::Gt(bsdf, zero), hn::Lt(fd, one)));
  if (!hn::AllFalse(d, trans)) {
    const V8 num = hn::Mul(hn::Mul(hn::Mul(hn::Mul(hn::Sub(one, fd), dv), gv), wo_h), wi_h);
    const V8 t = hn::Mul(bsdf, hn::Abs(hn::Div(num, hn::Mul(hn::Mul(abs_o, abs_i), denom2))));
    r = AddIf(trans, r, hn::Mul(hn::Sqrt(p.base_r), t));
    g = AddIf(trans, g, hn::Mul(hn::Sqrt(p.base_g), t));
    b = AddIf(trans, b, hn::Mul(hn::Sqrt(p.base_b), t));
  }
  density = AddIf(micro, density,
                  hn::Mul(hn::Mul(hn::IfThenElse(reflect_ok, lobes.reflection, lobes.transmission),
                                  pm),
                          jacobian));
  // The clearcoat.
  const M8 coat = hn::And(reflect_ok, front);
  if (!hn::AllFalse(d, coat)) {
    const V8 alpha_cc = ClearcoatAlpha(d, p.clearcoat_gloss);
    const M8 has_cc = hn::And(coat, hn::Gt(p.clearcoat, zero));
    if (!hn::AllFalse(d, has_cc)) {
      const V8 fcc = Schlick(d, hn::Set(d, 0.04f), SchlickFresnelWeight(d, wo_h, p.eta));
      const V8 v = hn::Mul(
          hn::Mul(hn::Mul(hn::Mul(hn::Set(d, 0.25f), p.clearcoat), fcc), Gtr1D(d, alpha_cc, hz)),
          ClearcoatG(d, ox, oy, oz, ix, iy, iz, hx, hy, hz));
      r = AddIf(has_cc, r, v), g = AddIf(has_cc, g, v), b = AddIf(has_cc, b, v);
    }
    density = AddIf(coat, density,
                    hn::Mul(hn::Mul(lobes.clearcoat, Gtr1Pdf(d, alpha_cc, hz)), jacobian));
  }
  // The diffuse base and the sheen.
  const M8 base = hn::And(has_h, hn::And(reflect, front));
  if (!hn::AllFalse(d, base)) {
    const V8 cos_pdf = hn::IfThenElseZero(hn::Gt(iz, zero), hn::Mul(iz, hn::Set(d, kInvPi)));
    density = AddIf(base, density, hn::Mul(lobes.diffuse, cos_pdf));
    const M8 diffuse = hn::And(base, hn::Gt(brdf, zero));
    if (!hn::AllFalse(d, diffuse)) {
      const V8 cos_d = wi_h;
      const V8 s = hn::Mul(hn::Mul(brdf, hn::Set(d, kInvPi)),
                           DiffuseFactor(d, p.roughness, p.flatness, abs_o, abs_i, cos_d));
      r = AddIf(diffuse, r, hn::Mul(p.base_r, s));
      g = AddIf(diffuse, g, hn::Mul(p.base_g, s));
      b = AddIf(diffuse, b, hn::Mul(p.base_b, s));
      const M8 sheen =
          hn::And(diffuse, hn::And(hn::Gt(p.sheen, zero), hn::Lt(p.metallic, one)));
      if (!hn::AllFalse(d, sheen)) {
        const V8 v = hn::Mul(hn::Mul(p.sheen, one_m), SchlickWeight(d, hn::Abs(cos_d)));
        V8 tr, tg, tb;
        TintColor(d, p, &tr, &tg, &tb);
        const M8 tinted = hn::Gt(p.sheen_tint, zero);
        const V8 cr = hn::IfThenElse(tinted, Lerp(one, tr, p.sheen_tint), one);
        const V8 cg = hn::IfThenElse(tinted, Lerp(one, tg, p.sheen_tint), one);
        const V8 cb = hn::IfThenElse(tinted, Lerp(one, tb, p.sheen_tint), one);
        r = AddIf(sheen, r, hn::Mul(cr, v)), g = AddIf(sheen, g, hn::Mul(cg, v));
        b = AddIf(sheen, b, hn::Mul(cb, v));
      }
    }
  }
  const M8 ok = hn::And(AllFinite3(d, r, g, b), hn::IsFinite(density));
  *fr = hn::IfThenElseZero(ok, r), *fg = hn::IfThenElseZero(ok, g),
  *fb = hn::IfThenElseZero(ok, b);
  return hn::IfThenElseZero(ok, density);
}

}  // namespace pr8
}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_PRINCIPLED_LOBES8_INL_H_
