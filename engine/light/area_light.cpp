// Area lights: uniform sampling by area over an emitting mesh, and emitted radiance.
#include "engine/light/area_light.h"

#include <algorithm>
#include <cmath>

#include "engine/render/interaction.h"
#include "engine/sampling/guide_table.h"
#include "engine/sampling/spherical_triangle.h"

namespace ptlab {

Vec3f ShadingNormalAt(const Scene& scene, uint32_t tri, float b1, float b2) {
  const TriangleShadingTable& sh = scene.shading;
  const uint32_t i0 = sh.vertex0[tri];
  if (i0 != kNoVertex && !scene.vertices.n_x.empty()) {
    const VertexTable& v = scene.vertices;
    const uint32_t i1 = sh.vertex1[tri], i2 = sh.vertex2[tri];
    const float b0 = 1.0f - b1 - b2;
    const Vec3f n{b0 * v.n_x[i0] + b1 * v.n_x[i1] + b2 * v.n_x[i2],
                  b0 * v.n_y[i0] + b1 * v.n_y[i1] + b2 * v.n_y[i2],
                  b0 * v.n_z[i0] + b1 * v.n_z[i1] + b2 * v.n_z[i2]};
    const float len = Length(n);
    if (len > 0) return n / len;
  }
  const TriangleTable& t = scene.triangles;
  const Vec3f ng = Cross(t.V1(tri) - t.V0(tri), t.V2(tri) - t.V0(tri));
  const float len = Length(ng);
  return len > 0 ? ng / len : Vec3f{0, 0, 1};
}

namespace {

// Solid-angle sampling pays off only for triangles that look large from ref: below
// kSolidAngleWorthIt the density of area sampling varies across the triangle by about its
// angular size (~0.1 rad), and Arvo's construction costs more than it saves. A float estimate
// A |cos| / d² at the centroid skips the exact solid angle for triangles far below it.
constexpr float kSolidAngleWorthIt = 0.01f;

// The solid angle of triangle tri from ref when SampleAreaLight and AreaLightPdf sample it by
// solid angle (the same test in both), else 0.
float SolidAngleSampled(const TriangleTable& t, uint32_t tri, const Vec3f& ref) {
  const Vec3f v0 = t.V0(tri), v1 = t.V1(tri), v2 = t.V2(tri);
  const Vec3f n2 = Cross(v1 - v0, v2 - v0);  // 2 A n
  const Vec3f d = (v0 + v1 + v2) * (1.0f / 3.0f) - ref;
  const float dist2 = Dot(d, d);
  // 0.5 |n2 · d| / d³ against half the threshold (the estimate is not a bound for large
  // triangles, so anything near the threshold is decided by the exact solid angle).
  if (dist2 > 0 && 0.5f * std::abs(Dot(n2, d)) < 0.5f * kSolidAngleWorthIt * dist2 * std::sqrt(dist2))
    return 0.0f;
  const float omega = SphericalTriangleArea(v0, v1, v2, ref);
  return omega >= kSolidAngleWorthIt && UsesSphericalTriangleSampling(omega) ? omega : 0.0f;
}

float TriangleArea(const TriangleTable& t, uint32_t tri) {
  return 0.5f * Length(Cross(t.V1(tri) - t.V0(tri), t.V2(tri) - t.V0(tri)));
}

// Area density at p turned into solid-angle density at ref (n: the light's normal at p).
float AreaToSolidAngle(float pdf_area, const Vec3f& p, const Vec3f& n, const Vec3f& ref) {
  const Vec3f d = p - ref;
  const float dist2 = Dot(d, d);
  if (!(dist2 > 0)) return 0.0f;
  const float cos_l = -Dot(n, d) / std::sqrt(dist2);
  if (!(cos_l > 0)) return 0.0f;
  return pdf_area * dist2 / cos_l;
}

}  // namespace

AreaLightTrianglePick PickAreaLightTriangle(const Scene& scene, uint32_t light, float u_x) {
  const AreaLightTable& lights = scene.area_lights;
  const uint32_t mesh = lights.mesh[light];
  const uint32_t count = scene.meshes.triangle_count[mesh];
  const float* cdf = lights.triangle_cdf.data() + lights.cdf_offset[light];
  const uint32_t* guide = lights.triangle_guide.data() + lights.guide_offset[light];
  // u_x within the triangle's CDF interval goes on to the point, so that a stratified u stays
  // stratified over the whole light.
  const CdfPick pick = PickCdfBin(cdf, count, guide, u_x);
  return {scene.meshes.first_triangle[mesh] + pick.bin, pick.u_remapped};
}

AreaLightSample SampleAreaLight(const Scene& scene, uint32_t light, const Vec3f& ref,
                                TriangleSampling mode, Vec2f u) {
  const AreaLightTable& lights = scene.area_lights;
  AreaLightSample s;
  if (!(lights.area[light] > 0)) return s;
  const AreaLightTrianglePick pick = PickAreaLightTriangle(scene, light, u.x);
  const uint32_t tri = pick.tri;
  u.x = pick.u_x;
  const TriangleTable& t = scene.triangles;
  const Vec3f ng = Cross(t.V1(tri) - t.V0(tri), t.V2(tri) - t.V0(tri));
  s.radiance = lights.radiance[light];
  SphericalTriangleSample st;
  if (mode == TriangleSampling::kSolidAngle && SolidAngleSampled(t, tri, ref) > 0 &&
      SampleSphericalTriangle(t.V0(tri), t.V1(tri), t.V2(tri), ref, u, &st)) {
    s.p = st.p;
    s.n = ShadingNormalAt(scene, tri, st.b1, st.b2);
    s.ng = Length(ng) > 0 ? Normalize(ng) : s.n;
    // The triangle is picked with probability area_tri / area_light.
    const float d = Dot(s.n, s.p - ref);
    s.pdf = d < 0 ? st.pdf * TriangleArea(t, tri) / lights.area[light] : 0.0f;
    if (lights.Textured(light))
      s.radiance = AreaLightRadianceAt(
          scene, light, TexturePoint{SurfaceUvAt(scene, tri, st.b1, st.b2), s.p, tri});
    return s;
  }
  const Vec2f b = SampleUniformTriangle(u);
  s.p = t.V0(tri) * (1.0f - b.x - b.y) + t.V1(tri) * b.x + t.V2(tri) * b.y;
  s.n = ShadingNormalAt(scene, tri, b.x, b.y);
  s.ng = Length(ng) > 0 ? Normalize(ng) : s.n;
  s.pdf = AreaToSolidAngle(1.0f / lights.area[light], s.p, s.n, ref);
  if (lights.Textured(light))
    s.radiance = AreaLightRadianceAt(scene, light,
                                     TexturePoint{SurfaceUvAt(scene, tri, b.x, b.y), s.p, tri});
  return s;
}

float AreaLightPdf(const Scene& scene, uint32_t light, uint32_t tri, const Vec3f& p,
                   const Vec3f& n, const Vec3f& ref, TriangleSampling mode) {
  const AreaLightTable& lights = scene.area_lights;
  if (!(lights.area[light] > 0)) return 0.0f;
  if (mode == TriangleSampling::kSolidAngle) {
    const TriangleTable& t = scene.triangles;
    if (const float omega = SolidAngleSampled(t, tri, ref); omega > 0) {
      if (!(Dot(n, p - ref) < 0)) return 0.0f;
      return TriangleArea(t, tri) / (lights.area[light] * omega);
    }
  }
  return AreaToSolidAngle(1.0f / lights.area[light], p, n, ref);
}

}  // namespace ptlab
