// Traversal stage, the scalar oracle (engine/wavefront/traverse.h).
#include "engine/wavefront/traverse.h"

#include <bit>

#include "engine/bvh/intersect1.h"

namespace ptlab {

Mask8 Intersect8(const Bvh& bvh, const RayPacket8& rays, Mask8 active, HitPacket8* hits) {
  Mask8 got = 0;
  for (Mask8 todo = active & kAllLanes; todo != 0; todo &= todo - 1) {
    const int j = std::countr_zero(todo);
    Hit h;
    if (!Intersect1(bvh, GetLaneRay(rays, j), &h)) continue;
    SetLaneHit(hits, j, h.t, h.b1, h.b2, h.prim);
    got |= LaneBit(j);
  }
  return got;
}

Mask8 Occluded8(const Bvh& bvh, const RayPacket8& rays, Mask8 active) {
  Mask8 got = 0;
  for (Mask8 todo = active & kAllLanes; todo != 0; todo &= todo - 1) {
    const int j = std::countr_zero(todo);
    if (Occluded1(bvh, GetLaneRay(rays, j))) got |= LaneBit(j);
  }
  return got;
}

}  // namespace ptlab
