// Scalar single-ray BVH traversal: robust slab test, nearer child first, watertight leaves.
#include "engine/bvh/intersect1.h"

#include <cmath>
#include <cstdint>
#include <limits>

#include "engine/bvh/bvh_walk.h"
#include "engine/bvh/instance_level.h"
#include "engine/bvh/sdf_grid_intersect.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/bvh/watertight_triangle.h"

namespace ptlab {
namespace {

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

// The triangles' closest hit (the BVH).
bool IntersectTriangles1(const Bvh& bvh, const Ray& ray, Hit* hit) {
  if (bvh.nodes.empty() || !(ray.t_min < ray.t_max)) return false;
  const WatertightRay wt = MakeWatertightRay(ray.o, ray.d);
  const PermutedColumns cols = PermuteColumns(bvh.leaf_triangles, wt);
  float best_t = ray.t_max;
  uint32_t best_prim = kNoHit;
  float best_b1 = 0.0f, best_b2 = 0.0f;
  WalkBvhClosest(bvh.nodes.data(), MakeSlabRay(ray), ray.t_min, &best_t,
                 [&](const BvhNode& node) {
                   for (uint32_t i = node.offset, end = node.offset + node.count; i < end; ++i) {
                     // The triangle test always gets the ray's own interval, not the closest
                     // hit so far: the set of accepted hits is then independent of visiting
                     // order, and the closest one (lowest row on a tie) is the same as a
                     // brute-force loop's.
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
                 });
  if (best_prim == kNoHit) return false;
  hit->t = best_t;
  hit->b1 = best_b1;
  hit->b2 = best_b2;
  hit->prim = best_prim;
  return true;
}

// Any triangle hit (the BVH).
bool OccludedTriangles1(const Bvh& bvh, const Ray& ray) {
  if (bvh.nodes.empty() || !(ray.t_min < ray.t_max)) return false;
  const WatertightRay wt = MakeWatertightRay(ray.o, ray.d);
  const PermutedColumns cols = PermuteColumns(bvh.leaf_triangles, wt);
  return WalkBvhAny(bvh.nodes.data(), MakeSlabRay(ray), ray.t_min, ray.t_max,
                    [&](const BvhNode& node) {
                      for (uint32_t i = node.offset, end = node.offset + node.count; i < end;
                           ++i) {
                        TriangleHit th;
                        if (IntersectLeafTriangle(cols, i, wt, ray.t_min, ray.t_max, &th))
                          return true;
                      }
                      return false;
                    });
}

bool IntersectGroup1(const void* groups, uint32_t g, const Ray& ray, Hit* hit) {
  return Intersect1(static_cast<const Bvh*>(groups)[g], ray, hit);
}

bool OccludedGroup1(const void* groups, uint32_t g, const Ray& ray) {
  return Occluded1(static_cast<const Bvh*>(groups)[g], ray);
}

}  // namespace

bool Intersect1(const Bvh& bvh, const Ray& ray, Hit* hit) {
  if (!(ray.t_min < ray.t_max)) return false;
  bool found = IntersectTriangles1(bvh, ray, hit);
  // Spheres after the triangles, strictly nearer only: a tie keeps the triangle (the lower id).
  float t_max = found ? hit->t : ray.t_max;
  uint32_t prim = kNoHit;
  if (IntersectSpheres1(bvh.spheres, ray, &t_max, &prim)) {
    hit->t = t_max;
    hit->b1 = hit->b2 = 0.0f;
    hit->prim = prim;
    found = true;
  }
  // Sdfgrids after the spheres, strictly nearer only; nothing to do in a scene without any.
  if (bvh.sdf_grids.size() != 0 && IntersectSdfGrids1(bvh.sdf_grids, ray, &t_max, &prim)) {
    hit->t = t_max;
    hit->b1 = hit->b2 = 0.0f;
    hit->prim = prim;
    found = true;
  }
  // Instances last (their ids lie between the triangle rows and the spheres').
  if (bvh.instances.empty()) return found;
  return IntersectInstances(bvh.instances, ray, found, hit, IntersectGroup1, bvh.groups.data());
}

bool Occluded1(const Bvh& bvh, const Ray& ray) {
  if (!(ray.t_min < ray.t_max)) return false;
  if (OccludedTriangles1(bvh, ray) || OccludedSpheres1(bvh.spheres, ray)) return true;
  if (bvh.sdf_grids.size() != 0 && OccludedSdfGrids1(bvh.sdf_grids, ray)) return true;
  return !bvh.instances.empty() &&
         OccludedInstances(bvh.instances, ray, OccludedGroup1, bvh.groups.data());
}

}  // namespace ptlab
