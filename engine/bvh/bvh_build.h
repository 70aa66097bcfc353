// BuildBvh on several threads (engine/bvh/bvh_build.cpp; the one-thread overloads are in bvh.h).
#pragma once

#include "engine/bvh/bvh.h"

namespace ptlab {

/// BuildBvh(triangles, spheres) on `threads` threads (a table of fewer than 16,384 triangles
/// is built on one): the top of the tree on the calling thread, its largest nodes binned by
/// two, and the subtrees below it by `threads` threads. The tree is the same bit for bit for
/// any thread count.
Bvh BuildBvh(const TriangleTable& triangles, const SphereTable& spheres, int threads);

}  // namespace ptlab
