// Mitsuba `roughplastic`: a rough dielectric coating (GGX or Beckmann) over a diffuse base.
#pragma once

#include <cmath>

#include "engine/bsdf/beckmann.h"  // ReflectAbout
#include "engine/bsdf/bsdf_sample.h"
#include "engine/bsdf/fresnel.h"
#include "engine/bsdf/microfacet.h"
#include "engine/bsdf/plastic.h"
#include "engine/sampling/warp.h"
#include "engine/scene/plastic_table.h"

namespace ptlab {

// Mitsuba 3's model (after Weidlich & Wilkie 2007, with its precomputed terms computed in
// ptlab by quadrature at load, engine/bsdf/plastic_precompute.cpp):
//   f = specular F(wo·h) D(h) G(wo, wi) / (4 cos θo cos θi) + base T(θo) T(θi) / π
// with T(μ) the rough coating's external transmittance (a 64-entry table over cos θ, linear
// interpolation) and base = ρ / (1 − R_int) / η² (or ρ / (1 − ρ R_int) / η², nonlinear), R_int
// the coating's hemispherical reflectance seen from inside. The specular lobe is sampled with
// visible normals (Mitsuba's default), chosen with probability
// (1 − T) w_s / ((1 − T) w_s + T (1 − w_s)) at wo; the pdf is the mixture of both lobes.

/// One rough row of PlasticTable.
struct RoughPlasticCoatParams {
  Microfacet dist;
  float eta = 1.49f;
  Color3f base{0.5f, 0.5f, 0.5f};
  Color3f specular{1, 1, 1};
  float specular_sampling_weight = 0.5f;
  const float* transmittance = nullptr;  // kCoatingTransmittanceRes entries
};

inline RoughPlasticCoatParams PlasticRoughRowParams(const PlasticTable& t, uint32_t i) {
  RoughPlasticCoatParams p;
  const MicrofacetType type = static_cast<CoatingDistribution>(t.distribution[i]) ==
                                      CoatingDistribution::kGgx
                                  ? MicrofacetType::kGgx
                                  : MicrofacetType::kBeckmann;
  p.dist = MakeMicrofacet(type, t.alpha[i], t.alpha[i]);
  p.eta = t.eta[i];
  p.base = {t.base_r[i], t.base_g[i], t.base_b[i]};
  p.specular = {t.specular_r[i], t.specular_g[i], t.specular_b[i]};
  p.specular_sampling_weight = t.specular_sampling_weight[i];
  p.transmittance = t.transmittance.data() + size_t(i) * kCoatingTransmittanceRes;
  return p;
}

/// The table's T at cos θ (clamped to [0, 1]), linearly interpolated.
inline float CoatingTransmittanceAt(const float* table, float cos_theta) {
  const float c = cos_theta > 0 ? (cos_theta < 1 ? cos_theta : 1.0f) : 0.0f;
  const float x = c * float(kCoatingTransmittanceRes - 1);
  int j = int(x);
  if (j > kCoatingTransmittanceRes - 2) j = kCoatingTransmittanceRes - 2;
  const float t = x - float(j);
  return table[j] * (1.0f - t) + table[j + 1] * t;
}

/// f and (*pdf) of a rough row for wo, wi above the surface (0 otherwise).
inline Color3f PlasticRoughEvalPdf(const RoughPlasticCoatParams& p, const Vec3f& wo,
                                   const Vec3f& wi, float* pdf) {
  *pdf = 0.0f;
  if (!(wo.z > 0) || !(wi.z > 0)) return {};
  const float t_o = CoatingTransmittanceAt(p.transmittance, wo.z);
  const float t_i = CoatingTransmittanceAt(p.transmittance, wi.z);
  Color3f f = p.base * (t_o * t_i * kInvPi);
  const float ps = CoatingSpecularProbability(t_o, p.specular_sampling_weight);
  float spec_pdf = 0.0f;
  const Vec3f sum = wo + wi;
  const float len = Length(sum);
  if (len > 0 && std::isfinite(len)) {
    const Vec3f h = sum / len;
    const float d = MicrofacetD(p.dist, h);
    const float wo_h = Dot(wo, h);
    if (d > 0 && wo_h > 0) {
      // G / (cos θo cos θi) and the visible-normal density over 4 wo·h, as G1/cos forms
      // (wi·h = wo·h > 0 and both above the surface, so every orientation test holds): no
      // cosine is divided out again, which keeps grazing and denormal cosines exact.
      float cos_t;
      const float fr = FresnelDielectric(wo_h, p.eta, &cos_t);
      const float g1o = MicrofacetG1OverCos(p.dist, wo), g1i = MicrofacetG1OverCos(p.dist, wi);
      const float s = fr * d * (0.25f * g1o * g1i);
      if (std::isfinite(s) && s > 0) f += p.specular * s;
      const float q = d * (0.25f * g1o);  // D G1(wo) (wo·h)/cos θo / (4 wo·h)
      if (std::isfinite(q)) spec_pdf = q;
    }
  }
  const float pdf_v = ps * spec_pdf + (1.0f - ps) * (wi.z * kInvPi);
  *pdf = std::isfinite(pdf_v) ? pdf_v : 0.0f;
  return IsFinite(f) ? f : Color3f{};
}

inline bool PlasticRoughSample(const RoughPlasticCoatParams& p, const Vec3f& wo, float u_lobe,
                               const Vec2f& u, BsdfSample* s) {
  if (!(wo.z > 0)) return false;
  const float ps = CoatingSpecularProbability(CoatingTransmittanceAt(p.transmittance, wo.z),
                                              p.specular_sampling_weight);
  Vec3f wi;
  if (u_lobe < ps) {
    float pm = 0.0f;
    const Vec3f m = SampleMicrofacet(p.dist, wo, u, &pm);
    if (!(pm > 0)) return false;
    wi = ReflectAbout(wo, m);
  } else {
    wi = SampleCosineHemisphere(u);
  }
  if (!(wi.z > 0)) return false;
  float pdf = 0.0f;
  const Color3f f = PlasticRoughEvalPdf(p, wo, wi, &pdf);
  if (!(pdf > 0) || !std::isfinite(pdf)) return false;
  const Color3f w = f * (wi.z / pdf);
  if (!IsFinite(w)) return false;
  s->wi = wi;
  s->pdf = pdf;
  s->weight = w;
  s->delta = false;
  s->eta = 1.0f;
  return true;
}

// The plastic tag's rows, smooth or rough (the dispatch's entry points).

inline bool PlasticRowIsRough(const PlasticTable& t, uint32_t i) {
  return static_cast<CoatingDistribution>(t.distribution[i]) != CoatingDistribution::kSmooth;
}
inline Color3f PlasticRowEvalPdf(const PlasticTable& t, uint32_t i, const Vec3f& wo,
                                 const Vec3f& wi, float* pdf) {
  if (PlasticRowIsRough(t, i)) return PlasticRoughEvalPdf(PlasticRoughRowParams(t, i), wo, wi, pdf);
  const PlasticParams p = PlasticRowParams(t, i);
  *pdf = PlasticPdf(p, wo, wi);
  return PlasticEval(p, wo, wi);
}
inline bool PlasticRowSample(const PlasticTable& t, uint32_t i, const Vec3f& wo, float u_lobe,
                             const Vec2f& u, BsdfSample* s) {
  if (PlasticRowIsRough(t, i))
    return PlasticRoughSample(PlasticRoughRowParams(t, i), wo, u_lobe, u, s);
  return PlasticSample(PlasticRowParams(t, i), wo, u_lobe, u, s);
}

}  // namespace ptlab
