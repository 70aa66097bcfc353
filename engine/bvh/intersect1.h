// Scalar single-ray BVH traversal: closest hit and any hit (the oracle for simd/traverse8).
#pragma once

#include "engine/bvh/bvh.h"
#include "engine/core/ray.h"

namespace ptlab {

/// Closest hit of `ray` (world space, d non-zero and finite) with t in the open interval
/// (ray.t_min, ray.t_max), using the watertight triangle test. Returns true and fills *hit
/// (t, barycentrics, scene triangle row) on a hit; leaves *hit untouched on a miss. Among
/// hits with the same (bit-identical) t the lowest scene row wins, so the result does not
/// depend on the tree: it equals a brute-force loop over all triangles with the same test.
/// No allocation; stack of kBvhMaxDepth entries.
bool Intersect1(const Bvh& bvh, const Ray& ray, Hit* hit);

/// True when `ray` hits any triangle with t in (ray.t_min, ray.t_max); exits at the first
/// hit found. Returns exactly what Intersect1 would return for the same ray.
bool Occluded1(const Bvh& bvh, const Ray& ray);

}  // namespace ptlab
