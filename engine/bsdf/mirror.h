// Specular reflection (Nori `mirror`, CS184's MirrorBSDF): a delta lobe weighted by the
// reflectance (1 1 1 for a perfect mirror).
#pragma once

#include "engine/bsdf/bsdf_sample.h"

namespace ptlab {

inline bool MirrorSample(const Color3f& reflectance, const Vec3f& wo, BsdfSample* s) {
  if (!(CosTheta(wo) > 0)) return false;
  s->wi = {-wo.x, -wo.y, wo.z};
  s->weight = reflectance;
  s->pdf = 1.0f;
  s->delta = true;
  s->eta = 1.0f;
  return true;
}

}  // namespace ptlab
