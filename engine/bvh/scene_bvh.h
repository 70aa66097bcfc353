// The BVH of a whole scene: its triangles and spheres, and with instancing the two levels.
#pragma once

#include "engine/bvh/bvh.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// BuildBvh(scene.triangles, scene.spheres) for a scene without shape groups (the same tree,
/// bit for bit). With shape groups (scene.instances): the top tree over the triangle rows that
/// belong to no group (prim_id = their scene rows), one BVH per group over its rows in group
/// space (prim_id = the row's index within the group), and the instance level
/// (BuildInstanceLevel) whose hits carry the instanced ids of InstanceTable. The scene's (or
/// the top) tree is built on `threads` threads (engine/bvh/bvh_build.h): the same tree for any
/// count.
Bvh BuildSceneBvh(const Scene& scene, int threads = 1);

}  // namespace ptlab
