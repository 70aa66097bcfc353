// Scalar single-ray BVH traversal: closest hit and any hit (the oracle for simd/traverse8).
#pragma once

#include "engine/bvh/bvh.h"
#include "engine/core/ray.h"

namespace ptlab {

/// Closest hit of `ray` (world space, d non-zero and finite) with t in the open interval
/// (ray.t_min, ray.t_max), using the watertight triangle test and IntersectSphere1 for the
/// bvh's spheres (all of them, after the tree). Returns true and fills *hit (t, barycentrics,
/// scene triangle row; or t, b1 = b2 = 0 and kSphereHitBit | sphere row) on a hit; leaves *hit
/// untouched on a miss. Among hits with the same (bit-identical) t the lowest id wins
/// (triangles before spheres), so the result does not depend on the tree: it equals a
/// brute-force loop over all triangles and spheres with the same tests.
/// No allocation; stack of kBvhMaxDepth entries.
bool Intersect1(const Bvh& bvh, const Ray& ray, Hit* hit);

/// True when `ray` hits any triangle or sphere with t in (ray.t_min, ray.t_max); exits at the first
/// hit found. Returns exactly what Intersect1 would return for the same ray.
bool Occluded1(const Bvh& bvh, const Ray& ray);

}  // namespace ptlab
