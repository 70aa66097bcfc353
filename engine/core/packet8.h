// 8-wide ray and hit packets: plain aligned SoA arrays (no Highway types), like Embree's RTCRay8.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/ray.h"

namespace ptlab {

inline constexpr size_t kPacketWidth = 8;

/// Bit i = lane i active.
using Mask8 = uint32_t;
inline constexpr Mask8 kAllLanes = 0xffu;

/// The bit of lane j (0 <= j < 8) in a Mask8.
constexpr Mask8 LaneBit(int j) { return Mask8{1} << j; }

/// Whether lane j of `m` is set.
constexpr bool LaneActive(Mask8 m, int j) { return ((m >> j) & 1u) != 0; }

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

/// Lane j of a packet as a single ray.
inline Ray GetLaneRay(const RayPacket8& p, int j) {
  return Ray{{p.org_x[j], p.org_y[j], p.org_z[j]},
             {p.dir_x[j], p.dir_y[j], p.dir_z[j]},
             p.t_min[j],
             p.t_max[j]};
}

/// Writes `r` into lane j of a packet.
inline void SetLaneRay(RayPacket8* p, int j, const Ray& r) {
  p->org_x[j] = r.o.x, p->org_y[j] = r.o.y, p->org_z[j] = r.o.z;
  p->dir_x[j] = r.d.x, p->dir_y[j] = r.d.y, p->dir_z[j] = r.d.z;
  p->t_min[j] = r.t_min, p->t_max[j] = r.t_max;
}

/// Writes one hit (Hit of engine/bvh/bvh.h, field by field) into lane j.
inline void SetLaneHit(HitPacket8* h, int j, float t, float b1, float b2, uint32_t prim) {
  h->t[j] = t, h->b1[j] = b1, h->b2[j] = b2, h->prim[j] = prim;
}

}  // namespace ptlab
