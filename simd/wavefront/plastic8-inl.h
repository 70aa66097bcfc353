// Per-target SIMD twin of engine/bsdf/plastic.h (Mitsuba `plastic`), included by bsdf8-inl.h.
// Oracle: PlasticEval / PlasticPdf / PlasticSample. The same operations in the same order, with
// IEEE add/mul/div/sqrt only, so f, pdf_l and the delta lobe are bit-identical to the oracle;
// the diffuse direction differs by the cosine-hemisphere warp's Sin/Cos (≤ 3 ulp, as for
// ShadeDiffuse), and the weight by what that moves.

#if defined(PTLAB_SIMD_PLASTIC8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_PLASTIC8_INL_H_
#undef PTLAB_SIMD_PLASTIC8_INL_H_
#else
#define PTLAB_SIMD_PLASTIC8_INL_H_
#endif

#include <algorithm>

#include "engine/scene/plastic_table.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

/// CoatingSpecularProbability (engine/bsdf/plastic.h).
HWY_INLINE V8 CoatingSpecularProbability(D8 d, V8 transmittance, V8 ws) {
  const V8 one = hn::Set(d, 1.0f), zero = hn::Zero(d);
  const V8 ps = hn::Mul(hn::Sub(one, transmittance), ws);
  const V8 pd = hn::Mul(transmittance, hn::Sub(one, ws));
  const V8 sum = hn::Add(ps, pd);
  const M8 pos = hn::Gt(sum, zero);
  return hn::IfThenElseZero(pos, hn::Div(ps, hn::IfThenElse(pos, sum, one)));
}

/// CoatingFresnel (engine/bsdf/plastic.h).
HWY_INLINE V8 CoatingFresnel(D8 d, V8 cos_theta, V8 eta) {
  V8 cos_t;
  return FresnelDielectric(d, cos_theta, eta, &cos_t);
}

/// PlasticEval / PlasticPdf / PlasticSample for rows [i, i + Lanes) of PlasticTable, every
/// lane as a smooth row (the rough lanes are overwritten by PlasticRoughBlock).
HWY_INLINE void PlasticBlock(const PlasticTable& t, const ShadeIo& b, size_t i, bool eval,
                             bool sample) {
  const D8 d;
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f), inv_pi = hn::Set(d, kInvPi);
  const V8 eta = Gather(d, t.eta, b.index, i);
  const V8 base_r = Gather(d, t.base_r, b.index, i), base_g = Gather(d, t.base_g, b.index, i),
           base_b = Gather(d, t.base_b, b.index, i);
  const V8 ws = Gather(d, t.specular_sampling_weight, b.index, i);
  const V8 ox = In(d, b, kWoX, i), oy = In(d, b, kWoY, i), oz = In(d, b, kWoZ, i);
  const M8 above = hn::Gt(oz, zero);
  const V8 f_o = CoatingFresnel(d, oz, eta);
  const V8 t_o = hn::Sub(one, f_o);
  const V8 ps = CoatingSpecularProbability(d, t_o, ws);
  const V8 pd = hn::Sub(one, ps);
  if (eval) {
    const V8 lz = In(d, b, kWlZ, i);
    const M8 both = hn::And(above, hn::Gt(lz, zero));
    const V8 tt = hn::Mul(t_o, hn::Sub(one, CoatingFresnel(d, lz, eta)));
    const V8 s = hn::Mul(tt, inv_pi);
    StoreEval(d, b, i, hn::IfThenElseZero(both, hn::Mul(base_r, s)),
              hn::IfThenElseZero(both, hn::Mul(base_g, s)),
              hn::IfThenElseZero(both, hn::Mul(base_b, s)),
              hn::IfThenElseZero(both, hn::Mul(pd, hn::Mul(lz, inv_pi))));
  }
  if (!sample) return;
  const V8 u_lobe = In(d, b, kULobe, i);
  const M8 spec = hn::Lt(u_lobe, ps);
  V8 ix, iy, iz;
  SampleCosineHemisphere(d, In(d, b, kUX, i), In(d, b, kUY, i), &ix, &iy, &iz);
  // Diffuse lanes: weight base (1 − F_o)(1 − F_i) / pd.
  const V8 q = hn::Div(hn::Mul(t_o, hn::Sub(one, CoatingFresnel(d, iz, eta))), pd);
  const V8 pdf_diffuse = hn::Mul(pd, hn::Mul(iz, inv_pi));
  V8 wr = hn::Mul(base_r, q), wg = hn::Mul(base_g, q), wb = hn::Mul(base_b, q);
  const M8 diffuse_ok =
      hn::And(hn::And(hn::Gt(iz, zero), hn::Gt(pdf_diffuse, zero)), AllFinite3(d, wr, wg, wb));
  // Specular lanes: the mirror direction, weight specular F_o / ps.
  const V8 fs = hn::Div(f_o, hn::IfThenElse(spec, ps, one));
  wr = hn::IfThenElse(spec, hn::Mul(Gather(d, t.specular_r, b.index, i), fs), wr);
  wg = hn::IfThenElse(spec, hn::Mul(Gather(d, t.specular_g, b.index, i), fs), wg);
  wb = hn::IfThenElse(spec, hn::Mul(Gather(d, t.specular_b, b.index, i), fs), wb);
  ix = hn::IfThenElse(spec, hn::Neg(ox), ix), iy = hn::IfThenElse(spec, hn::Neg(oy), iy);
  iz = hn::IfThenElse(spec, oz, iz);
  const V8 pdf = hn::IfThenElse(spec, ps, pdf_diffuse);
  const M8 ok = hn::And(above, hn::Or(spec, diffuse_ok));
  StoreSample(d, b, i, ok, ix, iy, iz, wr, wg, wb, pdf, one);
  if (b.out[kDelta] != nullptr)
    Store(d, hn::IfThenElseZero(hn::And(ok, spec), one), b.out[kDelta], i);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

// The rough coating's kernel (it uses the helpers above).
#include "simd/wavefront/plastic_rough8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

/// The plastic tag's batch, smooth (`plastic`) and rough (`roughplastic`) rows: grouped by the
/// coating's distribution (ForEachBlockGrouped), each 8-wide block runs PlasticBlock where it
/// has smooth rows and PlasticRoughBlock where it has rough ones (both for a mixed block).
inline HWY_NOINLINE void ShadePlasticRows(const MaterialTables& m,
                                          const uint32_t* /*material_index*/, size_t n,
                                          const ShadeInputs& /*in*/, const ShadeOutputs& /*out*/,
                                          const ShadeIo& io, bool eval, bool sample) {
  const PlasticTable& t = m.plastic;
  const auto key = [&t, &io](size_t r) { return uint32_t(t.distribution[io.index[r]]); };
  const auto block = [&t, eval, sample](const ShadeIo& b, size_t i) HWY_ATTR {
    const D8 d;
    const M8 rough = RoughCoatingLanes(d, t, b.index, i);
    if (!hn::AllTrue(d, rough)) PlasticBlock(t, b, i, eval, sample);
    if (!hn::AllFalse(d, rough)) PlasticRoughBlock(t, b, i, rough, eval, sample);
  };
  // A table of one coating (the usual case) has no blocks to group: when it is no longer than
  // the batch, checking its rows costs less than keying the batch's. A rough one's blocks also
  // take the distribution as known (no per-block gathers of the coating column).
  const auto& dist = t.distribution;
  if (!dist.empty() && dist.size() <= n &&
      std::all_of(dist.begin(), dist.end(), [&dist](uint8_t v) { return v == dist[0]; })) {
    const CoatingDistribution one = static_cast<CoatingDistribution>(dist[0]);
    if (one == CoatingDistribution::kSmooth) return ForEachBlock(io, n, block);
    return ForEachBlock(io, n, [&t, eval, sample, &one](const ShadeIo& b, size_t i) HWY_ATTR {
      const D8 d;
      PlasticRoughBlock(t, b, i, hn::Eq(hn::Zero(d), hn::Zero(d)), eval, sample, &one);
    });
  }
  ForEachBlockGrouped(io, n, key, block);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_PLASTIC8_INL_H_
