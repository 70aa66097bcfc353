// Mitsuba `thindielectric`: a thin slab, delta reflection or straight-through transmission.
#pragma once

#include "engine/bsdf/bsdf_sample.h"
#include "engine/bsdf/fresnel.h"

namespace ptlab {

/// Reflectance of a thin slab of relative IOR eta (= int_ior / ext_ior) at |cos θ| = |cos_o|,
/// every internal bounce included: with R the one-interface Fresnel term and T = 1 − R, the
/// rays leaving on the incident side sum to R + T² R (1 + R² + R⁴ + …) = R + T² R / (1 − R²)
/// = 2R / (1 + R). The slab is symmetric, so the side of wo does not matter; TIR (R = 1) gives 1.
inline float ThinDielectricReflectance(float cos_o, float eta) {
  float cos_t;
  const float r = FresnelDielectric(ClampCosine(cos_o), eta, &cos_t);
  return 2.0f * r / (1.0f + r);
}

/// Samples the two delta lobes: u < R reflects (wi = (−x, −y, z), pdf R, weight
/// `reflectance`), else the ray goes straight through (wi = −wo, pdf 1 − R, weight
/// `transmittance`); the slab displaces nothing and bends nothing, so eta stays 1. Eval and Pdf
/// of this model are 0.
inline bool ThinDielectricSample(float eta, const Color3f& reflectance,
                                 const Color3f& transmittance, const Vec3f& wo, float u,
                                 BsdfSample* s) {
  const float r = ThinDielectricReflectance(wo.z, eta);
  s->delta = true;
  s->eta = 1.0f;
  if (u < r) {
    s->wi = {-wo.x, -wo.y, wo.z};
    s->pdf = r;
    s->weight = reflectance;
  } else {
    s->wi = {-wo.x, -wo.y, -wo.z};
    s->pdf = 1.0f - r;
    s->weight = transmittance;
  }
  return s->pdf > 0;
}

}  // namespace ptlab
