// Mitsuba 3 `conductor`: a smooth metal, the mirror's delta lobe weighted by the conductor
// Fresnel term of its complex IOR and a specular reflectance.
#pragma once

#include "engine/bsdf/fresnel.h"
#include "engine/bsdf/mirror.h"

namespace ptlab {

/// MirrorSample with weight R F(cos θo; η, κ) (Born & Wolf, FresnelConductor); η = κ = 0 and
/// Mitsuba's material "none" (η = 0, κ = 1) both give F = 1 exactly, the plain mirror.
inline bool SmoothConductorSample(const Color3f& reflectance, const Color3f& eta, const Color3f& k,
                                  const Vec3f& wo, BsdfSample* s) {
  if (!MirrorSample(reflectance, wo, s)) return false;
  s->weight *= FresnelConductor(wo.z, eta, k);
  return true;
}

}  // namespace ptlab
