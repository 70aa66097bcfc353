// Mitsuba 3 `roughconductor`: Beckmann or GGX, isotropic or anisotropic, visible-normal
// sampling, complex IOR per RGB channel and a specular reflectance.
#pragma once

#include "engine/bsdf/bsdf_sample.h"
#include "engine/bsdf/fresnel.h"
#include "engine/bsdf/microfacet.h"

namespace ptlab {

/// One row of ConductorTable in its Mitsuba form (ConductorTable::microfacet()).
struct RoughConductorParams {
  Microfacet dist;
  Color3f eta, k;                  // complex IOR relative to the exterior, per RGB channel
  Color3f specular{1, 1, 1};       // Mitsuba's specular_reflectance
};

/// f = R F(wi·h) D(h) G(wo, wi, h) / (4 cos θo cos θi), h = (wo + wi)/|wo + wi| (Walter et al.
/// 2007 eq. 20), R the specular reflectance; one-sided (0 unless wo and wi are above the
/// surface), as Mitsuba. Written as R F D (G1/cos)(G1/cos)/4: symmetric and finite at grazing
/// angles.
inline Color3f RoughConductorEval(const RoughConductorParams& p, const Vec3f& wo,
                                  const Vec3f& wi) {
  if (!(wo.z > 0) || !(wi.z > 0)) return {};
  const Vec3f h = Normalize(wo + wi);
  const float d = MicrofacetD(p.dist, h);
  if (!(d > 0)) return {};
  const float g = MicrofacetG1OverCos(p.dist, wo) * MicrofacetG1OverCos(p.dist, wi);
  const Color3f f = p.specular * FresnelConductor(Dot(wi, h), p.eta, p.k) * (0.25f * d * g);
  return IsFinite(f) ? f : Color3f{};
}

/// Solid-angle density of RoughConductorSample: MicrofacetPdf(wo, h) / (4 wi·h), which with
/// visible normals is D(h) (G1(wo)/cos θo) / 4.
inline float RoughConductorPdf(const RoughConductorParams& p, const Vec3f& wo, const Vec3f& wi) {
  if (!(wo.z > 0) || !(wi.z > 0)) return 0.0f;
  const Vec3f h = Normalize(wo + wi);
  const float wi_h = Dot(wi, h);
  if (!(wi_h > 0)) return 0.0f;
  const float pdf = MicrofacetPdf(p.dist, wo, h) / (4.0f * wi_h);
  return std::isfinite(pdf) ? pdf : 0.0f;
}

/// m ~ SampleMicrofacet(wo), wi = reflect(wo, m); false when wo or wi is not above the
/// surface. pdf = RoughConductorPdf(wo, wi); the weight f cos θi / pdf is, D having
/// cancelled, R F G1(wi) with visible normals and R F G (wo·h) / (cos θo h.z) otherwise.
inline bool RoughConductorSample(const RoughConductorParams& p, const Vec3f& wo, const Vec2f& u,
                                 BsdfSample* s) {
  if (!(wo.z > 0)) return false;
  float pdf_m;
  const Vec3f m = SampleMicrofacet(p.dist, wo, u, &pdf_m);
  if (!(pdf_m > 0)) return false;
  const float wo_m = Dot(wo, m);
  const Vec3f wi{2.0f * wo_m * m.x - wo.x, 2.0f * wo_m * m.y - wo.y, 2.0f * wo_m * m.z - wo.z};
  if (!(wi.z > 0)) return false;
  const float pdf = RoughConductorPdf(p, wo, wi);
  if (!(pdf > 0)) return false;
  const Vec3f h = Normalize(wo + wi);
  const float g = p.dist.sample_visible
                      ? MicrofacetG1(p.dist, wi, h)
                      : MicrofacetG(p.dist, wo, wi, h) * Dot(wo, h) / (wo.z * h.z);
  const Color3f w = p.specular * FresnelConductor(Dot(wi, h), p.eta, p.k) * g;
  if (!IsFinite(w)) return false;
  s->wi = wi;
  s->pdf = pdf;
  s->weight = w;
  s->delta = false;
  s->eta = 1.0f;
  return true;
}

}  // namespace ptlab
