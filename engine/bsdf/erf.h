// Single-precision erf and erf⁻¹ as short polynomial forms, so that a SIMD twin can repeat them.
#pragma once

#include <cmath>

namespace ptlab {

// std::erf has no vector form and the standard library has no erf⁻¹ (Boost.Math's erf_inv is a
// double-precision scalar routine); the microfacet sampler (engine/bsdf/microfacet.h) and its
// 8-wide twin need both, operation for operation alike. These are the published forms:
// Abramowitz & Stegun 7.1.26 for erf (|error| ≤ 1.5e-7) and Giles 2010, "Approximating the
// erfinv function" (GPU Computing Gems), single-precision branch, for erf⁻¹ (relative error
// ≲ 4e-7 away from ±1, before float rounding).

inline constexpr float kInvSqrtPi = 0.56418958354775628695f;

/// erf(x) within 1.5e-7 absolute (plus float rounding); odd; ±1 at ±∞; NaN → NaN.
inline float ErfApprox(float x) {
  const float a = std::fabs(x);
  const float t = 1.0f / (1.0f + 0.3275911f * a);
  const float poly =
      t * (0.254829592f +
           t * (-0.284496736f + t * (1.421413741f + t * (-1.453152027f + t * 1.061405429f))));
  const float r = 1.0f - poly * std::exp(-(a * a));
  return std::copysign(r, x);
}

/// Inputs of ErfInvApprox are clamped into [−kErfInvMaxArg, kErfInvMaxArg] (NaN → the lower
/// end), the largest float below 1, so the result is finite (|erf⁻¹| ≤ 3.82).
inline constexpr float kErfInvMaxArg = 0x1.fffffep-1f;

/// erf⁻¹(x) (Giles 2010, single precision); x clamped as above.
inline float ErfInvApprox(float x) {
  x = !(x > -kErfInvMaxArg) ? -kErfInvMaxArg : (x < kErfInvMaxArg ? x : kErfInvMaxArg);
  float w = -std::log((1.0f - x) * (1.0f + x));
  float p;
  if (w < 5.0f) {
    w = w - 2.5f;
    p = 2.81022636e-08f;
    p = 3.43273939e-07f + p * w;
    p = -3.5233877e-06f + p * w;
    p = -4.39150654e-06f + p * w;
    p = 0.00021858087f + p * w;
    p = -0.00125372503f + p * w;
    p = -0.00417768164f + p * w;
    p = 0.246640727f + p * w;
    p = 1.50140941f + p * w;
  } else {
    w = std::sqrt(w) - 3.0f;
    p = -0.000200214257f;
    p = 0.000100950558f + p * w;
    p = 0.00134934322f + p * w;
    p = -0.00367342844f + p * w;
    p = 0.00573950773f + p * w;
    p = -0.0076224613f + p * w;
    p = 0.00943887047f + p * w;
    p = 1.00167406f + p * w;
    p = 2.83297682f + p * w;
  }
  return p * x;
}

}  // namespace ptlab
