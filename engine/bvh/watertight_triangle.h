// Watertight ray-triangle intersection (Woop, Benthin & Wald 2013, JCGT 2(1)), scalar.
#pragma once

#include <cmath>
#include <utility>

#include "engine/core/vec.h"

namespace ptlab {

/// Per-ray state of the watertight test (the paper's ray precomputation): the axis kz
/// where |d| is largest and the two others kx, ky (swapped when d[kz] < 0 to keep the
/// winding), the shear constants and the origin permuted to (kx, ky, kz).
struct WatertightRay {
  int kx = 0, ky = 1, kz = 2;
  float sx = 0.0f, sy = 0.0f, sz = 1.0f;
  float ox = 0.0f, oy = 0.0f, oz = 0.0f;
};

/// Result of a watertight triangle test: distance in units of |d| and the barycentrics of v1
/// and v2.
struct TriangleHit {
  float t = 0.0f;
  float b1 = 0.0f, b2 = 0.0f;
};

/// Precomputes the watertight-test state for a ray with origin o and direction d (world
/// space, d non-zero and finite, need not be normalised).
inline WatertightRay MakeWatertightRay(const Vec3f& o, const Vec3f& d) {
  WatertightRay r;
  r.kz = MaxDimension(Abs(d));
  r.kx = r.kz == 2 ? 0 : r.kz + 1;
  r.ky = r.kx == 2 ? 0 : r.kx + 1;
  if (d[r.kz] < 0.0f) std::swap(r.kx, r.ky);
  r.sx = d[r.kx] / d[r.kz];
  r.sy = d[r.ky] / d[r.kz];
  r.sz = 1.0f / d[r.kz];
  r.ox = o[r.kx];
  r.oy = o[r.ky];
  r.oz = o[r.kz];
  return r;
}

/// 2-D edge function px * qy - py * qx of the sheared edge from p to q. Watertightness needs
/// the two triangles sharing an edge, which see it in opposite directions, to get exact
/// negatives of each other. Plain float arithmetic guarantees that, but a compiler that fuses
/// one product into an FMA (-ffp-contract=fast with an FMA target) breaks it; evaluating the
/// endpoints in a canonical order and negating restores it either way. Without fusion the
/// result equals the plain formula (up to the sign of a zero).
inline float WatertightEdgeFunction(float px, float py, float qx, float qy) {
  const bool swap = qx < px || (qx == px && qy < py);
  const float ax = swap ? qx : px, ay = swap ? qy : py;
  const float bx = swap ? px : qx, by = swap ? py : qy;
  const float e = ax * by - ay * bx;
  return swap ? -e : e;
}

/// The watertight test on vertices whose coordinates were already permuted to the ray's
/// (kx, ky, kz) axes: ax = v0[kx], ay = v0[ky], az = v0[kz], likewise b* for v1, c* for v2.
/// Reports a hit when the ray crosses the triangle (either side: no backface culling) at a
/// distance t with t_min < t < t_max; fills *hit only then. A ray through an edge or vertex
/// shared by several triangles hits at least one of them, also when compiled with FMA
/// contraction. A triangle with a repeated vertex never hits (det is exactly 0).
inline bool IntersectTriangleWatertightPermuted(const WatertightRay& r, float ax, float ay,
                                                float az, float bx, float by, float bz, float cx,
                                                float cy, float cz, float t_min, float t_max,
                                                TriangleHit* hit) {
  // Vertices relative to the ray origin.
  const float a_kx = ax - r.ox, a_ky = ay - r.oy, a_kz = az - r.oz;
  const float b_kx = bx - r.ox, b_ky = by - r.oy, b_kz = bz - r.oz;
  const float c_kx = cx - r.ox, c_ky = cy - r.oy, c_kz = cz - r.oz;
  // Shear so that the ray becomes the +z axis through the origin.
  const float a_x = a_kx - r.sx * a_kz, a_y = a_ky - r.sy * a_kz;
  const float b_x = b_kx - r.sx * b_kz, b_y = b_ky - r.sy * b_kz;
  const float c_x = c_kx - r.sx * c_kz, c_y = c_ky - r.sy * c_kz;
  // Scaled barycentrics: 2-D edge functions of the sheared triangle at the origin.
  // U weights v0, V weights v1, W weights v2.
  float u = WatertightEdgeFunction(c_x, c_y, b_x, b_y);  // c_x b_y - c_y b_x
  float v = WatertightEdgeFunction(a_x, a_y, c_x, c_y);  // a_x c_y - a_y c_x
  float w = WatertightEdgeFunction(b_x, b_y, a_x, a_y);  // b_x a_y - b_y a_x
  // On an edge in float: decide it again in double, where the products are exact, so that
  // the ray is not lost between two triangles (paper, double-precision fallback). Exact
  // products also make the difference the same with or without FMA fusion.
  if (u == 0.0f || v == 0.0f || w == 0.0f) {
    const double cx_by = static_cast<double>(c_x) * static_cast<double>(b_y);
    const double cy_bx = static_cast<double>(c_y) * static_cast<double>(b_x);
    u = static_cast<float>(cx_by - cy_bx);
    const double ax_cy = static_cast<double>(a_x) * static_cast<double>(c_y);
    const double ay_cx = static_cast<double>(a_y) * static_cast<double>(c_x);
    v = static_cast<float>(ax_cy - ay_cx);
    const double bx_ay = static_cast<double>(b_x) * static_cast<double>(a_y);
    const double by_ax = static_cast<double>(b_y) * static_cast<double>(a_x);
    w = static_cast<float>(bx_ay - by_ax);
  }
  // No backface culling: the edge functions must share a sign (zeros allowed).
  if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f)) return false;
  const float det = u + v + w;
  if (det == 0.0f) return false;
  // Scaled hit distance T = t * det.
  const float s_az = r.sz * a_kz, s_bz = r.sz * b_kz, s_cz = r.sz * c_kz;
  const float t_scaled = u * s_az + v * s_bz + w * s_cz;
  // t_min < T / det < t_max without a division: flip T by det's sign.
  const float abs_det = std::fabs(det);
  const float signed_t = det < 0.0f ? -t_scaled : t_scaled;
  if (!(signed_t > t_min * abs_det) || !(signed_t < t_max * abs_det)) return false;
  const float rcp_det = 1.0f / det;
  const float t = t_scaled * rcp_det;
  // The rounded quotient can land on the interval's end points; the interval is open.
  if (!(t > t_min) || !(t < t_max)) return false;
  hit->t = t;
  hit->b1 = v * rcp_det;
  hit->b2 = w * rcp_det;
  return true;
}

/// Watertight test of the ray prepared in `r` against triangle (v0, v1, v2) in world space;
/// see IntersectTriangleWatertightPermuted.
inline bool IntersectTriangleWatertight(const WatertightRay& r, const Vec3f& v0, const Vec3f& v1,
                                        const Vec3f& v2, float t_min, float t_max,
                                        TriangleHit* hit) {
  return IntersectTriangleWatertightPermuted(r, v0[r.kx], v0[r.ky], v0[r.kz], v1[r.kx], v1[r.ky],
                                             v1[r.kz], v2[r.kx], v2[r.ky], v2[r.kz], t_min, t_max,
                                             hit);
}

}  // namespace ptlab
