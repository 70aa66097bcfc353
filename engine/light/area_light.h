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

/// A batch of area-light samples as columns, row i: light[i] (row in AreaLightTable), the
/// reference point ref (x, y, z) and the numbers u (x, y) of SampleAreaLight.
struct AreaLightBatchInputs {
  const uint32_t* light = nullptr;
  const float *ref_x = nullptr, *ref_y = nullptr, *ref_z = nullptr;
  const float *u_x = nullptr, *u_y = nullptr;
};

/// What a batch writes per row: AreaLightSample's p, n, ng and pdf; its radiance only into
/// le_r, le_g, le_b when they are given (a scene with textured area lights: the radiance is
/// then the point's; otherwise it is the light's, AreaLightTable::radiance). Every row is
/// written; pdf 0 = no valid sample.
struct AreaLightBatchOutputs {
  float *p_x = nullptr, *p_y = nullptr, *p_z = nullptr;
  float *n_x = nullptr, *n_y = nullptr, *n_z = nullptr;
  float *ng_x = nullptr, *ng_y = nullptr, *ng_z = nullptr;
  float* pdf = nullptr;
  float *le_r = nullptr, *le_g = nullptr, *le_b = nullptr;
};

/// SampleAreaLight for n rows: the oracle of simd::SampleAreaLightBatch (simd/wavefront/area_light8.h),
/// bit-identical to SampleAreaLight row by row.
void SampleAreaLightBatch(const Scene& scene, TriangleSampling mode, size_t n,
                          const AreaLightBatchInputs& in, const AreaLightBatchOutputs& out);

/// Writes s into row i of `out`.
inline void SetAreaLightRow(const AreaLightBatchOutputs& out, size_t i, const AreaLightSample& s) {
  out.p_x[i] = s.p.x, out.p_y[i] = s.p.y, out.p_z[i] = s.p.z;
  out.n_x[i] = s.n.x, out.n_y[i] = s.n.y, out.n_z[i] = s.n.z;
  out.ng_x[i] = s.ng.x, out.ng_y[i] = s.ng.y, out.ng_z[i] = s.ng.z;
  out.pdf[i] = s.pdf;
  if (out.le_r != nullptr)
    out.le_r[i] = s.radiance.r, out.le_g[i] = s.radiance.g, out.le_b[i] = s.radiance.b;
}

/// Row i of a batch's inputs as SampleAreaLight's reference point and numbers.
inline Vec3f AreaLightRowRef(const AreaLightBatchInputs& in, size_t i) {
  return {in.ref_x[i], in.ref_y[i], in.ref_z[i]};
}
inline Vec2f AreaLightRowU(const AreaLightBatchInputs& in, size_t i) { return {in.u_x[i], in.u_y[i]}; }

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
