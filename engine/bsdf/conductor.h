// Rough conductor with a Beckmann distribution (Mitsuba `roughconductor`, distribution beckmann).
#pragma once

#include "engine/bsdf/beckmann.h"
#include "engine/bsdf/bsdf_sample.h"
#include "engine/bsdf/fresnel.h"

namespace ptlab {

/// One row of ConductorTable: roughness α and the complex IOR η + iκ per RGB channel, relative
/// to the exterior medium.
struct ConductorParams {
  float alpha = 0.1f;
  Color3f eta, k;
};

/// f = F(wi·h) D(h) G1(wo) G1(wi) / (4 cos θi cos θo) with D = BeckmannD, h = (wo + wi)/|wo + wi|
/// (Walter et al. 2007 eq. 20, as Mitsuba's roughconductor). One-sided: 0 unless wo and wi are
/// above the surface. Written as F D (G1/cos)(G1/cos)/4, so it is exactly symmetric in
/// (wo, wi) and finite at grazing angles.
inline Color3f ConductorEval(const ConductorParams& p, const Vec3f& wo, const Vec3f& wi) {
  if (!(wo.z > 0) || !(wi.z > 0)) return {};
  const Vec3f h = wo + wi;
  const float d = BeckmannD(p.alpha, h);
  if (!(d > 0)) return {};
  // For unit wo, wi: wi·h = wo·h = |wo + wi| / 2 > 0, so χ⁺ holds for both G1 factors.
  const float wi_h = 0.5f * std::sqrt(Dot(h, h));
  const float g = BeckmannG1OverCos(p.alpha, wo) * BeckmannG1OverCos(p.alpha, wi);
  const Color3f f = FresnelConductor(wi_h, p.eta, p.k) * (0.25f * d * g);
  return IsFinite(f) ? f : Color3f{};
}

/// Solid-angle density of ConductorSample: BeckmannReflectionPdf.
inline float ConductorPdf(const ConductorParams& p, const Vec3f& wo, const Vec3f& wi) {
  return BeckmannReflectionPdf(p.alpha, wo, wi);
}

/// Samples h ~ BeckmannPdfH (h-density D cos θh, not the visible normals) and reflects wo.
/// False when wo or the reflected wi is not above the surface. The weight is
/// f cos θi / pdf = F G1(wi) (G1(wo)/cos θo) (wo·H) / H.z with H = wo + wi, where D has
/// cancelled; pdf = ConductorPdf(wo, wi).
inline bool ConductorSample(const ConductorParams& p, const Vec3f& wo, const Vec2f& u,
                            BsdfSample* s) {
  if (!(wo.z > 0)) return false;
  const Vec3f m = SampleBeckmannNormal(p.alpha, u);
  const Vec3f wi = ReflectAbout(wo, m);
  if (!(wi.z > 0)) return false;
  const float pdf = ConductorPdf(p, wo, wi);
  if (!(pdf > 0)) return false;
  const Vec3f h = wo + wi;
  const float g = BeckmannG1(p.alpha, wi) * BeckmannG1OverCos(p.alpha, wo);
  const Color3f w =
      FresnelConductor(0.5f * std::sqrt(Dot(h, h)), p.eta, p.k) * (g * Dot(wo, h) / h.z);
  if (!IsFinite(w)) return false;
  s->wi = wi;
  s->pdf = pdf;
  s->weight = w;
  s->delta = false;
  s->eta = 1.0f;
  return true;
}

}  // namespace ptlab
