// Instancing's top level: building the instance tree, the ray into a group's space, and the
// closest-hit / any-hit walks over the instances that the oracle and simd/ share.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/bvh/bvh.h"
#include "engine/core/ray.h"
#include "engine/scene/instance_table.h"

namespace ptlab {

/// World box of one group (its BVH root's), or lo > hi for a group nothing can hit.
struct GroupBounds {
  Vec3f lo, hi;
};

/// The instance level of `instances` for a scene of `triangle_rows` triangle rows: each
/// instance's world box (its group's box's eight corners through to_world, padded outwards by
/// 1e-5 of its largest coordinate magnitude, since the ray meets the group in group space),
/// a median-split tree over them (one instance per leaf), and the world-to-group transforms.
/// Instances of a group nothing can hit are left out.
InstanceLevel BuildInstanceLevel(const InstanceTable& instances, uint32_t triangle_rows,
                                 const std::vector<GroupBounds>& group_bounds);

/// `ray` in the space of instance i: o and d through the world-to-group transform (affine, so
/// t keeps its meaning: the group-space hit at t is the world hit at t), the same interval.
/// One out-of-line function, so every caller gets the same bits.
Ray RayToInstance(const InstanceLevel& level, uint32_t i, const Ray& ray);

/// Closest hit of a ray in group g's BVH (group space), for IntersectInstances: the oracle
/// passes ptlab::Intersect1 on its group Bvhs, simd/ its BVH8 twin.
using GroupIntersectFn = bool (*)(const void* groups, uint32_t g, const Ray& ray, Hit* hit);
using GroupOccludedFn = bool (*)(const void* groups, uint32_t g, const Ray& ray);

/// The instances' part of a closest hit: every instance whose box the ray enters before the
/// best hit so far is met in its group's space with the ray's own interval, and its hit (id
/// first_prim + the group's prim) replaces *best when nearer, or as near with a lower id. So the
/// result is the least (t, id) over all candidates whatever the visiting order. `found`: *best
/// holds a hit already (from the triangles and spheres of the top level). Returns whether *best
/// holds a hit now.
bool IntersectInstances(const InstanceLevel& level, const Ray& ray, bool found, Hit* best,
                        GroupIntersectFn intersect, const void* groups);

/// Whether any instance occludes `ray` (t in (t_min, t_max)).
bool OccludedInstances(const InstanceLevel& level, const Ray& ray, GroupOccludedFn occluded,
                       const void* groups);

}  // namespace ptlab
