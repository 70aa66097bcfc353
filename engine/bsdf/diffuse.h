// Lambertian BRDF (Nori `diffuse`): f = albedo / π on the upper hemisphere, cosine sampling.
#pragma once

#include "engine/bsdf/bsdf_sample.h"
#include "engine/sampling/warp.h"

namespace ptlab {

/// One-sided, as in Nori: zero unless both wo and wi are above the shading surface.
inline Color3f DiffuseEval(const Color3f& albedo, const Vec3f& wo, const Vec3f& wi) {
  if (!(CosTheta(wo) > 0) || !(CosTheta(wi) > 0)) return {};
  return albedo * kInvPi;
}
inline float DiffusePdf(const Vec3f& wo, const Vec3f& wi) {
  if (!(CosTheta(wo) > 0) || !(CosTheta(wi) > 0)) return 0.0f;
  return CosineHemispherePdf(wi);
}
/// Cosine-weighted sampling; the weight f cos / pdf is exactly the albedo.
inline bool DiffuseSample(const Color3f& albedo, const Vec3f& wo, const Vec2f& u, BsdfSample* s) {
  if (!(CosTheta(wo) > 0)) return false;
  s->wi = SampleCosineHemisphere(u);
  s->pdf = CosineHemispherePdf(s->wi);
  if (!(s->pdf > 0)) return false;
  s->weight = albedo;
  s->delta = false;
  s->eta = 1.0f;
  return true;
}

}  // namespace ptlab
