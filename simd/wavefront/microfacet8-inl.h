// Per-target 8-wide twins of engine/bsdf/erf.h and engine/bsdf/microfacet.h (re-included once
// per Highway target): D, G1/cos, the visible-normal and D cos θ samplers, the pdf, with the
// distribution type, roughness and sampling mode per lane.

#if defined(PTLAB_SIMD_MICROFACET8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_MICROFACET8_INL_H_
#undef PTLAB_SIMD_MICROFACET8_INL_H_
#else
#define PTLAB_SIMD_MICROFACET8_INL_H_
#endif

#include "engine/bsdf/erf.h"
#include "engine/bsdf/microfacet.h"
#include "hwy/contrib/math/math-inl.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {
namespace mf8 {

namespace hn = hwy::HWY_NAMESPACE;
using D8 = hn::CappedTag<float, 8>;
using V8 = hn::Vec<D8>;
using M8 = hn::Mask<D8>;

// The operations repeat the scalar oracle's in order (the project builds with
// -ffp-contract=off, so neither side fuses). hwy::Exp / Log / Sin / Cos convert their
// argument to an integer before range checks, which is undefined for NaN and ±∞ on the EMU128
// target: every argument is made finite first (the oracle's libm gives the same value there).

/// max(x, −200) with NaN → −200: an argument for hwy::Exp (exp(−200) = 0 in float).
HWY_INLINE V8 ExpArg(D8 d, V8 x) {
  const V8 low = hn::Set(d, -200.0f);
  return hn::IfThenElse(hn::Ge(x, low), x, low);
}

/// ErfApprox (engine/bsdf/erf.h); *e (when non-null) receives its exp(−x²), which callers
/// that need e^(−x²) themselves take instead of a second Exp (the same bits: (−x)² = x²).
HWY_INLINE V8 Erf(D8 d, V8 x, V8* e = nullptr) {
  const V8 a = hn::Abs(x), one = hn::Set(d, 1.0f);
  const V8 t = hn::Div(one, hn::Add(one, hn::Mul(hn::Set(d, 0.3275911f), a)));
  V8 p = hn::Add(hn::Set(d, -1.453152027f), hn::Mul(t, hn::Set(d, 1.061405429f)));
  p = hn::Add(hn::Set(d, 1.421413741f), hn::Mul(t, p));
  p = hn::Add(hn::Set(d, -0.284496736f), hn::Mul(t, p));
  p = hn::Add(hn::Set(d, 0.254829592f), hn::Mul(t, p));
  p = hn::Mul(t, p);
  const V8 exp_a2 = hn::Exp(d, ExpArg(d, hn::Neg(hn::Mul(a, a))));
  if (e != nullptr) *e = exp_a2;
  const V8 r = hn::Sub(one, hn::Mul(p, exp_a2));
  return hn::CopySign(r, x);
}

/// ErfInvApprox's central branch (w < 5) before the product with x.
HWY_INLINE V8 ErfInvCentral(D8 d, V8 w) {
  const V8 w1 = hn::Sub(w, hn::Set(d, 2.5f));
  V8 p = hn::Set(d, 2.81022636e-08f);
  p = hn::Add(hn::Set(d, 3.43273939e-07f), hn::Mul(p, w1));
  p = hn::Add(hn::Set(d, -3.5233877e-06f), hn::Mul(p, w1));
  p = hn::Add(hn::Set(d, -4.39150654e-06f), hn::Mul(p, w1));
  p = hn::Add(hn::Set(d, 0.00021858087f), hn::Mul(p, w1));
  p = hn::Add(hn::Set(d, -0.00125372503f), hn::Mul(p, w1));
  p = hn::Add(hn::Set(d, -0.00417768164f), hn::Mul(p, w1));
  p = hn::Add(hn::Set(d, 0.246640727f), hn::Mul(p, w1));
  p = hn::Add(hn::Set(d, 1.50140941f), hn::Mul(p, w1));
  return p;
}

/// ErfInvApprox's tail branch (w ≥ 5) before the product with x.
HWY_INLINE V8 ErfInvTail(D8 d, V8 w) {
  const V8 w2 = hn::Sub(hn::Sqrt(w), hn::Set(d, 3.0f));
  V8 q = hn::Set(d, -0.000200214257f);
  q = hn::Add(hn::Set(d, 0.000100950558f), hn::Mul(q, w2));
  q = hn::Add(hn::Set(d, 0.00134934322f), hn::Mul(q, w2));
  q = hn::Add(hn::Set(d, -0.00367342844f), hn::Mul(q, w2));
  q = hn::Add(hn::Set(d, 0.00573950773f), hn::Mul(q, w2));
  q = hn::Add(hn::Set(d, -0.0076224613f), hn::Mul(q, w2));
  q = hn::Add(hn::Set(d, 0.00943887047f), hn::Mul(q, w2));
  q = hn::Add(hn::Set(d, 1.00167406f), hn::Mul(q, w2));
  q = hn::Add(hn::Set(d, 2.83297682f), hn::Mul(q, w2));
  return q;
}

/// ErfInvApprox (engine/bsdf/erf.h): Giles's branch selected per lane.
HWY_INLINE V8 ErfInv(D8 d, V8 x) {
  const V8 one = hn::Set(d, 1.0f), hi = hn::Set(d, kErfInvMaxArg), lo = hn::Neg(hi);
  x = hn::IfThenElse(hn::Gt(x, lo), hn::Min(x, hi), lo);
  const V8 w = hn::Neg(hn::Log(d, hn::Mul(hn::Sub(one, x), hn::Add(one, x))));
  // Giles's branches, each only where some lane takes it (the tail one, |x| ≳ 0.9966, seldom).
  const M8 central = hn::Lt(w, hn::Set(d, 5.0f));
  V8 p = hn::Zero(d), q = p;
  if (!hn::AllFalse(d, central)) p = ErfInvCentral(d, w);
  if (!hn::AllTrue(d, central)) q = ErfInvTail(d, w);
  return hn::Mul(hn::IfThenElse(central, p, q), x);
}

/// One block's distributions: GGX lanes, visible-sampling lanes, αu, αv (clamped).
struct Dist8 {
  M8 ggx, visible;
  V8 au, av;
};

/// ClampMicrofacetAlpha.
HWY_INLINE V8 ClampAlpha(D8 d, V8 alpha) {
  const V8 lo = hn::Set(d, kMicrofacetMinAlpha);
  return hn::IfThenElse(hn::Gt(alpha, lo), hn::Min(alpha, hn::Set(d, kMicrofacetMaxAlpha)), lo);
}

/// MicrofacetD for unit m.
HWY_INLINE V8 D(D8 d, const Dist8& f, V8 mx, V8 my, V8 mz) {
  const V8 zero = hn::Zero(d);
  const V8 x = hn::Div(mx, f.au), y = hn::Div(my, f.av), z2 = hn::Mul(mz, mz);
  const V8 xy = hn::Add(hn::Mul(x, x), hn::Mul(y, y));
  const V8 pa = hn::Mul(hn::Mul(hn::Set(d, kPi), f.au), f.av);
  V8 r = zero;
  if (!hn::AllTrue(d, f.ggx)) {
    const V8 e = hn::Exp(d, ExpArg(d, hn::Div(hn::Neg(xy), z2)));
    r = hn::Div(e, hn::Mul(pa, hn::Mul(z2, z2)));
  }
  if (!hn::AllFalse(d, f.ggx)) {
    const V8 t = hn::Add(xy, z2);
    r = hn::IfThenElse(f.ggx, hn::Div(hn::Set(d, 1.0f), hn::Mul(pa, hn::Mul(t, t))), r);
  }
  const M8 ok = hn::And(hn::Gt(mz, zero),
                        hn::And(hn::Gt(hn::Mul(r, mz), hn::Set(d, 1e-20f)), hn::IsFinite(r)));
  return hn::IfThenElseZero(ok, r);
}

/// MicrofacetG1OverCos.
HWY_INLINE V8 G1OverCos(D8 d, const Dist8& f, V8 vx, V8 vy, V8 vz) {
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f), two = hn::Set(d, 2.0f);
  const V8 ax = hn::Mul(f.au, vx), ay = hn::Mul(f.av, vy);
  const V8 s2 = hn::Add(hn::Mul(ax, ax), hn::Mul(ay, ay)), z = hn::Abs(vz);
  V8 r = zero;
  if (!hn::AllTrue(d, f.ggx)) {
    const M8 tilted = hn::Gt(s2, zero);
    const V8 s = hn::Sqrt(s2);
    const V8 a = hn::IfThenElseZero(tilted, hn::Div(z, s));
    V8 exp_a2;  // e^(−a²), from the Erf
    const V8 erf_a = Erf(d, a, &exp_a2);
    const V8 den = hn::Add(hn::Mul(z, hn::Add(one, erf_a)),
                           hn::Mul(hn::Mul(s, hn::Set(d, kInvSqrtPi)), exp_a2));
    r = hn::IfThenElse(tilted, hn::Div(two, den), hn::Div(one, z));
  }
  if (!hn::AllFalse(d, f.ggx)) {
    r = hn::IfThenElse(f.ggx, hn::Div(two, hn::Add(z, hn::Sqrt(hn::Add(hn::Mul(z, z), s2)))), r);
  }
  return hn::IfThenElseZero(hn::IsFinite(r), r);
}

/// MicrofacetG1: |v.z| G1OverCos capped at 1, 0 unless (v·m) v.z > 0. g1_over_cos, when
/// non-null, is G1OverCos(d, f, v) computed already (for v or −v: the same bits).
HWY_INLINE V8 G1(D8 d, const Dist8& f, V8 vx, V8 vy, V8 vz, V8 mx, V8 my, V8 mz,
                 const V8* g1_over_cos = nullptr) {
  const V8 vm = hn::Add(hn::Add(hn::Mul(vx, mx), hn::Mul(vy, my)), hn::Mul(vz, mz));
  const V8 goc = g1_over_cos != nullptr ? *g1_over_cos : G1OverCos(d, f, vx, vy, vz);
  const V8 g = hn::Min(hn::Mul(hn::Abs(vz), goc), hn::Set(d, 1.0f));
  return hn::IfThenElseZero(hn::Gt(hn::Mul(vm, vz), hn::Zero(d)), g);
}

/// MicrofacetPdf (w.z > 0 lanes; 0 elsewhere). g1_w and d_m, when non-null, are G1OverCos(d,
/// f, w) and D(d, f, m) computed already by the caller (the same operations: the same bits).
HWY_INLINE V8 Pdf(D8 d, const Dist8& f, V8 wx, V8 wy, V8 wz, V8 mx, V8 my, V8 mz,
                  const V8* g1_w = nullptr, const V8* d_m = nullptr) {
  const V8 zero = hn::Zero(d);
  const V8 dm = d_m != nullptr ? *d_m : D(d, f, mx, my, mz);
  const V8 wm = hn::Add(hn::Add(hn::Mul(wx, mx), hn::Mul(wy, my)), hn::Mul(wz, mz));
  const V8 g1 = g1_w != nullptr ? *g1_w : G1OverCos(d, f, wx, wy, wz);
  const V8 vis = hn::Mul(hn::Mul(dm, g1), wm);
  V8 p = hn::IfThenElse(f.visible, hn::IfThenElseZero(hn::Gt(wm, zero), vis), hn::Mul(dm, mz));
  p = hn::IfThenElseZero(hn::And(hn::Gt(wz, zero), hn::IsFinite(p)), p);
  return p;
}

/// ClampMicrofacetSample.
HWY_INLINE V8 ClampU(D8 d, V8 u) {
  return hn::IfThenElseZero(hn::Gt(u, hn::Zero(d)), hn::Min(u, hn::Set(d, kOneMinusEpsilon)));
}

/// x / √(x² + y² + z²) etc. as Normalize does (times the reciprocal of the length).
HWY_INLINE void Normalize3(D8 d, V8* x, V8* y, V8* z) {
  const V8 len = hn::Sqrt(hn::Add(hn::Add(hn::Mul(*x, *x), hn::Mul(*y, *y)), hn::Mul(*z, *z)));
  const V8 inv = hn::Div(hn::Set(d, 1.0f), len);
  *x = hn::Mul(*x, inv), *y = hn::Mul(*y, inv), *z = hn::Mul(*z, inv);
}

/// SampleBeckmannVisibleSlope.
HWY_INLINE void BeckmannVisibleSlope(D8 d, V8 cos_t, V8 u_x, V8 u_y, V8* sx, V8* sy) {
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f), lo = hn::Set(d, 1e-6f),
           hi = hn::Set(d, 1.0f - 1e-6f), isp = hn::Set(d, kInvSqrtPi);
  const V8 ux = hn::Min(hn::Max(u_x, lo), hi), uy = hn::Min(hn::Max(u_y, lo), hi);
  const V8 sin_t = hn::Sqrt(hn::Max(zero, hn::Mul(hn::Sub(one, cos_t), hn::Add(one, cos_t))));
  const V8 tan_t = hn::Div(sin_t, cos_t);
  const M8 tilted = hn::Gt(tan_t, zero);
  // cot = ∞ at normal incidence; erf(∞) = 1 and the tail is 0 there, as in the oracle.
  const V8 cot_t = hn::IfThenElse(tilted, hn::Div(cos_t, sin_t), hn::Set(d, 1e30f));
  V8 exp_cot2;  // e^(−cot²), from the Erf
  const V8 max_x = Erf(d, cot_t, &exp_cot2);
  const V8 tail = hn::IfThenElseZero(tilted, hn::Mul(hn::Mul(tan_t, isp), exp_cot2));
  const V8 target = hn::Mul(ux, hn::Add(hn::Add(one, max_x), tail));
  V8 x = hn::Sub(max_x, hn::Mul(hn::Add(max_x, one), Erf(d, hn::Sqrt(hn::Neg(hn::Log(d, ux))))));
  for (int i = 0; i < 3; ++i) {
    const V8 slope = ErfInv(d, x);
    const V8 value = hn::Sub(
        hn::Add(hn::Add(one, x), hn::Mul(hn::Mul(tan_t, isp),
                                         hn::Exp(d, ExpArg(d, hn::Neg(hn::Mul(slope, slope)))))),
        target);
    const V8 derivative = hn::Sub(one, hn::Mul(slope, tan_t));
    x = hn::Sub(x, hn::Div(value, derivative));
  }
  *sx = ErfInv(d, x);
  *sy = ErfInv(d, hn::Sub(hn::Mul(hn::Set(d, 2.0f), uy), one));
}

/// SampleMicrofacet: sets m and *pdf (0 and m = +z where the oracle returns those). g1_w, when
/// non-null, is G1OverCos(d, f, w) computed already (Pdf's).
HWY_INLINE void Sample(D8 d, const Dist8& f, V8 wx, V8 wy, V8 wz, V8 u_x, V8 u_y, V8* mx, V8* my,
                       V8* mz, V8* pdf, const V8* g1_w = nullptr) {
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f), two_pi = hn::Set(d, 2.0f * kPi);
  V8 x = zero, y = zero, z = one;
  if (!hn::AllTrue(d, f.visible)) {
    const V8 u1 = ClampU(d, u_x), phi = hn::Mul(two_pi, ClampU(d, u_y));
    const V8 c = hn::Cos(d, phi), s = hn::Sin(d, phi);
    const V8 ac = hn::Mul(f.au, c), as = hn::Mul(f.av, s);
    const V8 a2 = hn::Add(hn::Mul(ac, ac), hn::Mul(as, as));
    const V8 inv_a = hn::Div(one, hn::Sqrt(a2));
    const V8 tan2_b = hn::Mul(hn::Neg(a2), hn::Log1p(d, hn::Neg(u1)));
    const V8 tan2_g = hn::Div(hn::Mul(a2, u1), hn::Sub(one, u1));
    const V8 tan2 = hn::IfThenElse(f.ggx, tan2_g, tan2_b);
    const V8 cos_t = hn::Div(one, hn::Sqrt(hn::Add(one, tan2)));
    const V8 sin_t = hn::Mul(hn::Sqrt(tan2), cos_t);
    x = hn::Mul(hn::Mul(sin_t, ac), inv_a);
    y = hn::Mul(hn::Mul(sin_t, as), inv_a);
    z = cos_t;
  }
  if (!hn::AllFalse(d, f.visible)) {
    V8 vx = hn::Mul(f.au, wx), vy = hn::Mul(f.av, wy), vz = wz;
    Normalize3(d, &vx, &vy, &vz);
    const V8 r2 = hn::Add(hn::Mul(vx, vx), hn::Mul(vy, vy));
    const M8 tilted = hn::Gt(r2, zero);
    const V8 inv_r = hn::IfThenElseZero(tilted, hn::Div(one, hn::Sqrt(r2)));
    const M8 vis_ggx = hn::And(f.visible, f.ggx), vis_beck = hn::AndNot(f.ggx, f.visible);
    V8 gx = zero, gy = zero, gz = one;
    if (!hn::AllFalse(d, vis_ggx)) {
      // Heitz 2018, as SampleMicrofacet.
      const V8 t1x = hn::IfThenElse(tilted, hn::Mul(hn::Neg(vy), inv_r), one);
      const V8 t1y = hn::IfThenElseZero(tilted, hn::Mul(vx, inv_r));
      // t2 = v × t1 with t1.z = 0.
      const V8 t2x = hn::Sub(hn::Mul(vy, zero), hn::Mul(vz, t1y));
      const V8 t2y = hn::Sub(hn::Mul(vz, t1x), hn::Mul(vx, zero));
      const V8 t2z = hn::Sub(hn::Mul(vx, t1y), hn::Mul(vy, t1x));
      const V8 r = hn::Sqrt(ClampU(d, u_x));
      const V8 phi = hn::Mul(two_pi, ClampU(d, u_y));
      const V8 p1 = hn::Mul(r, hn::Cos(d, phi));
      const V8 s = hn::Mul(hn::Set(d, 0.5f), hn::Add(one, vz));
      const V8 p2 =
          hn::Add(hn::Mul(hn::Sub(one, s), hn::Sqrt(hn::Max(zero, hn::Sub(one, hn::Mul(p1, p1))))),
                  hn::Mul(s, hn::Mul(r, hn::Sin(d, phi))));
      const V8 pz =
          hn::Sqrt(hn::Max(zero, hn::Sub(hn::Sub(one, hn::Mul(p1, p1)), hn::Mul(p2, p2))));
      // nh = t1 p1 + t2 p2 + v pz, summed as the oracle's Vec3f operators do.
      const V8 nx = hn::Add(hn::Add(hn::Mul(t1x, p1), hn::Mul(t2x, p2)), hn::Mul(vx, pz));
      const V8 ny = hn::Add(hn::Add(hn::Mul(t1y, p1), hn::Mul(t2y, p2)), hn::Mul(vy, pz));
      const V8 nz = hn::Add(hn::Add(hn::Mul(zero, p1), hn::Mul(t2z, p2)), hn::Mul(vz, pz));
      gx = hn::Mul(f.au, nx), gy = hn::Mul(f.av, ny), gz = hn::Max(zero, nz);
      Normalize3(d, &gx, &gy, &gz);
    }
    V8 bx = zero, by = zero, bz = one;
    if (!hn::AllFalse(d, vis_beck)) {
      const V8 cos_phi = hn::IfThenElse(tilted, hn::Mul(vx, inv_r), one);
      const V8 sin_phi = hn::IfThenElseZero(tilted, hn::Mul(vy, inv_r));
      V8 sx, sy;
      BeckmannVisibleSlope(d, vz, u_x, u_y, &sx, &sy);
      const V8 rx = hn::Mul(hn::Sub(hn::Mul(cos_phi, sx), hn::Mul(sin_phi, sy)), f.au);
      const V8 ry = hn::Mul(hn::Add(hn::Mul(sin_phi, sx), hn::Mul(cos_phi, sy)), f.av);
      bx = hn::Neg(rx), by = hn::Neg(ry), bz = one;
      Normalize3(d, &bx, &by, &bz);
    }
    x = hn::IfThenElse(f.visible, hn::IfThenElse(f.ggx, gx, bx), x);
    y = hn::IfThenElse(f.visible, hn::IfThenElse(f.ggx, gy, by), y);
    z = hn::IfThenElse(f.visible, hn::IfThenElse(f.ggx, gz, bz), z);
  }
  const M8 valid = hn::And(hn::And(hn::Gt(wz, zero), hn::Gt(z, zero)),
                           hn::And(hn::IsFinite(x), hn::IsFinite(y)));
  x = hn::IfThenElseZero(valid, x), y = hn::IfThenElseZero(valid, y);
  z = hn::IfThenElse(valid, z, one);
  const V8 p = Pdf(d, f, wx, wy, wz, x, y, z, g1_w);
  *pdf = hn::IfThenElseZero(hn::And(valid, hn::And(hn::Gt(p, zero), hn::IsFinite(p))), p);
  *mx = x, *my = y, *mz = z;
}

}  // namespace mf8
}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_MICROFACET8_INL_H_
