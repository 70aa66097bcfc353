// The oracle's robust ray/box slab test, shared by the triangle tree and the instance tree.
#pragma once

#include <cmath>
#include <limits>

#include "engine/bvh/bvh.h"
#include "engine/core/ray.h"

namespace ptlab {

// pbrt-v3 section 3.9.2 (after Ize 2013, "Robust BVH ray traversal"): each slab distance
// (b - o) * (1 / d) carries three roundings, so it is within gamma(3) of the exact value;
// scaling the far end of the interval by 1 + 2 gamma(3) makes the overlap test conservative.
inline constexpr float kMachineEpsilon = std::numeric_limits<float>::epsilon() * 0.5f;
constexpr float Gamma(int n) { return (n * kMachineEpsilon) / (1.0f - n * kMachineEpsilon); }
inline constexpr float kRobustFarScale = 1.0f + 2.0f * Gamma(3);

struct SlabRay {
  Vec3f o;
  Vec3f inv_d;  // 1 / d; a zero component gives +-inf, as intended
  bool neg_x, neg_y, neg_z;
};

inline SlabRay MakeSlabRay(const Ray& ray) {
  SlabRay r;
  r.o = ray.o;
  r.inv_d = {1.0f / ray.d.x, 1.0f / ray.d.y, 1.0f / ray.d.z};
  r.neg_x = std::signbit(r.inv_d.x);
  r.neg_y = std::signbit(r.inv_d.y);
  r.neg_z = std::signbit(r.inv_d.z);
  return r;
}

// Overlap of the ray with the node's box inside [t_min, t_max]; on success *t_entry is where
// the ray enters it. A slab distance that is NaN (0 * inf: the origin lies on the plane of a
// slab the ray is parallel to) fails both comparisons and leaves the interval unchanged,
// which is the conservative answer.
inline bool IntersectBox(const BvhNode& n, const SlabRay& r, float t_min, float t_max,
                         float* t_entry) {
  float t0 = t_min, t1 = t_max;
  const float near_x = ((r.neg_x ? n.bounds_max.x : n.bounds_min.x) - r.o.x) * r.inv_d.x;
  const float far_x = ((r.neg_x ? n.bounds_min.x : n.bounds_max.x) - r.o.x) * r.inv_d.x;
  t0 = near_x > t0 ? near_x : t0;
  t1 = far_x < t1 ? far_x : t1;
  const float near_y = ((r.neg_y ? n.bounds_max.y : n.bounds_min.y) - r.o.y) * r.inv_d.y;
  const float far_y = ((r.neg_y ? n.bounds_min.y : n.bounds_max.y) - r.o.y) * r.inv_d.y;
  t0 = near_y > t0 ? near_y : t0;
  t1 = far_y < t1 ? far_y : t1;
  const float near_z = ((r.neg_z ? n.bounds_max.z : n.bounds_min.z) - r.o.z) * r.inv_d.z;
  const float far_z = ((r.neg_z ? n.bounds_min.z : n.bounds_max.z) - r.o.z) * r.inv_d.z;
  t0 = near_z > t0 ? near_z : t0;
  t1 = far_z < t1 ? far_z : t1;
  *t_entry = t0;
  return t0 <= t1 * kRobustFarScale;
}

}  // namespace ptlab
