// The range a <lookat> transform step accepts, shared by the Nori and Mitsuba readers.
#pragma once

#include <cmath>
#include <string>
#include <utility>

#include "engine/core/vec.h"
#include "engine/io/xml_properties.h"
#include "engine/scene/scene_limits.h"

namespace ptlab {

/// Largest component of a <lookat> `up` vector: its length then stays finite in float.
inline constexpr float kMaxLookatUp = 1e18f;

/// Empty when origin and target lie within the world's range (|coordinate| <= 1e12) and `up`'s
/// components within +-1e18; else what is wrong, naming the attribute and the range. Past those
/// ranges a length overflows float, and the step used to be reported as "up parallel to
/// target - origin", which named neither the cause nor the limit.
inline std::string LookatRangeError(const Vec3f& origin, const Vec3f& target, const Vec3f& up) {
  using internal::FormatNumber;
  const std::pair<const char*, Vec3f> points[] = {{"origin", origin}, {"target", target}};
  for (const auto& [name, v] : points)
    if (!(std::abs(v.x) <= kMaxWorldCoordinate && std::abs(v.y) <= kMaxWorldCoordinate &&
          std::abs(v.z) <= kMaxWorldCoordinate))
      return "<lookat> " + std::string(name) + " (" + FormatNumber(v.x) + ", " +
             FormatNumber(v.y) + ", " + FormatNumber(v.z) +
             ") is out of range; expected components within +-" +
             FormatNumber(kMaxWorldCoordinate);
  if (!(std::abs(up.x) <= kMaxLookatUp && std::abs(up.y) <= kMaxLookatUp &&
        std::abs(up.z) <= kMaxLookatUp))
    return "<lookat> up (" + FormatNumber(up.x) + ", " + FormatNumber(up.y) + ", " +
           FormatNumber(up.z) + ") is out of range; expected components within +-" +
           FormatNumber(kMaxLookatUp);
  return "";
}

}  // namespace ptlab
