// Self-intersection avoidance: offset a surface point along its normal by integer ULPs.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include "engine/core/vec.h"

namespace ptlab {

/// Origin for a ray leaving a surface at hit point p (world space, finite) on the side the
/// unit geometric normal ng points to (callers flip ng to the side they leave on). Wächter &
/// Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems ch. 6:
/// each coordinate moves by 256 * ng[i] units in the last place, so the offset scales with
/// |p| (the error of a computed hit point does too); coordinates within 1/32 of zero, where
/// ULPs get too small, move by a fixed ng[i] / 65536 instead. Never a fixed epsilon overall.
inline Vec3f OffsetRayOrigin(const Vec3f& p, const Vec3f& ng) {
  constexpr float kOrigin = 1.0f / 32.0f;
  constexpr float kFloatScale = 1.0f / 65536.0f;
  constexpr float kIntScale = 256.0f;
  Vec3f out;
  for (int i = 0; i < 3; ++i) {
    // Stepping the bit pattern of a negative float up moves it away from zero, so the step
    // is negated there to move along +ng[i] either way. Unsigned wrap-around is defined.
    const int32_t of_i = static_cast<int32_t>(kIntScale * ng[i]);
    const uint32_t step = static_cast<uint32_t>(p[i] < 0.0f ? -of_i : of_i);
    const float p_i = std::bit_cast<float>(std::bit_cast<uint32_t>(p[i]) + step);
    out[i] = std::fabs(p[i]) < kOrigin ? p[i] + kFloatScale * ng[i] : p_i;
  }
  return out;
}

}  // namespace ptlab
