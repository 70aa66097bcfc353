// Smooth dielectric (Nori `dielectric`): reflect with probability F, refract otherwise.
#pragma once

#include <cmath>
#include <cstdint>

#include "engine/bsdf/bsdf_sample.h"
#include "engine/bsdf/fresnel.h"
#include "engine/scene/material_tables.h"

namespace ptlab {

/// Samples the delta lobes of a smooth interface; eta = intIOR / extIOR (clamped to
/// [1e-4, 1e4]), the normal points to the exterior and wo may be on either side.
/// `flags` (DielectricFlags, a column of DielectricTable):
/// - default: exact unpolarised Fresnel term; reflection is chosen with probability F (so the
///   weight is 1), total internal reflection (also exactly at the critical angle) always
///   reflects. Radiance is not scaled on refraction: Nori's convention, its references were
///   rendered that way.
/// - kDielectricSchlick: F by Schlick's approximation with the cosine of wo (CS184 GlassBSDF);
///   TIR is still detected exactly.
/// - kDielectricScaleRadiance: refraction multiplies the weight by (η_o/η_i)², the squared ratio
///   of the IOR on wo's side to the one on wi's side (pbrt's TransportMode::Radiance), because
///   radiance L/η² is what is conserved across the interface.
/// - kDielectricRefractOnly: the reflection lobe is dropped (CS184 RefractionBSDF): refraction
///   has probability 1 and weight 1 (or the radiance scale); under total internal reflection
///   nothing is sampled (false).
/// pdf is the discrete probability of the chosen lobe; s->eta is η_i/η_o (η on wi's side over
/// η on wo's side) for refraction, 1 for reflection. Eval and Pdf of this model are 0.
inline bool DielectricSample(float eta, const Vec3f& wo, float u, BsdfSample* s,
                             uint8_t flags = 0) {
  eta = ClampRelativeIor(eta);
  float cos_t = 0;
  const float cos_o = CosTheta(wo);
  float f = FresnelDielectric(cos_o, eta, &cos_t);
  if ((flags & kDielectricSchlick) && f < 1.0f) f = FresnelSchlick(cos_o, eta);
  if (flags & kDielectricRefractOnly) {
    if (f >= 1.0f) return false;  // total internal reflection: no refracted direction
    f = 0.0f;
  }
  s->delta = true;
  s->weight = {1, 1, 1};
  if (u < f) {
    s->wi = {-wo.x, -wo.y, wo.z};
    s->pdf = f;
    s->eta = 1.0f;
    return true;
  }
  // Refraction (Snell): rel = η_o/η_i, the relative index seen from wo's side.
  const float rel = cos_o > 0 ? 1.0f / eta : eta;
  s->wi = {-wo.x * rel, -wo.y * rel, cos_o > 0 ? -cos_t : cos_t};
  if (!std::isfinite(s->wi.x) || !std::isfinite(s->wi.y)) return false;  // non-unit huge wo
  s->pdf = 1.0f - f;
  s->eta = 1.0f / rel;
  if (flags & kDielectricScaleRadiance) s->weight = {rel * rel, rel * rel, rel * rel};
  return true;
}

}  // namespace ptlab
