// 8-wide ray and hit packets: plain aligned SoA arrays (no Highway types), like Embree's RTCRay8.
#pragma once

#include <cstddef>
#include <cstdint>

namespace ptlab {

inline constexpr size_t kPacketWidth = 8;

/// Bit i = lane i active.
using Mask8 = uint32_t;
inline constexpr Mask8 kAllLanes = 0xffu;

/// Eight rays o + t d, t in (t_min, t_max), world space; the same contract per lane as Ray.
struct alignas(32) RayPacket8 {
  float org_x[8], org_y[8], org_z[8];
  float dir_x[8], dir_y[8], dir_z[8];
  float t_min[8], t_max[8];
};

/// Closest hits: t, barycentrics of v1 and v2, and the scene triangle row (0xffffffff = none).
struct alignas(32) HitPacket8 {
  float t[8];
  float b1[8], b2[8];
  uint32_t prim[8];
};

}  // namespace ptlab
