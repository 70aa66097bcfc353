// Perfect specular reflection (Nori `mirror`): a delta lobe with weight 1.
#pragma once

#include "engine/bsdf/bsdf_sample.h"

namespace ptlab {

inline bool MirrorSample(const Vec3f& wo, BsdfSample* s) {
  if (!(CosTheta(wo) > 0)) return false;
  s->wi = {-wo.x, -wo.y, wo.z};
  s->weight = {1, 1, 1};
  s->pdf = 1.0f;
  s->delta = true;
  s->eta = 1.0f;
  return true;
}

}  // namespace ptlab
