// Uniform sampling of the solid angle a triangle subtends (Arvo 1995, "Stratified Sampling of
// Spherical Triangles"), as a sample / pdf pair: SampleSphericalTriangle, SphericalTrianglePdf.
#pragma once

#include "engine/core/vec.h"

namespace ptlab {

/// Solid angle (sr) of triangle (v0, v1, v2) seen from p, by Van Oosterom and Strackee's
/// formula (in double). 0 for a degenerate triangle or when p lies in its plane.
float SphericalTriangleArea(const Vec3f& v0, const Vec3f& v1, const Vec3f& v2, const Vec3f& p);

/// Solid-angle sampling is used between these bounds (sr); outside them the caller samples by
/// area: below, the sub-triangle construction loses its precision in float/double; above, the
/// triangle covers nearly a hemisphere and the construction's divisions degenerate.
inline constexpr float kMinSphericalTriangleArea = 3e-4f;
inline constexpr float kMaxSphericalTriangleArea = 6.22f;

/// A point on the triangle whose direction from p is uniform over its solid angle.
struct SphericalTriangleSample {
  Vec3f p;          // the point on the triangle
  float b1 = 0, b2 = 0;  // its barycentrics (weights of v1 and v2)
  float pdf = 0;    // solid-angle density, 1 / solid angle
};

/// Samples triangle (v0, v1, v2) uniformly in the solid angle seen from p with u in [0, 1)².
/// Returns false when its solid angle is outside [kMinSphericalTriangleArea,
/// kMaxSphericalTriangleArea] (the caller then samples by area) or not finite.
bool SampleSphericalTriangle(const Vec3f& v0, const Vec3f& v1, const Vec3f& v2, const Vec3f& p,
                             const Vec2f& u, SphericalTriangleSample* out);

/// True when SampleSphericalTriangle would sample this triangle from p (the same test, so that
/// sampling and the pdf of MIS agree).
inline bool UsesSphericalTriangleSampling(float solid_angle) {
  return solid_angle >= kMinSphericalTriangleArea && solid_angle <= kMaxSphericalTriangleArea;
}

}  // namespace ptlab
