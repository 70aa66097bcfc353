// Area lights: uniform sampling by area over an emitting mesh, and emitted radiance.
#pragma once

#include <algorithm>
#include <cstdint>

#include "engine/core/vec.h"
#include "engine/scene/scene.h"
#include "engine/sampling/warp.h"

namespace ptlab {

/// A point sampled on a light: position, its shading normal n (which decides the emitting
/// side), its unit geometric normal ng (for offsetting shadow rays), the radiance it emits, and
/// the area density of the sample on that light (1 / area).
struct AreaLightSample {
  Vec3f p, n, ng;
  Color3f radiance;
  float pdf_area = 0.0f;
};

/// Normal at barycentrics (b1, b2) of triangle `tri`: the interpolated vertex normal when the
/// mesh has normals, else the geometric normal (both unit length).
Vec3f ShadingNormalAt(const Scene& scene, uint32_t tri, float b1, float b2);

/// Samples light `light` (row in AreaLightTable) uniformly by area: u_tri picks the triangle
/// (∝ area), u the point within it.
AreaLightSample SampleAreaLight(const Scene& scene, uint32_t light, float u_tri, const Vec2f& u);

/// Radiance leaving a light point with normal n towards direction w (unit, pointing away from
/// the light): one-sided, zero behind the surface.
inline Color3f AreaLightRadiance(const Color3f& radiance, const Vec3f& n, const Vec3f& w) {
  return Dot(n, w) > 0 ? radiance : Color3f{};
}

}  // namespace ptlab
