// What a BSDF's Sample returns: the sampled direction, its weight f·|cos|/pdf and its pdf.
#pragma once

#include "engine/core/vec.h"

namespace ptlab {

/// All directions are in the local shading frame (z = shading normal); wo points to the
/// viewer, wi to the light (pbrt's convention).
struct BsdfSample {
  Vec3f wi;
  Color3f weight;     // f(wo, wi) |cos θi| / pdf, or the delta lobe's throughput
  float pdf = 0.0f;   // solid-angle density; for delta lobes the discrete probability
  bool delta = false; // true for mirror / smooth dielectric lobes
  float eta = 1.0f;   // relative IOR η_t/η_i crossed by a refraction (1 for reflection)
};

inline float CosTheta(const Vec3f& w) { return w.z; }
inline float AbsCosTheta(const Vec3f& w) { return w.z < 0 ? -w.z : w.z; }

}  // namespace ptlab
