// Per-target SIMD twin of engine/bsdf/plastic_rough.h (Mitsuba `roughplastic`: the plastic tag's
// rough rows), included by plastic8-inl.h after its coating helpers. Oracle: PlasticRoughEvalPdf
// / PlasticRoughSample over PlasticRoughRowParams. The same operations in the same order (the
// transmittance table's interpolation, the half vector times 1/|wo + wi|, the G1/cos forms, the
// dielectric Fresnel, the lobe mixture); the internal-scattering terms are the row's own (base
// and T(μ) precomputed at load, nonlinear or not), read from the same columns. GGX rows are
// therefore bit-identical to the oracle in f and pdf; Beckmann rows differ by hwy's Exp/Erf in D
// and G1 (a few ulp). Samples add the visible-normal sampler's Log/Exp/Sin/Cos (microfacet8).

#if defined(PTLAB_SIMD_PLASTIC_ROUGH8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_PLASTIC_ROUGH8_INL_H_
#undef PTLAB_SIMD_PLASTIC_ROUGH8_INL_H_
#else
#define PTLAB_SIMD_PLASTIC_ROUGH8_INL_H_
#endif

#include "engine/bsdf/plastic_rough.h"
#include "engine/scene/plastic_table.h"
#include "hwy/highway.h"
#include "simd/wavefront/microfacet8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

/// The distribution column of rows [i, i + Lanes) as int32 lanes.
HWY_INLINE hn::Vec<hn::RebindToSigned<D8>> GatherCoatingDistribution(D8 d, const PlasticTable& t,
                                                                     const uint32_t* index,
                                                                     size_t i) {
  const hn::RebindToSigned<D8> di;
  HWY_ALIGN int32_t dist[8] = {};
  for (size_t j = 0; j < hn::Lanes(d); ++j) dist[j] = t.distribution[index[i + j]];
  return hn::Load(di, dist);
}

/// The lanes of rows [i, i + Lanes) whose coating is rough (Beckmann or GGX).
HWY_INLINE M8 RoughCoatingLanes(D8 d, const PlasticTable& t, const uint32_t* index, size_t i) {
  const hn::RebindToSigned<D8> di;
  const auto dist = GatherCoatingDistribution(d, t, index, i);
  return hn::RebindMask(d, hn::Ne(dist, hn::Set(di, int32_t(CoatingDistribution::kSmooth))));
}

/// One block's rough coatings (PlasticRoughRowParams).
struct PlasticRoughLanes {
  mf8::Dist8 dist;
  V8 eta, ws, base_r, base_g, base_b, s_r, s_g, s_b;
  V8 eta2_m1, eta2;  // η clamped (ClampRelIor): (η − 1)(η + 1) rounded, η²
  hn::Vec<hn::RebindToSigned<D8>> table;  // first entry of the row's T(μ) table
};

/// `uniform`: the distribution of every row of the table when it has one (else null: gathered).
HWY_INLINE PlasticRoughLanes GatherPlasticRough(D8 d, const PlasticTable& t, const uint32_t* index,
                                                size_t i, const CoatingDistribution* uniform) {
  const hn::RebindToSigned<D8> di;
  PlasticRoughLanes c;
  const auto dist = uniform != nullptr ? hn::Set(di, int32_t(*uniform))
                                       : GatherCoatingDistribution(d, t, index, i);
  c.dist.ggx = hn::RebindMask(d, hn::Eq(dist, hn::Set(di, int32_t(CoatingDistribution::kGgx))));
  c.dist.visible = hn::RebindMask(d, hn::Eq(dist, dist));  // MakeMicrofacet's default
  c.dist.au = mf8::ClampAlpha(d, Gather(d, t.alpha, index, i));
  c.dist.av = c.dist.au;
  c.eta = ClampRelIor(d, Gather(d, t.eta, index, i));
  const V8 one = hn::Set(d, 1.0f);
  c.eta2_m1 = RoundedMul(d, hn::Sub(c.eta, one), hn::Add(c.eta, one));
  c.eta2 = hn::Mul(c.eta, c.eta);
  c.ws = Gather(d, t.specular_sampling_weight, index, i);
  c.base_r = Gather(d, t.base_r, index, i), c.base_g = Gather(d, t.base_g, index, i);
  c.base_b = Gather(d, t.base_b, index, i);
  c.s_r = Gather(d, t.specular_r, index, i), c.s_g = Gather(d, t.specular_g, index, i);
  c.s_b = Gather(d, t.specular_b, index, i);
  c.table = hn::Mul(hn::LoadU(di, reinterpret_cast<const int32_t*>(index + i)),
                    hn::Set(di, int32_t(kCoatingTransmittanceRes)));
  return c;
}

/// CoatingTransmittanceAt: cos θ clamped to [0, 1] (NaN → 0), linear interpolation.
HWY_INLINE V8 CoatingTransmittance8(D8 d, const PlasticTable& t, const PlasticRoughLanes& c,
                                    V8 cos_theta) {
  const hn::RebindToSigned<D8> di;
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V8 cc = hn::IfThenElseZero(hn::Gt(cos_theta, zero), hn::Min(cos_theta, one));
  const V8 x = hn::Mul(cc, hn::Set(d, float(kCoatingTransmittanceRes - 1)));
  const auto j = hn::Min(hn::ConvertTo(di, x), hn::Set(di, kCoatingTransmittanceRes - 2));
  const V8 f = hn::Sub(x, hn::ConvertTo(d, j));
  const auto at = hn::Add(c.table, j);
  const V8 t0 = hn::GatherIndex(d, t.transmittance.data(), at);
  const V8 t1 = hn::GatherIndex(d, t.transmittance.data(), hn::Add(at, hn::Set(di, 1)));
  return hn::Add(hn::Mul(t0, hn::Sub(one, f)), hn::Mul(t1, f));
}

/// FresnelDielectric(cos_i, c.eta) where cos_i > 0 (the lobe's wo·h; F is not used in the other
/// lanes): its operations, less the η clamp, the 1/η for cos_i < 0 and the transmitted cosine,
/// with the η terms taken once per block (GatherPlasticRough).
HWY_INLINE V8 CoatingFresnelAbove(D8 d, const PlasticRoughLanes& c, V8 cos_i) {
  const V8 one = hn::Set(d, 1.0f);
  const V8 cc = ClampCos(d, cos_i);
  const V8 p = hn::Add(c.eta2_m1, RoundedMul(d, cc, cc));
  const M8 refracts = hn::Gt(p, hn::Zero(d));
  const V8 eta_ct = hn::Sqrt(hn::IfThenElseZero(refracts, p));
  const V8 ct_over_eta = hn::Div(eta_ct, c.eta2);
  const V8 rs = hn::Div(hn::Sub(cc, eta_ct), hn::Add(cc, eta_ct));
  const V8 rp = hn::Div(hn::Sub(cc, ct_over_eta), hn::Add(cc, ct_over_eta));
  const V8 f = hn::Mul(hn::Set(d, 0.5f), hn::Add(hn::Mul(rs, rs), hn::Mul(rp, rp)));
  return hn::IfThenElse(refracts, f, one);
}

/// PlasticRoughEvalPdf: f into *fr, *fg, *fb, the pdf returned (both 0 unless wo.z, wi.z > 0).
/// t_o: the coating's transmittance at wo.z, ps: CoatingSpecularProbability of it, g1o:
/// G1OverCos(wo) (the three depend on wo only: computed once for eval and sample).
HWY_INLINE V8 PlasticRoughEvalPdf8(D8 d, const PlasticTable& t, const PlasticRoughLanes& c, V8 t_o,
                                   V8 ps, V8 g1o, V8 ox, V8 oy, V8 oz, V8 ix, V8 iy, V8 iz, V8* fr,
                                   V8* fg, V8* fb) {
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f), inv_pi = hn::Set(d, kInvPi),
           quarter = hn::Set(d, 0.25f);
  const M8 above = hn::And(hn::Gt(oz, zero), hn::Gt(iz, zero));
  const V8 t_i = CoatingTransmittance8(d, t, c, iz);
  const V8 s_d = hn::Mul(hn::Mul(t_o, t_i), inv_pi);
  V8 r = hn::Mul(c.base_r, s_d), g = hn::Mul(c.base_g, s_d), b = hn::Mul(c.base_b, s_d);
  // The half vector as the oracle's sum / Length(sum) (times the reciprocal).
  const V8 sx = hn::Add(ox, ix), sy = hn::Add(oy, iy), sz = hn::Add(oz, iz);
  const V8 len = hn::Sqrt(hn::Add(hn::Add(hn::Mul(sx, sx), hn::Mul(sy, sy)), hn::Mul(sz, sz)));
  const M8 has_h = hn::And(hn::Gt(len, zero), hn::IsFinite(len));
  const V8 inv_len = hn::Div(one, hn::IfThenElse(has_h, len, one));
  const V8 hx = hn::Mul(sx, inv_len), hy = hn::Mul(sy, inv_len), hz = hn::Mul(sz, inv_len);
  const V8 dv = mf8::D(d, c.dist, hx, hy, hz);
  const V8 wo_h = hn::Add(hn::Add(hn::Mul(ox, hx), hn::Mul(oy, hy)), hn::Mul(oz, hz));
  const M8 lobe = hn::And(has_h, hn::And(hn::Gt(dv, zero), hn::Gt(wo_h, zero)));
  const V8 fresnel = CoatingFresnelAbove(d, c, wo_h);
  const V8 g1i = mf8::G1OverCos(d, c.dist, ix, iy, iz);
  const V8 s = hn::Mul(hn::Mul(fresnel, dv), hn::Mul(hn::Mul(quarter, g1o), g1i));
  const M8 add = hn::And(lobe, hn::And(hn::IsFinite(s), hn::Gt(s, zero)));
  r = hn::IfThenElse(add, hn::Add(r, hn::Mul(c.s_r, s)), r);
  g = hn::IfThenElse(add, hn::Add(g, hn::Mul(c.s_g, s)), g);
  b = hn::IfThenElse(add, hn::Add(b, hn::Mul(c.s_b, s)), b);
  const V8 q = hn::Mul(dv, hn::Mul(quarter, g1o));
  const V8 spec_pdf = hn::IfThenElseZero(hn::And(lobe, hn::IsFinite(q)), q);
  const V8 pdf = hn::Add(hn::Mul(ps, spec_pdf), hn::Mul(hn::Sub(one, ps), hn::Mul(iz, inv_pi)));
  const M8 f_ok = hn::And(above, AllFinite3(d, r, g, b));
  *fr = hn::IfThenElseZero(f_ok, r), *fg = hn::IfThenElseZero(f_ok, g);
  *fb = hn::IfThenElseZero(f_ok, b);
  return hn::IfThenElseZero(hn::And(above, hn::IsFinite(pdf)), pdf);
}

/// Stores v into rows [i, i + Lanes) of col where `lanes` (every lane when `all`), keeping the
/// others.
HWY_INLINE void StoreLanes(D8 d, bool all, M8 lanes, V8 v, float* col, size_t i) {
  if (col == nullptr) return;
  Store(d, all ? v : hn::IfThenElse(lanes, v, Load(d, col, i)), col, i);
}

/// One block's inputs and the terms that depend on wo only (PlasticRoughBlock's first part).
struct PlasticRoughStart {
  PlasticRoughLanes c;
  V8 ox, oy, oz, t_o, ps, g1o, ux, uy;
  M8 rough, spec;
  bool all;    // every lane rough
  bool micro;  // a rough lane samples the specular lobe: the microfacet sampler runs
};

HWY_INLINE PlasticRoughStart StartPlasticRough(const PlasticTable& t, const ShadeIo& b, size_t i,
                                               M8 rough, bool sample,
                                               const CoatingDistribution* uniform) {
  const D8 d;
  PlasticRoughStart s;
  s.rough = rough;
  s.all = hn::AllTrue(d, rough);
  s.c = GatherPlasticRough(d, t, b.index, i, uniform);
  s.ox = In(d, b, kWoX, i), s.oy = In(d, b, kWoY, i), s.oz = In(d, b, kWoZ, i);
  s.t_o = CoatingTransmittance8(d, t, s.c, s.oz);
  s.ps = CoatingSpecularProbability(d, s.t_o, s.c.ws);
  s.g1o = mf8::G1OverCos(d, s.c.dist, s.ox, s.oy, s.oz);
  s.ux = hn::Zero(d), s.uy = s.ux;
  s.spec = hn::FirstN(d, 0);  // none (eval only)
  s.micro = false;
  if (sample) {
    s.ux = In(d, b, kUX, i), s.uy = In(d, b, kUY, i);
    s.spec = hn::Lt(In(d, b, kULobe, i), s.ps);
    s.micro = !hn::AllFalse(d, hn::And(rough, s.spec));
  }
  return s;
}

/// PlasticRoughBlock's second part, given the sampled microfacet normal m (valid: its lanes;
/// used where s.micro): the sampled direction, the evals at the light direction and at it, the
/// outputs. The light's eval follows the sampler in program order: it does not depend on the
/// sampler's long chain, which out-of-order execution overlaps with it.
HWY_INLINE void FinishPlasticRough(const PlasticTable& t, const ShadeIo& b, size_t i,
                                   const PlasticRoughStart& s, M8 valid, V8 mx, V8 my, V8 mz,
                                   bool eval, bool sample) {
  const D8 d;
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const PlasticRoughLanes& c = s.c;
  const M8 rough = s.rough, spec = s.spec;
  const bool all = s.all;
  V8 ix = zero, iy = zero, iz = zero;
  M8 drawn = hn::Not(spec);  // the cosine lobe always draws; the specular one where pm > 0
  if (sample) {
    if (s.micro) {
      // Only pm > 0 of the sampler's pdf is used: SamplePdfPositive skips D(m) where it is sure.
      const M8 pm_pos = mf8::SamplePdfPositive(d, c.dist, s.ox, s.oy, s.oz, mx, my, mz, valid,
                                               hn::And(rough, spec), s.g1o);
      Reflect(d, s.ox, s.oy, s.oz, mx, my, mz, &ix, &iy, &iz);
      drawn = hn::Or(drawn, hn::And(spec, pm_pos));
    }
    if (!hn::AllTrue(d, spec)) {
      V8 cx, cy, cz;
      SampleCosineHemisphere(d, s.ux, s.uy, &cx, &cy, &cz);
      ix = hn::IfThenElse(spec, ix, cx), iy = hn::IfThenElse(spec, iy, cy);
      iz = hn::IfThenElse(spec, iz, cz);
    }
  }
  if (eval) {
    V8 fr, fg, fb;
    const V8 pdf_l =
        PlasticRoughEvalPdf8(d, t, c, s.t_o, s.ps, s.g1o, s.ox, s.oy, s.oz, In(d, b, kWlX, i),
                             In(d, b, kWlY, i), In(d, b, kWlZ, i), &fr, &fg, &fb);
    StoreLanes(d, all, rough, fr, b.out[kFR], i), StoreLanes(d, all, rough, fg, b.out[kFG], i);
    StoreLanes(d, all, rough, fb, b.out[kFB], i), StoreLanes(d, all, rough, pdf_l, b.out[kPdfL], i);
  }
  if (!sample) return;
  V8 fr, fg, fb;
  const V8 pdf = PlasticRoughEvalPdf8(d, t, c, s.t_o, s.ps, s.g1o, s.ox, s.oy, s.oz, ix, iy, iz,
                                      &fr, &fg, &fb);
  const V8 scale = hn::Div(iz, hn::IfThenElse(hn::Gt(pdf, zero), pdf, one));
  const V8 wr = hn::Mul(fr, scale), wg = hn::Mul(fg, scale), wb = hn::Mul(fb, scale);
  const M8 ok = hn::And(hn::And(drawn, hn::And(hn::Gt(s.oz, zero), hn::Gt(iz, zero))),
                        hn::And(hn::Gt(pdf, zero), AllFinite3(d, wr, wg, wb)));
  StoreLanes(d, all, rough, hn::IfThenElseZero(ok, ix), b.out[kWiX], i);
  StoreLanes(d, all, rough, hn::IfThenElseZero(ok, iy), b.out[kWiY], i);
  StoreLanes(d, all, rough, hn::IfThenElseZero(ok, iz), b.out[kWiZ], i);
  StoreLanes(d, all, rough, hn::IfThenElseZero(ok, wr), b.out[kWR], i);
  StoreLanes(d, all, rough, hn::IfThenElseZero(ok, wg), b.out[kWG], i);
  StoreLanes(d, all, rough, hn::IfThenElseZero(ok, wb), b.out[kWB], i);
  StoreLanes(d, all, rough, hn::IfThenElseZero(ok, pdf), b.out[kPdf], i);
  StoreLanes(d, all, rough, one, b.out[kEta], i);
  StoreLanes(d, all, rough, zero, b.out[kDelta], i);
}

/// PlasticRoughEvalPdf / PlasticRoughSample for the `rough` lanes of rows [i, i + Lanes) of the
/// plastic table (the other lanes' outputs are left as they are). `uniform` as for
/// GatherPlasticRough.
HWY_INLINE void PlasticRoughBlock(const PlasticTable& t, const ShadeIo& b, size_t i, M8 rough,
                                  bool eval, bool sample,
                                  const CoatingDistribution* uniform = nullptr) {
  const D8 d;
  const PlasticRoughStart s = StartPlasticRough(t, b, i, rough, sample, uniform);
  V8 mx = hn::Zero(d), my = mx, mz = mx;
  M8 valid = hn::FirstN(d, 0);
  if (s.micro) valid = mf8::SampleNormal(d, s.c.dist, s.ox, s.oy, s.oz, s.ux, s.uy, &mx, &my, &mz);
  FinishPlasticRough(t, b, i, s, valid, mx, my, mz, eval, sample);
}

/// PlasticRoughBlock for every lane of rows [i, i + 2 Lanes): two blocks, whose microfacet
/// samplers run together (mf8::SampleNormal2); each block's outputs are PlasticRoughBlock's.
HWY_INLINE void PlasticRoughBlockPair(const PlasticTable& t, const ShadeIo& b, size_t i, bool eval,
                                      bool sample, const CoatingDistribution* uniform) {
  const D8 d;
  const M8 every = hn::Eq(hn::Zero(d), hn::Zero(d));
  const size_t j = i + hn::Lanes(d);
  const PlasticRoughStart sa = StartPlasticRough(t, b, i, every, sample, uniform);
  const PlasticRoughStart sb = StartPlasticRough(t, b, j, every, sample, uniform);
  V8 max = hn::Zero(d), may = max, maz = max, mbx = max, mby = max, mbz = max;
  M8 valid_a = hn::FirstN(d, 0), valid_b = valid_a;
  if (sa.micro && sb.micro) {
    mf8::SampleNormal2(d, sa.c.dist, sa.ox, sa.oy, sa.oz, sa.ux, sa.uy, &max, &may, &maz, &valid_a,
                       sb.c.dist, sb.ox, sb.oy, sb.oz, sb.ux, sb.uy, &mbx, &mby, &mbz, &valid_b);
  } else {
    if (sa.micro)
      valid_a =
          mf8::SampleNormal(d, sa.c.dist, sa.ox, sa.oy, sa.oz, sa.ux, sa.uy, &max, &may, &maz);
    if (sb.micro)
      valid_b =
          mf8::SampleNormal(d, sb.c.dist, sb.ox, sb.oy, sb.oz, sb.ux, sb.uy, &mbx, &mby, &mbz);
  }
  FinishPlasticRough(t, b, i, sa, valid_a, max, may, maz, eval, sample);
  FinishPlasticRough(t, b, j, sb, valid_b, mbx, mby, mbz, eval, sample);
}

/// The plastic batch of a table whose rows are all rough with one distribution (`uniform`):
/// pairs of blocks (PlasticRoughBlockPair), then ForEachBlock over the rest.
inline HWY_NOINLINE void ShadePlasticRoughUniform(const PlasticTable& t, const ShadeIo& io,
                                                  size_t n, bool eval, bool sample,
                                                  const CoatingDistribution& uniform) {
  const D8 d;
  const size_t pair = 2 * hn::Lanes(d);
  size_t i = 0;
  for (; i + pair <= n; i += pair) PlasticRoughBlockPair(t, io, i, eval, sample, &uniform);
  if (i == n) return;
  ShadeIo rest = io;  // rows [i, n)
  rest.index = io.index + i;
  if (io.entry != nullptr) rest.entry = io.entry + i;
  for (auto& c : rest.in)
    if (c != nullptr) c += i;
  for (auto& c : rest.out)
    if (c != nullptr) c += i;
  ForEachBlock(rest, n - i, [&t, eval, sample, &uniform](const ShadeIo& b, size_t k) HWY_ATTR {
    const D8 d8;
    PlasticRoughBlock(t, b, k, hn::Eq(hn::Zero(d8), hn::Zero(d8)), eval, sample, &uniform);
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_PLASTIC_ROUGH8_INL_H_
