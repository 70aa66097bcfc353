// Shared BSDF test inputs: adversarial parameter/direction/sample sets and random generators.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/bsdf/beckmann.h"
#include "engine/core/rng.h"
#include "engine/core/vec.h"
#include "engine/sampling/warp.h"

namespace ptlab::bsdf_test {

/// Roughness values of the hard-case list, plus values the clamp must absorb.
inline std::vector<float> HardAlphas() {
  return {0.0f, 1e-30f, 1e-4f, 1e-3f, 0.005f, 0.05f, 0.5f, 1.0f, 2.0f, 1e30f};
}

/// Relative IORs: 1, 1 ± 1e-6, 1.5, 1/1.5, Nori's default, and values the clamp must absorb.
inline std::vector<float> HardEtas() {
  return {1.0f, 1.0f + 1e-6f, 1.0f - 1e-6f, 1.5f, 1.0f / 1.5f, 1.5046f / 1.000277f, 1e-30f, 1e30f};
}

/// Cosines: exactly 0, denormal, tiny, grazing, ordinary, 1, and below the surface.
inline std::vector<float> HardCosines() {
  return {0.0f, 1e-45f, 1e-40f, 1e-30f,  1e-12f, 1e-7f, 1e-4f, 1e-2f,
          0.5f, 0.999f, 1.0f,   -1e-40f, -1e-4f, -0.5f, -1.0f};
}

/// Sample coordinates: the ends of [0, 1) and denormal/tiny values.
inline std::vector<float> HardUs() {
  return {0.0f, 1e-45f, 1e-30f, 0x1p-25f, 0.25f, 0.5f, 0.75f, kOneMinusEpsilon};
}

/// A unit direction with the given cosine and azimuth (sin θ from 1 − cos², exactly 1 for
/// denormal cosines).
inline Vec3f DirectionWithCos(float c, float phi) {
  const float s = std::sqrt(std::max(0.0f, (1.0f - c) * (1.0f + c)));
  return {s * std::cos(phi), s * std::sin(phi), c};
}

/// Hard directions: every HardCosines value at a few azimuths (incl. axis-aligned ones), the
/// critical angles of η = 1.5 from both sides, and non-unit vectors with huge or denormal
/// components (outside the preconditions; only finiteness is required for those).
inline std::vector<Vec3f> HardDirections(bool with_non_unit = true) {
  std::vector<Vec3f> dirs;
  for (float c : HardCosines())
    for (float phi : {0.0f, 0.7f, kPi / 2, kPi, 4.0f}) dirs.push_back(DirectionWithCos(c, phi));
  const float cos_crit = std::sqrt(1.0f - 1.0f / (1.5f * 1.5f));  // sin θc = 1/1.5
  dirs.push_back(DirectionWithCos(cos_crit, 0.3f));
  dirs.push_back(DirectionWithCos(-cos_crit, 0.3f));
  if (with_non_unit) {
    dirs.push_back({1e30f, 0.0f, 1e30f});
    dirs.push_back({3e38f, -3e38f, 3e38f});
    dirs.push_back({1e-40f, 0.0f, 1e-40f});
    dirs.push_back({0.0f, 0.0f, 0.0f});
  }
  return dirs;
}

/// A random unit direction on the upper hemisphere with cos θ log-uniform in [1e-4, 1] (so
/// grazing angles are well represented).
inline Vec3f RandomUpperDirection(Pcg32& rng) {
  const float c = std::pow(10.0f, -4.0f * rng.NextFloat());
  return DirectionWithCos(c, 2.0f * kPi * rng.NextFloat());
}

/// α log-uniform in [1e-3, 1].
inline float RandomAlpha(Pcg32& rng) { return std::pow(10.0f, -3.0f * rng.NextFloat()); }

/// A direction pair where wi is the Beckmann reflection of wo about a sampled normal, so that
/// D(h) is not negligible (random pairs would mostly give D = 0 for small α).
inline Vec3f NearSpecularPartner(float alpha, const Vec3f& wo, Pcg32& rng) {
  const float u1 = rng.NextFloat();
  return ReflectAbout(wo, SampleBeckmannNormal(alpha, {u1, rng.NextFloat()}));
}

}  // namespace ptlab::bsdf_test
