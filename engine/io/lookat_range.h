// The range a <lookat> transform step accepts, shared by the Nori and Mitsuba readers.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "engine/core/vec.h"
#include "engine/scene/scene_limits.h"

namespace ptlab {

/// Largest component of a <lookat> `up` vector: its length then stays finite in float.
inline constexpr float kMaxLookatUp = 1e18f;

/// Empty when origin and target lie within the world's range (|coordinate| <= 1e12) and `up`'s
/// components within +-1e18; else what is wrong, naming the attribute and the range. Past those
/// ranges a length overflows float, and the step used to be reported as "up parallel to
/// target - origin", which named neither the cause nor the limit.
inline std::string LookatRangeError(const Vec3f& origin, const Vec3f& target, const Vec3f& up) {
  const auto number = [](float v) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%g", double(v));
    return std::string(buffer);
  };
  const std::pair<const char*, Vec3f> points[] = {{"origin", origin}, {"target", target}, {"up", up}};
  for (const auto& [name, v] : points) {
    const float limit = std::string(name) == "up" ? kMaxLookatUp : kMaxWorldCoordinate;
    if (std::abs(v.x) <= limit && std::abs(v.y) <= limit && std::abs(v.z) <= limit) continue;
    return "<lookat> " + std::string(name) + " (" + number(v.x) + ", " + number(v.y) + ", " +
           number(v.z) + ") is out of range; expected components within +-" + number(limit);
  }
  return "";
}

}  // namespace ptlab
