// The exact piecewise sRGB transfer curve (IEC 61966-2-1) between linear and encoded values.
#pragma once

#include <cmath>

#include "engine/core/vec.h"

namespace ptlab {

/// Encoded sRGB value in [0, 1] -> linear value. Exact piecewise curve (linear toe below 0.04045).
/// Values outside [0, 1] follow the same formula (the toe for v < 0, the power law for v > 1).
inline float SrgbToLinear(float v) {
  const double d = v;
  return float(d <= 0.04045 ? d / 12.92 : std::pow((d + 0.055) / 1.055, 2.4));
}

/// Linear value -> encoded sRGB value. Exact piecewise curve (linear toe below 0.0031308). No
/// clamping: callers that quantise clamp the result to [0, 1] themselves.
inline float LinearToSrgb(float v) {
  const double d = v;
  return float(d <= 0.0031308 ? d * 12.92 : 1.055 * std::pow(d, 1.0 / 2.4) - 0.055);
}

/// SrgbToLinear on each channel.
inline Color3f SrgbToLinear(const Color3f& c) {
  return {SrgbToLinear(c.r), SrgbToLinear(c.g), SrgbToLinear(c.b)};
}

/// LinearToSrgb on each channel.
inline Color3f LinearToSrgb(const Color3f& c) {
  return {LinearToSrgb(c.r), LinearToSrgb(c.g), LinearToSrgb(c.b)};
}

}  // namespace ptlab
