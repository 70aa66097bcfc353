// Mitsuba `plastic`: a smooth dielectric coating (delta reflection) over a diffuse base.
#pragma once

#include <cmath>

#include "engine/bsdf/bsdf_sample.h"
#include "engine/bsdf/fresnel.h"
#include "engine/sampling/warp.h"
#include "engine/scene/plastic_table.h"

namespace ptlab {

// The model (Mitsuba 3's `plastic`, after Weidlich & Wilkie 2007): light meets the coating;
// the part the Fresnel term F reflects leaves as a mirror lobe; the rest enters, reflects off
// the diffuse base and bounces between base and coating, and leaves with the coating's
// transmittance (1 − F) on the way out. With ρ_d the base albedo and F_dr the coating's
// hemispherical reflectance seen from inside, the bounces sum to ρ_d / (1 − ρ_d F_dr)
// (`nonlinear`) or to Mitsuba's default, linear in ρ_d, ρ_d / (1 − F_dr); radiance leaving a
// medium of relative IOR η is scaled by 1/η². PlasticRow::base holds that quotient, so
//   f(wo, wi) = base (1 − F(cos θo)) (1 − F(cos θi)) / π        (non-delta part; one-sided)
// and the delta lobe reflects with weight specular F(cos θo) / P(specular).

/// One row of PlasticTable as the smooth model reads it.
struct PlasticParams {
  float eta = 1.49f / 1.000277f;
  Color3f base{0.5f, 0.5f, 0.5f};
  Color3f specular{1, 1, 1};
  float specular_sampling_weight = 0.5f;
};

inline PlasticParams PlasticRowParams(const PlasticTable& t, uint32_t i) {
  return {t.eta[i], {t.base_r[i], t.base_g[i], t.base_b[i]},
          {t.specular_r[i], t.specular_g[i], t.specular_b[i]}, t.specular_sampling_weight[i]};
}

/// Fresnel reflectance of the coating for light arriving from outside at cos θ ≥ 0.
inline float CoatingFresnel(float cos_theta, float eta) {
  float cos_t;
  return FresnelDielectric(cos_theta, eta, &cos_t);
}

/// Mitsuba's choice of lobe: the specular lobe with probability F w_s / (F w_s + T (1 − w_s)),
/// F = 1 − T the coating's reflectance at wo and w_s the row's specular sampling weight. 0
/// when both terms vanish (no lobe carries anything).
inline float CoatingSpecularProbability(float transmittance, float specular_sampling_weight) {
  const float ps = (1.0f - transmittance) * specular_sampling_weight;
  const float pd = transmittance * (1.0f - specular_sampling_weight);
  const float sum = ps + pd;
  return sum > 0 ? ps / sum : 0.0f;
}

inline Color3f PlasticEval(const PlasticParams& p, const Vec3f& wo, const Vec3f& wi) {
  if (!(wo.z > 0) || !(wi.z > 0)) return {};
  const float t = (1.0f - CoatingFresnel(wo.z, p.eta)) * (1.0f - CoatingFresnel(wi.z, p.eta));
  return p.base * (t * kInvPi);
}

/// Density of the diffuse (non-delta) samples: (1 − P(specular)) cos θi / π.
inline float PlasticPdf(const PlasticParams& p, const Vec3f& wo, const Vec3f& wi) {
  if (!(wo.z > 0) || !(wi.z > 0)) return 0.0f;
  const float ps =
      CoatingSpecularProbability(1.0f - CoatingFresnel(wo.z, p.eta), p.specular_sampling_weight);
  return (1.0f - ps) * CosineHemispherePdf(wi);
}

/// u_lobe < P(specular): the mirror direction, delta, pdf P(specular), weight
/// specular F / P(specular); else a cosine-distributed wi with pdf PlasticPdf and weight
/// PlasticEval cos θi / PlasticPdf = base (1 − F_o)(1 − F_i) / (1 − P(specular)).
inline bool PlasticSample(const PlasticParams& p, const Vec3f& wo, float u_lobe, const Vec2f& u,
                          BsdfSample* s) {
  if (!(wo.z > 0)) return false;
  const float f_o = CoatingFresnel(wo.z, p.eta);
  const float ps = CoatingSpecularProbability(1.0f - f_o, p.specular_sampling_weight);
  s->eta = 1.0f;
  if (u_lobe < ps) {
    s->wi = {-wo.x, -wo.y, wo.z};
    s->pdf = ps;
    s->weight = p.specular * (f_o / ps);
    s->delta = true;
    return true;
  }
  const Vec3f wi = SampleCosineHemisphere(u);
  const float pd = 1.0f - ps;
  const float pdf = pd * CosineHemispherePdf(wi);
  if (!(wi.z > 0) || !(pdf > 0)) return false;
  s->wi = wi;
  s->pdf = pdf;
  s->weight = p.base * ((1.0f - f_o) * (1.0f - CoatingFresnel(wi.z, p.eta)) / pd);
  s->delta = false;
  return IsFinite(s->weight);
}

}  // namespace ptlab
