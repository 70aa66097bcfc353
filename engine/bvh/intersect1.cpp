// Scalar single-ray BVH traversal: robust slab test, nearer child first, watertight leaves.
#include "engine/bvh/intersect1.h"

#include <cmath>
#include <cstdint>
#include <limits>

#include "engine/bvh/sphere_intersect.h"
#include "engine/bvh/watertight_triangle.h"
#include "engine/core/check.h"

namespace ptlab {
namespace {

// pbrt-v3 section 3.9.2 (after Ize 2013, "Robust BVH ray traversal"): each slab distance
// (b - o) * (1 / d) carries three roundings, so it is within gamma(3) of the exact value;
// scaling the far end of the interval by 1 + 2 gamma(3) makes the overlap test conservative.
constexpr float kMachineEpsilon = std::numeric_limits<float>::epsilon() * 0.5f;
constexpr float Gamma(int n) { return (n * kMachineEpsilon) / (1.0f - n * kMachineEpsilon); }
constexpr float kRobustFarScale = 1.0f + 2.0f * Gamma(3);

struct SlabRay {
  Vec3f o;
  Vec3f inv_d;  // 1 / d; a zero component gives +-inf, as intended
  bool neg_x, neg_y, neg_z;
};

SlabRay MakeSlabRay(const Ray& ray) {
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

// Leaf-ordered vertex columns permuted to the watertight ray's (kx, ky, kz) axes, chosen
// once per ray so the leaf loop reads them without branching.
struct PermutedColumns {
  const float *ax, *ay, *az, *bx, *by, *bz, *cx, *cy, *cz;
};

PermutedColumns PermuteColumns(const TriangleTable& t, const WatertightRay& r) {
  const float* v0[3] = {t.v0_x.data(), t.v0_y.data(), t.v0_z.data()};
  const float* v1[3] = {t.v1_x.data(), t.v1_y.data(), t.v1_z.data()};
  const float* v2[3] = {t.v2_x.data(), t.v2_y.data(), t.v2_z.data()};
  return {v0[r.kx], v0[r.ky], v0[r.kz], v1[r.kx], v1[r.ky], v1[r.kz], v2[r.kx], v2[r.ky], v2[r.kz]};
}

inline bool IntersectLeafTriangle(const PermutedColumns& c, uint32_t i, const WatertightRay& r,
                                  float t_min, float t_max, TriangleHit* hit) {
  return IntersectTriangleWatertightPermuted(r, c.ax[i], c.ay[i], c.az[i], c.bx[i], c.by[i],
                                             c.bz[i], c.cx[i], c.cy[i], c.cz[i], t_min, t_max, hit);
}

struct StackEntry {
  uint32_t node;
  float t_entry;
};

// The triangles' closest hit (the BVH).
bool IntersectTriangles1(const Bvh& bvh, const Ray& ray, Hit* hit) {
  if (bvh.nodes.empty() || !(ray.t_min < ray.t_max)) return false;
  const BvhNode* nodes = bvh.nodes.data();
  const SlabRay slab = MakeSlabRay(ray);
  const WatertightRay wt = MakeWatertightRay(ray.o, ray.d);
  const PermutedColumns cols = PermuteColumns(bvh.leaf_triangles, wt);

  float best_t = ray.t_max;
  uint32_t best_prim = kNoHit;
  float best_b1 = 0.0f, best_b2 = 0.0f;
  StackEntry stack[kBvhMaxDepth];
  int stack_size = 0;
  float t_entry;
  if (!IntersectBox(nodes[0], slab, ray.t_min, best_t, &t_entry)) return false;
  uint32_t current = 0;
  for (;;) {
    const BvhNode& node = nodes[current];
    if (!node.IsLeaf()) {
      const uint32_t left = current + 1, right = node.offset;
      float t_left, t_right;
      const bool hit_left = IntersectBox(nodes[left], slab, ray.t_min, best_t, &t_left);
      const bool hit_right = IntersectBox(nodes[right], slab, ray.t_min, best_t, &t_right);
      if (hit_left && hit_right) {
        PTLAB_DCHECK(stack_size < kBvhMaxDepth);
        if (t_right < t_left) {
          stack[stack_size++] = {left, t_left};
          current = right;
        } else {
          stack[stack_size++] = {right, t_right};
          current = left;
        }
        continue;
      }
      if (hit_left || hit_right) {
        current = hit_left ? left : right;
        continue;
      }
    } else {
      for (uint32_t i = node.offset, end = node.offset + node.count; i < end; ++i) {
        // The triangle test always gets the ray's own interval, not the closest hit so far:
        // the set of accepted hits is then independent of visiting order, and the closest
        // one (lowest row on a tie) is the same as a brute-force loop's.
        TriangleHit th;
        if (!IntersectLeafTriangle(cols, i, wt, ray.t_min, ray.t_max, &th)) continue;
        const uint32_t prim = bvh.prim_id[i];
        if (th.t < best_t || (th.t == best_t && prim < best_prim)) {
          best_t = th.t;
          best_prim = prim;
          best_b1 = th.b1;
          best_b2 = th.b2;
        }
      }
    }
    // Pop the next subtree that may still hold a hit at or before the closest one.
    for (;;) {
      if (stack_size == 0) {
        if (best_prim == kNoHit) return false;
        hit->t = best_t;
        hit->b1 = best_b1;
        hit->b2 = best_b2;
        hit->prim = best_prim;
        return true;
      }
      const StackEntry& e = stack[--stack_size];
      if (e.t_entry <= best_t * kRobustFarScale) {
        current = e.node;
        break;
      }
    }
  }
}

// Any triangle hit (the BVH).
bool OccludedTriangles1(const Bvh& bvh, const Ray& ray) {
  if (bvh.nodes.empty() || !(ray.t_min < ray.t_max)) return false;
  const BvhNode* nodes = bvh.nodes.data();
  const SlabRay slab = MakeSlabRay(ray);
  const WatertightRay wt = MakeWatertightRay(ray.o, ray.d);
  const PermutedColumns cols = PermuteColumns(bvh.leaf_triangles, wt);

  uint32_t stack[kBvhMaxDepth];
  int stack_size = 0;
  float t_entry;
  if (!IntersectBox(nodes[0], slab, ray.t_min, ray.t_max, &t_entry)) return false;
  uint32_t current = 0;
  for (;;) {
    const BvhNode& node = nodes[current];
    if (!node.IsLeaf()) {
      const uint32_t left = current + 1, right = node.offset;
      float t_left, t_right;
      const bool hit_left = IntersectBox(nodes[left], slab, ray.t_min, ray.t_max, &t_left);
      const bool hit_right = IntersectBox(nodes[right], slab, ray.t_min, ray.t_max, &t_right);
      if (hit_left && hit_right) {
        PTLAB_DCHECK(stack_size < kBvhMaxDepth);
        const bool right_first = t_right < t_left;
        stack[stack_size++] = right_first ? left : right;
        current = right_first ? right : left;
        continue;
      }
      if (hit_left || hit_right) {
        current = hit_left ? left : right;
        continue;
      }
    } else {
      for (uint32_t i = node.offset, end = node.offset + node.count; i < end; ++i) {
        TriangleHit th;
        if (IntersectLeafTriangle(cols, i, wt, ray.t_min, ray.t_max, &th)) return true;
      }
    }
    if (stack_size == 0) return false;
    current = stack[--stack_size];
  }
}

}  // namespace

bool Intersect1(const Bvh& bvh, const Ray& ray, Hit* hit) {
  if (!(ray.t_min < ray.t_max)) return false;
  const bool triangle = IntersectTriangles1(bvh, ray, hit);
  // Spheres after the triangles, strictly nearer only: a tie keeps the triangle (the lower id).
  float t_max = triangle ? hit->t : ray.t_max;
  uint32_t prim = kNoHit;
  if (!IntersectSpheres1(bvh.spheres, ray, &t_max, &prim)) return triangle;
  hit->t = t_max;
  hit->b1 = hit->b2 = 0.0f;
  hit->prim = prim;
  return true;
}

bool Occluded1(const Bvh& bvh, const Ray& ray) {
  if (!(ray.t_min < ray.t_max)) return false;
  return OccludedTriangles1(bvh, ray) || OccludedSpheres1(bvh.spheres, ray);
}

}  // namespace ptlab
