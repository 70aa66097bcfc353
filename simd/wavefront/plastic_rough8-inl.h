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
  c.eta = Gather(d, t.eta, index, i);
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
  V8 cos_t;
  const V8 fresnel = FresnelDielectric(d, wo_h, c.eta, &cos_t);
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

/// Stores v into rows [i, i + Lanes) of col where `lanes`, keeping the others.
HWY_INLINE void StoreLanes(D8 d, M8 lanes, V8 v, float* col, size_t i) {
  if (col == nullptr) return;
  Store(d, hn::IfThenElse(lanes, v, Load(d, col, i)), col, i);
}

/// PlasticRoughEvalPdf / PlasticRoughSample for the `rough` lanes of rows [i, i + Lanes) of the
/// plastic table (the other lanes' outputs are left as they are). `uniform` as for
/// GatherPlasticRough.
HWY_INLINE void PlasticRoughBlock(const PlasticTable& t, const ShadeIo& b, size_t i, M8 rough,
                                  bool eval, bool sample,
                                  const CoatingDistribution* uniform = nullptr) {
  const D8 d;
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const PlasticRoughLanes c = GatherPlasticRough(d, t, b.index, i, uniform);
  const V8 ox = In(d, b, kWoX, i), oy = In(d, b, kWoY, i), oz = In(d, b, kWoZ, i);
  const V8 t_o = CoatingTransmittance8(d, t, c, oz);
  const V8 ps = CoatingSpecularProbability(d, t_o, c.ws);
  const V8 g1o = mf8::G1OverCos(d, c.dist, ox, oy, oz);
  if (eval) {
    V8 fr, fg, fb;
    const V8 pdf_l = PlasticRoughEvalPdf8(d, t, c, t_o, ps, g1o, ox, oy, oz, In(d, b, kWlX, i),
                                          In(d, b, kWlY, i), In(d, b, kWlZ, i), &fr, &fg, &fb);
    StoreLanes(d, rough, fr, b.out[kFR], i), StoreLanes(d, rough, fg, b.out[kFG], i);
    StoreLanes(d, rough, fb, b.out[kFB], i), StoreLanes(d, rough, pdf_l, b.out[kPdfL], i);
  }
  if (!sample) return;
  const V8 ux = In(d, b, kUX, i), uy = In(d, b, kUY, i);
  const M8 spec = hn::Lt(In(d, b, kULobe, i), ps);
  V8 ix = zero, iy = zero, iz = zero;
  M8 drawn = hn::Not(spec);  // the cosine lobe always draws; the specular one where pm > 0
  if (!hn::AllTrue(d, spec)) SampleCosineHemisphere(d, ux, uy, &ix, &iy, &iz);
  if (!hn::AllFalse(d, hn::And(rough, spec))) {
    V8 mx, my, mz, pm;
    mf8::Sample(d, c.dist, ox, oy, oz, ux, uy, &mx, &my, &mz, &pm, &g1o);
    V8 rx, ry, rz;
    Reflect(d, ox, oy, oz, mx, my, mz, &rx, &ry, &rz);
    ix = hn::IfThenElse(spec, rx, ix), iy = hn::IfThenElse(spec, ry, iy);
    iz = hn::IfThenElse(spec, rz, iz);
    drawn = hn::Or(drawn, hn::And(spec, hn::Gt(pm, zero)));
  }
  V8 fr, fg, fb;
  const V8 pdf = PlasticRoughEvalPdf8(d, t, c, t_o, ps, g1o, ox, oy, oz, ix, iy, iz, &fr, &fg, &fb);
  const V8 scale = hn::Div(iz, hn::IfThenElse(hn::Gt(pdf, zero), pdf, one));
  const V8 wr = hn::Mul(fr, scale), wg = hn::Mul(fg, scale), wb = hn::Mul(fb, scale);
  const M8 ok = hn::And(hn::And(drawn, hn::And(hn::Gt(oz, zero), hn::Gt(iz, zero))),
                        hn::And(hn::Gt(pdf, zero), AllFinite3(d, wr, wg, wb)));
  StoreLanes(d, rough, hn::IfThenElseZero(ok, ix), b.out[kWiX], i);
  StoreLanes(d, rough, hn::IfThenElseZero(ok, iy), b.out[kWiY], i);
  StoreLanes(d, rough, hn::IfThenElseZero(ok, iz), b.out[kWiZ], i);
  StoreLanes(d, rough, hn::IfThenElseZero(ok, wr), b.out[kWR], i);
  StoreLanes(d, rough, hn::IfThenElseZero(ok, wg), b.out[kWG], i);
  StoreLanes(d, rough, hn::IfThenElseZero(ok, wb), b.out[kWB], i);
  StoreLanes(d, rough, hn::IfThenElseZero(ok, pdf), b.out[kPdf], i);
  StoreLanes(d, rough, one, b.out[kEta], i);
  StoreLanes(d, rough, zero, b.out[kDelta], i);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_PLASTIC_ROUGH8_INL_H_
