// Mitsuba `thindielectric` rows: a thin slab with two parallel smooth interfaces (SoA).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/aligned.h"
#include "engine/core/vec.h"

namespace ptlab {

/// eta = int_ior / ext_ior; reflectance / transmittance tint the reflected and the transmitted
/// sample (Mitsuba's specular_reflectance and specular_transmittance, default 1).
struct ThinDielectricTable {
  AlignedVector<float> eta, reflectance_r, reflectance_g, reflectance_b, transmittance_r,
      transmittance_g, transmittance_b;
  size_t size() const { return eta.size(); }
  uint32_t Add(float e, const Color3f& refl, const Color3f& trans) {
    eta.push_back(e);
    reflectance_r.push_back(refl.r), reflectance_g.push_back(refl.g),
        reflectance_b.push_back(refl.b);
    transmittance_r.push_back(trans.r), transmittance_g.push_back(trans.g),
        transmittance_b.push_back(trans.b);
    return uint32_t(size() - 1);
  }
  Color3f Reflectance(size_t i) const {
    return {reflectance_r[i], reflectance_g[i], reflectance_b[i]};
  }
  Color3f Transmittance(size_t i) const {
    return {transmittance_r[i], transmittance_g[i], transmittance_b[i]};
  }
};

}  // namespace ptlab
