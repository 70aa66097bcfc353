// Ray-sphere intersection (scalar oracle of simd/traverse8's sphere kernel) and sphere hit ids.
#pragma once

#include <cmath>
#include <cstdint>

#include "engine/bvh/bvh.h"
#include "engine/core/ray.h"
#include "engine/scene/sphere_table.h"

namespace ptlab {

/// Hit::prim of a hit on sphere row i is kSphereHitBit | i; triangle rows stay below 2^28.
inline constexpr uint32_t kSphereHitBit = 0x80000000u;
inline constexpr uint32_t kMaxSpheres = 1u << 28;
/// (Bit 30 set as well is an sdfgrid hit: engine/bvh/sdf_grid_intersect.h.)
constexpr bool IsSphereHit(uint32_t prim) {
  return prim != kNoHit && (prim & kSphereHitBit) && !(prim & 0x40000000u);
}
constexpr uint32_t SphereHitRow(uint32_t prim) { return prim & ~kSphereHitBit; }

/// c = |o − centre|² − r², in double: o − centre is exact there, so a ray origin pushed a few
/// ulps off a large sphere (OffsetRayOrigin) keeps its side. In float, o − centre alone
/// already rounds that push away (ulp(10⁴) ≈ 10⁻³), c loses its sign and c/q finds the surface
/// the ray starts on. Shared by IntersectSphere1 and simd/traverse8's kernel (per lane).
inline float SphereOriginC(float ox, float oy, float oz, float cx, float cy, float cz, float r) {
  const double fx = double(ox) - double(cx), fy = double(oy) - double(cy),
               fz = double(oz) - double(cz);
  return float((fx * fx + fy * fy) + fz * fz - double(r) * double(r));
}

/// The point of the sphere nearest to p and the unit outward normal there (pbrt-v4 re-projects
/// a computed hit point o + t d so). In double, so the point is as exact as its own float
/// coordinates allow even when |centre| ≫ r: c + r n in float would carry the rounding of the
/// centre's magnitude, more than OffsetRayOrigin's push where |p| is small. A p at the centre
/// gets the normal +z.
inline Vec3f ProjectOntoSphere(const Vec3f& p, const Vec3f& c, float r, Vec3f* n) {
  const double fx = double(p.x) - double(c.x), fy = double(p.y) - double(c.y),
               fz = double(p.z) - double(c.z);
  const double len = std::sqrt((fx * fx + fy * fy) + fz * fz);
  if (!(len > 0)) {
    *n = {0, 0, 1};
    return {c.x, c.y, c.z + r};
  }
  const double nx = fx / len, ny = fy / len, nz = fz / len;
  *n = {float(nx), float(ny), float(nz)};
  return {float(double(c.x) + double(r) * nx), float(double(c.y) + double(r) * ny),
          float(double(c.z) + double(r) * nz)};
}

/// The first t in the open interval (ray.t_min, t_max) where `ray` (d non-zero, finite) meets
/// the sphere of centre (cx, cy, cz) and radius r; false when there is none. Rays starting
/// inside find the exit. The quadratic a t² + 2 b t + c = 0 is solved as in Ray Tracing Gems
/// ch. 7 (Haines et al., "Precision Improvements for Ray/Sphere Intersection"): the
/// discriminant b² − a c is formed as a (r² − |f − (b/a) d|²), f = o − centre, which keeps its
/// precision for small spheres far from the origin, and the two roots as q/a and c/q with
/// q = −(b + sign(b) √disc), so neither suffers cancellation; c comes from SphereOriginC. Every
/// operation is a single IEEE rounding in a fixed order (no FMA), the contract simd/traverse8's
/// 8-wide twin meets bit for bit.
inline bool IntersectSphere1(float cx, float cy, float cz, float r, const Ray& ray, float t_max,
                             float* t) {
  const float fx = ray.o.x - cx, fy = ray.o.y - cy, fz = ray.o.z - cz;
  const float dx = ray.d.x, dy = ray.d.y, dz = ray.d.z;
  const float a = (dx * dx + dy * dy) + dz * dz;
  const float b = (fx * dx + fy * dy) + fz * dz;
  const float r2 = r * r;
  const float c = SphereOriginC(ray.o.x, ray.o.y, ray.o.z, cx, cy, cz, r);
  const float s = b / a;
  const float vx = fx - s * dx, vy = fy - s * dy, vz = fz - s * dz;
  const float disc = r2 - ((vx * vx + vy * vy) + vz * vz);
  if (!(disc >= 0.0f)) return false;
  const float root = std::sqrt(a * disc);
  const float q = b < 0.0f ? root - b : -(b + root);
  float t0 = q / a, t1 = c / q;
  if (t0 > t1) {
    const float swap = t0;
    t0 = t1;
    t1 = swap;
  }
  if (t0 > ray.t_min && t0 < t_max) {
    *t = t0;
    return true;
  }
  if (t1 > ray.t_min && t1 < t_max) {
    *t = t1;
    return true;
  }
  return false;
}

/// Closest sphere hit of `ray` before *t_max: updates *t_max and *prim (kSphereHitBit | row)
/// for each sphere met nearer, in row order (ties keep the earlier hit). Every sphere is
/// tested: scenes hold a handful, so they sit beside the triangle BVH, not in it.
inline bool IntersectSpheres1(const SphereTable& spheres, const Ray& ray, float* t_max,
                              uint32_t* prim) {
  bool found = false;
  for (uint32_t i = 0; i < spheres.size(); ++i) {
    float t = 0.0f;
    if (IntersectSphere1(spheres.center_x[i], spheres.center_y[i], spheres.center_z[i],
                         spheres.radius[i], ray, *t_max, &t)) {
      *t_max = t;
      *prim = kSphereHitBit | i;
      found = true;
    }
  }
  return found;
}

/// True when `ray` meets any sphere with t in (ray.t_min, ray.t_max).
inline bool OccludedSpheres1(const SphereTable& spheres, const Ray& ray) {
  float t = 0.0f;
  for (uint32_t i = 0; i < spheres.size(); ++i)
    if (IntersectSphere1(spheres.center_x[i], spheres.center_y[i], spheres.center_z[i],
                         spheres.radius[i], ray, ray.t_max, &t))
      return true;
  return false;
}

}  // namespace ptlab
