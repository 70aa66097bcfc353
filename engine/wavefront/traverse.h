// Traversal stage: packets of eight rays against the scene's acceleration structure (slots
// intersect8 and occluded8) and the scalar oracle, each active lane alone through Intersect1 /
// Occluded1 (engine/bvh/intersect1.h); SIMD twin simd::Intersect8 / simd::Occluded8
// (simd/traverse8.h), bit-identical lane by lane.
#pragma once

#include "engine/bvh/bvh.h"
#include "engine/core/packet8.h"

namespace ptlab {

/// The closest hit of every lane in `active` (Intersect1 on `bvh`): a lane that hits gets its
/// hit written into `hits` and its bit in the result; a lane that misses or is inactive is not
/// written.
Mask8 Intersect8(const Bvh& bvh, const RayPacket8& rays, Mask8 active, HitPacket8* hits);

/// The lanes in `active` whose ray is occluded within its interval (Occluded1 on `bvh`).
Mask8 Occluded8(const Bvh& bvh, const RayPacket8& rays, Mask8 active);

}  // namespace ptlab
