// Per-target 8-wide twin of Mitsuba's `principledthin` (engine/bsdf/principled_thin.h), part of
// simd/wavefront/bsdf8-inl.h through principled8-inl.h: it uses the principled lobes of
// principled_lobes8-inl.h, bsdf8-inl.h's Fresnel kernel and cosine warp and microfacet8-inl.h's
// GGX kernels. The oracle's operations in its order; only hwy's Sin/Cos (the GGX and cosine
// samplers) round differently from libm.

#if defined(PTLAB_SIMD_PRINCIPLED_THIN8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_PRINCIPLED_THIN8_INL_H_
#undef PTLAB_SIMD_PRINCIPLED_THIN8_INL_H_
#else
#define PTLAB_SIMD_PRINCIPLED_THIN8_INL_H_
#endif

#include "hwy/highway.h"
#include "simd/wavefront/principled_lobes8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {
namespace pr8 {

/// ThinLobeProbabilities: [reflection, transmission, diffuse, diffuse transmission].
struct ThinLobes8 {
  V8 reflection, transmission, diffuse, diffuse_transmission;
};
HWY_INLINE ThinLobes8 ThinLobeProbabilities(D8 d, const PrincipledLanes& p) {
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f), half = hn::Set(d, 0.5f);
  const V8 one_st = hn::Sub(one, p.spec_trans);
  ThinLobes8 l;
  l.reflection = hn::Mul(half, p.spec_trans);
  l.transmission = hn::Mul(half, p.spec_trans);
  l.diffuse = hn::Mul(one_st, hn::Sub(one, p.diff_trans));
  l.diffuse_transmission = hn::Mul(one_st, p.diff_trans);
  const V8 total = hn::Add(hn::Add(hn::Add(l.reflection, l.transmission), l.diffuse),
                           l.diffuse_transmission);
  const M8 pos = hn::Gt(total, zero);
  const V8 inv = hn::Div(one, total);
  l.reflection = hn::IfThenElseZero(pos, hn::Mul(l.reflection, inv));
  l.transmission = hn::IfThenElseZero(pos, hn::Mul(l.transmission, inv));
  l.diffuse = hn::IfThenElseZero(pos, hn::Mul(l.diffuse, inv));
  l.diffuse_transmission = hn::IfThenElseZero(pos, hn::Mul(l.diffuse_transmission, inv));
  return l;
}

/// ThinTransmissionDistribution: roughness scaled by 0.65 η − 0.35.
HWY_INLINE mf8::Dist8 ThinTransmissionDistribution(D8 d, const PrincipledLanes& p) {
  const V8 k = hn::Sub(hn::Mul(hn::Set(d, 0.65f), p.eta), hn::Set(d, 0.35f));
  return Distribution(d, hn::Mul(k, p.roughness), p.anisotropic);
}

/// PrincipledThinEvalPdf: f(wo, wi) into *fr, *fg, *fb and the density (returned).
HWY_INLINE V8 ThinEvalPdf(D8 d, const PrincipledLanes& p, V8 ox, V8 oy, V8 oz, V8 ix, V8 iy,
                          V8 iz, V8* fr, V8* fg, V8* fb) {
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f), minus = hn::Set(d, -1.0f),
           four = hn::Set(d, 4.0f), inv_pi = hn::Set(d, kInvPi);
  const M8 flip = hn::Lt(oz, zero);
  const V8 vx = hn::IfThenElse(flip, hn::Mul(ox, minus), ox),
           vy = hn::IfThenElse(flip, hn::Mul(oy, minus), oy),
           vz = hn::IfThenElse(flip, hn::Mul(oz, minus), oz);
  const V8 lx = hn::IfThenElse(flip, hn::Mul(ix, minus), ix),
           ly = hn::IfThenElse(flip, hn::Mul(iy, minus), iy),
           lz = hn::IfThenElse(flip, hn::Mul(iz, minus), iz);
  const M8 reflect = hn::Gt(lz, zero), refract = hn::Lt(lz, zero);
  const V8 cos_o = vz, abs_i = hn::Abs(lz);
  V8 hx = hn::Add(vx, lx), hy = hn::Add(vy, ly), hz = hn::Add(vz, abs_i);
  const V8 len2 = Dot(hx, hy, hz, hx, hy, hz);
  const M8 valid = hn::And(hn::And(hn::Ne(oz, zero), hn::IsFinite(oz)),
                           hn::And(hn::Or(reflect, refract),
                                   hn::And(hn::Gt(len2, zero), hn::IsFinite(len2))));
  const V8 inv_len = hn::Div(one, hn::Sqrt(hn::IfThenElse(valid, len2, one)));
  hx = hn::IfThenElseZero(valid, hn::Mul(hx, inv_len));
  hy = hn::IfThenElseZero(valid, hn::Mul(hy, inv_len));
  hz = hn::IfThenElse(valid, hn::Mul(hz, inv_len), one);
  const ThinLobes8 lobes = ThinLobeProbabilities(d, p);
  const V8 st = p.spec_trans, dt = p.diff_trans;
  const V8 one_st = hn::Sub(one, st), one_dt = hn::Sub(one, dt);
  V8 r = zero, g = zero, b = zero, density = zero;
  const M8 spec = hn::And(valid, hn::Gt(st, zero));
  if (!hn::AllFalse(d, spec)) {
    const V8 jacobian = hn::Abs(hn::Div(one, hn::Mul(four, Dot(lx, ly, abs_i, hx, hy, hz))));
    const V8 v_h = Dot(vx, vy, vz, hx, hy, hz);
    V8 cos_t;
    const V8 fd = FresnelDielectric(d, v_h, p.eta, &cos_t);
    const V8 den = hn::Mul(hn::Mul(four, cos_o), abs_i);
    const M8 refl = hn::And(
        spec, hn::And(reflect, MicroMacroCompatible(d, hx, hy, hz, vx, vy, vz, lx, ly, lz, cos_o,
                                                    true)));
    if (!hn::AllFalse(d, refl)) {
      V8 cr = fd, cg = fd, cb = fd;
      const M8 tint = hn::Gt(p.spec_tint, zero);
      if (!hn::AllFalse(d, tint)) {
        V8 tr, tg, tb;
        TintColor(d, p, &tr, &tg, &tb);
        const V8 r0 = SchlickR0(d, p.eta), w = SchlickFresnelWeight(d, v_h, p.eta);
        cr = hn::IfThenElse(tint, Lerp(cr, Schlick(d, hn::Mul(tr, r0), w), p.spec_tint), cr);
        cg = hn::IfThenElse(tint, Lerp(cg, Schlick(d, hn::Mul(tg, r0), w), p.spec_tint), cg);
        cb = hn::IfThenElse(tint, Lerp(cb, Schlick(d, hn::Mul(tb, r0), w), p.spec_tint), cb);
      }
      const V8 dg = hn::Mul(mf8::D(d, p.dist, hx, hy, hz),
                            hn::Mul(mf8::G1(d, p.dist, vx, vy, vz, hx, hy, hz),
                                    mf8::G1(d, p.dist, lx, ly, lz, hx, hy, hz)));
      const V8 s = hn::Div(hn::Mul(st, dg), den);
      r = AddIf(refl, r, hn::Mul(cr, s)), g = AddIf(refl, g, hn::Mul(cg, s));
      b = AddIf(refl, b, hn::Mul(cb, s));
      density = AddIf(refl, density,
                      hn::Mul(hn::Mul(lobes.reflection, mf8::Pdf(d, p.dist, vx, vy, vz, hx, hy, hz)),
                              jacobian));
    }
    const M8 trans = hn::And(
        spec, hn::And(refract, MicroMacroCompatible(d, hx, hy, hz, vx, vy, vz, lx, ly, lz, cos_o,
                                                    false)));
    if (!hn::AllFalse(d, trans)) {
      const mf8::Dist8 dist = ThinTransmissionDistribution(d, p);
      const V8 dg = hn::Mul(mf8::D(d, dist, hx, hy, hz),
                            hn::Mul(mf8::G1(d, dist, vx, vy, vz, hx, hy, hz),
                                    mf8::G1(d, dist, lx, ly, lz, hx, hy, hz)));
      const V8 s = hn::Div(hn::Mul(hn::Mul(st, hn::Sub(one, fd)), dg), den);
      r = AddIf(trans, r, hn::Mul(p.base_r, s)), g = AddIf(trans, g, hn::Mul(p.base_g, s));
      b = AddIf(trans, b, hn::Mul(p.base_b, s));
      density = AddIf(trans, density,
                      hn::Mul(hn::Mul(lobes.transmission, mf8::Pdf(d, dist, vx, vy, vz, hx, hy, hz)),
                              jacobian));
    }
  }
  // The diffuse reflection (and sheen) above, the diffuse transmission below.
  const M8 up = hn::And(valid, reflect), down = hn::And(valid, refract);
  density = AddIf(up, density, hn::Mul(lobes.diffuse, hn::Mul(lz, inv_pi)));
  const M8 diffuse = hn::And(up, hn::And(hn::Lt(st, one), hn::Lt(dt, one)));
  if (!hn::AllFalse(d, diffuse)) {
    const V8 cos_d = Dot(hx, hy, hz, lx, ly, lz);
    const V8 s = hn::Mul(hn::Mul(hn::Mul(one_st, inv_pi), one_dt),
                         DiffuseFactor(d, p.roughness, p.flatness, cos_o, abs_i, cos_d));
    r = AddIf(diffuse, r, hn::Mul(p.base_r, s)), g = AddIf(diffuse, g, hn::Mul(p.base_g, s));
    b = AddIf(diffuse, b, hn::Mul(p.base_b, s));
    const M8 sheen = hn::And(diffuse, hn::Gt(p.sheen, zero));
    if (!hn::AllFalse(d, sheen)) {
      const V8 v = hn::Mul(hn::Mul(hn::Mul(p.sheen, one_st), SchlickWeight(d, hn::Abs(cos_d))),
                           one_dt);
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
  density = AddIf(down, density, hn::Mul(lobes.diffuse_transmission, hn::Mul(abs_i, inv_pi)));
  const M8 dtrans = hn::And(down, hn::And(hn::Lt(st, one), hn::Gt(dt, zero)));
  const V8 t = hn::Mul(hn::Mul(one_st, dt), inv_pi);
  r = AddIf(dtrans, r, hn::Mul(p.base_r, t)), g = AddIf(dtrans, g, hn::Mul(p.base_g, t));
  b = AddIf(dtrans, b, hn::Mul(p.base_b, t));
  const M8 ok = hn::And(valid, hn::And(AllFinite3(d, r, g, b), hn::IsFinite(density)));
  *fr = hn::IfThenElseZero(ok, r), *fg = hn::IfThenElseZero(ok, g),
  *fb = hn::IfThenElseZero(ok, b);
  return hn::IfThenElseZero(ok, density);
}

/// PrincipledThinSample for one block: sets the sample's direction *ix, *iy, *iz and returns
/// the lanes where the oracle's sampler gets that far (before its evaluation).
HWY_INLINE M8 ThinSampleDirection(D8 d, const PrincipledLanes& p, V8 ox, V8 oy, V8 oz,
                                  V8 u_lobe, V8 ux, V8 uy, V8* ix, V8* iy, V8* iz) {
  const V8 zero = hn::Zero(d), minus = hn::Set(d, -1.0f);
  const M8 flip = hn::Lt(oz, zero);
  const V8 vx = hn::IfThenElse(flip, hn::Mul(ox, minus), ox),
           vy = hn::IfThenElse(flip, hn::Mul(oy, minus), oy),
           vz = hn::IfThenElse(flip, hn::Mul(oz, minus), oz);
  const ThinLobes8 lobes = ThinLobeProbabilities(d, p);
  const V8 c_spec = hn::Add(lobes.reflection, lobes.transmission);
  const M8 specular = hn::Lt(u_lobe, c_spec);
  M8 ok = hn::And(hn::Ne(oz, zero), hn::IsFinite(oz));
  V8 lx = zero, ly = zero, lz = zero;
  if (!hn::AllFalse(d, specular)) {
    const M8 refl = hn::Lt(u_lobe, lobes.reflection);
    const mf8::Dist8 dt = ThinTransmissionDistribution(d, p);
    mf8::Dist8 dist = p.dist;
    dist.au = hn::IfThenElse(refl, p.dist.au, dt.au);
    dist.av = hn::IfThenElse(refl, p.dist.av, dt.av);
    V8 mx, my, mz, pm;
    mf8::Sample(d, dist, vx, vy, vz, ux, uy, &mx, &my, &mz, &pm);
    const V8 two_v_m = hn::Mul(hn::Set(d, 2.0f), Dot(vx, vy, vz, mx, my, mz));
    lx = hn::Sub(hn::Mul(mx, two_v_m), vx), ly = hn::Sub(hn::Mul(my, two_v_m), vy);
    const V8 rz = hn::Sub(hn::Mul(mz, two_v_m), vz);
    lz = hn::IfThenElse(refl, rz, hn::Neg(rz));
    const M8 side = hn::Or(hn::And(refl, hn::Gt(lz, zero)), hn::AndNot(refl, hn::Lt(lz, zero)));
    const M8 mmc_r = MicroMacroCompatible(d, mx, my, mz, vx, vy, vz, lx, ly, lz, vz, true);
    const M8 mmc_t = MicroMacroCompatible(d, mx, my, mz, vx, vy, vz, lx, ly, lz, vz, false);
    const M8 spec_ok = hn::And(hn::And(hn::Gt(pm, zero), side),
                               hn::Or(hn::And(refl, mmc_r), hn::AndNot(refl, mmc_t)));
    ok = hn::And(ok, hn::Or(hn::Not(specular), spec_ok));
  }
  if (!hn::AllTrue(d, specular)) {
    V8 cx, cy, cz;
    SampleCosineHemisphere(d, ux, uy, &cx, &cy, &cz);
    const M8 below = hn::Not(hn::Lt(u_lobe, hn::Add(c_spec, lobes.diffuse)));
    cz = hn::IfThenElse(below, hn::Neg(cz), cz);
    lx = hn::IfThenElse(specular, lx, cx), ly = hn::IfThenElse(specular, ly, cy);
    lz = hn::IfThenElse(specular, lz, cz);
    ok = hn::And(ok, hn::Or(specular, hn::Ne(cz, zero)));
  }
  *ix = hn::IfThenElse(flip, hn::Mul(lx, minus), lx);
  *iy = hn::IfThenElse(flip, hn::Mul(ly, minus), ly);
  *iz = hn::IfThenElse(flip, hn::Mul(lz, minus), lz);
  return hn::And(ok, AllFinite3(d, *ix, *iy, *iz));
}

}  // namespace pr8
}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_PRINCIPLED_THIN8_INL_H_
