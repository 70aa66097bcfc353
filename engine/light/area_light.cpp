// Area lights: uniform sampling by area over an emitting mesh, and emitted radiance.
#include "engine/light/area_light.h"

#include <algorithm>

#include "engine/sampling/guide_table.h"

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

AreaLightSample SampleAreaLight(const Scene& scene, uint32_t light, float u_tri, const Vec2f& u) {
  const AreaLightTable& lights = scene.area_lights;
  const uint32_t mesh = lights.mesh[light];
  const uint32_t count = scene.meshes.triangle_count[mesh];
  const float* cdf = lights.triangle_cdf.data() + lights.cdf_offset[light];
  const uint32_t* guide = lights.triangle_guide.data() + lights.guide_offset[light];
  const uint32_t k = std::min<uint32_t>(GuidedUpperBound(cdf, count, guide, u_tri), count - 1);
  const uint32_t tri = scene.meshes.first_triangle[mesh] + k;
  const Vec2f b = SampleUniformTriangle(u);
  const TriangleTable& t = scene.triangles;
  AreaLightSample s;
  s.p = t.V0(tri) * (1.0f - b.x - b.y) + t.V1(tri) * b.x + t.V2(tri) * b.y;
  s.n = ShadingNormalAt(scene, tri, b.x, b.y);
  const Vec3f ng = Cross(t.V1(tri) - t.V0(tri), t.V2(tri) - t.V0(tri));
  s.ng = Length(ng) > 0 ? Normalize(ng) : s.n;
  s.radiance = lights.radiance[light];
  s.pdf_area = lights.area[light] > 0 ? 1.0f / lights.area[light] : 0.0f;
  return s;
}

}  // namespace ptlab
