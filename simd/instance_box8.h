// The instance tree's box test for the eight lanes of a packet at once (the packet instance
// walk of simd/traverse8.cpp): the oracle's IntersectBox per lane, in vectors.
#pragma once

#include <cstdint>

#include "engine/bvh/bvh.h"
#include "engine/core/packet8.h"

namespace ptlab::simd {

/// Per lane: origin, 1 / d (MakeSlabRay's division) and t_min; lanes not built from a ray hold
/// benign values that enter no box.
struct alignas(32) InstanceLanes {
  float o[3][8], inv[3][8], t_min[8];
};

/// The lanes of `rays` in `live`.
InstanceLanes MakeInstanceLanes(const RayPacket8& rays, Mask8 live);

/// The lanes whose ray enters the node's box in [t_min, t_far[j]] by IntersectBox's test (the
/// same slab distances, comparisons and robust far scale, so the same answer lane by lane);
/// t_entry[j]: each lane's entry distance. t_far and t_entry are eight floats, 32-byte aligned
/// (loaded and stored aligned). Highway-dispatched.
Mask8 InstanceBoxLanes(const BvhNode& node, const InstanceLanes& lanes, const float* t_far,
                       float* t_entry);

}  // namespace ptlab::simd
