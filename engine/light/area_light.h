// Area lights: sampling points of an emitting mesh (a triangle by area, then a point uniform by
// area or by the solid angle seen from the shading point), their densities, emitted radiance.
#pragma once

#include <algorithm>
#include <cstdint>

#include "engine/core/vec.h"
#include "engine/scene/scene.h"
#include "engine/sampling/warp.h"
#include "engine/texture/texture.h"

namespace ptlab {

/// A point sampled on a light: position, its shading normal n (which decides the emitting
/// side), its unit geometric normal ng (for offsetting shadow rays), the radiance it emits, and
/// the solid-angle density of the sample's direction seen from the reference point (0: no
/// valid sample, e.g. the point is behind the light or coincides with the reference point).
struct AreaLightSample {
  Vec3f p, n, ng;
  Color3f radiance;
  float pdf = 0.0f;
};

/// Normal at barycentrics (b1, b2) of triangle `tri`: the interpolated vertex normal when the
/// mesh has normals, else the geometric normal (both unit length).
Vec3f ShadingNormalAt(const Scene& scene, uint32_t tri, float b1, float b2);

/// Samples light `light` (row in AreaLightTable) for the reference point ref: u.x picks the
/// triangle (∝ area) and, rescaled to the triangle's share, goes on with u.y to the point within
/// it, uniform by area or (kSolidAngle) uniform in the triangle's solid angle from ref where
/// that is accurate (UsesSphericalTriangleSampling). One 2-D point for the whole light keeps a
/// stratified point set stratified across its triangles.
AreaLightSample SampleAreaLight(const Scene& scene, uint32_t light, const Vec3f& ref,
                                TriangleSampling mode, Vec2f u);

/// The triangle SampleAreaLight picks on light `light` (area > 0) with u_x, and u_x rescaled to
/// that triangle's share of the CDF (uniform in [0, 1) again), which goes on to the point.
struct AreaLightTrianglePick {
  uint32_t tri;  // row in TriangleTable
  float u_x;
};
AreaLightTrianglePick PickAreaLightTriangle(const Scene& scene, uint32_t light, float u_x);

/// Solid-angle density with which SampleAreaLight(light, ref, mode) produces the point p on
/// triangle tri of the light, whose shading normal there is n; 0 when p faces away from ref.
float AreaLightPdf(const Scene& scene, uint32_t light, uint32_t tri, const Vec3f& p,
                   const Vec3f& n, const Vec3f& ref, TriangleSampling mode);

/// Radiance of area light `light` at a point of it (surface uv, position p, triangle prim),
/// either side: its constant radiance, or its texture at uv (Mitsuba's area emitter with a
/// textured radiance). Every evaluation of an area light's radiance goes through here.
inline Color3f AreaLightRadianceAt(const Scene& scene, uint32_t light, const TexturePoint& at) {
  const AreaLightTable& lights = scene.area_lights;
  if (!lights.Textured(light)) return lights.radiance[light];
  return EvalTexture(scene.textures, lights.texture[light], at);
}

/// Radiance leaving a light point with normal n towards direction w (unit, pointing away from
/// the light): one-sided, zero behind the surface.
inline Color3f AreaLightRadiance(const Color3f& radiance, const Vec3f& n, const Vec3f& w) {
  return Dot(n, w) > 0 ? radiance : Color3f{};
}

}  // namespace ptlab
