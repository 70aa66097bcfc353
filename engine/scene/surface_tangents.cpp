// normal: the uv tangents ∂p/∂u, ∂p/∂v of every triangle.
#include "engine/scene/surface_tangents.h"

#include <cmath>

#include "engine/core/frame.h"

namespace ptlab {
namespace {

bool Finite(const Vec3f& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

void TriangleTangents(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2, const Vec2f& uv0,
                      const Vec2f& uv1, const Vec2f& uv2, const Vec3f& ng, Vec3f* dp_du,
                      Vec3f* dp_dv) {
  const Vec2f d1{uv1.x - uv0.x, uv1.y - uv0.y}, d2{uv2.x - uv0.x, uv2.y - uv0.y};
  const Vec3f e1 = p1 - p0, e2 = p2 - p0;
  const float det = d1.x * d2.y - d1.y * d2.x;
  if (det != 0) {
    const float inv = 1.0f / det;
    const Vec3f du = (e1 * d2.y - e2 * d1.y) * inv, dv = (e2 * d1.x - e1 * d2.x) * inv;
    if (Finite(du) && Finite(dv)) {
      *dp_du = du, *dp_dv = dv;
      return;
    }
  }
  const Frame f(ng);
  *dp_du = f.s, *dp_dv = f.t;
}

void BuildSurfaceTangents(Scene* scene) {
  ShadingPerturbations& p = scene->materials.perturbation;
  if (p.empty()) return;
  const TriangleTable& t = scene->triangles;
  const TriangleShadingTable& sh = scene->shading;
  const VertexTable& v = scene->vertices;
  const size_t n = t.size();
  for (auto* c : {&p.dp_du_x, &p.dp_du_y, &p.dp_du_z, &p.dp_dv_x, &p.dp_dv_y, &p.dp_dv_z})
    c->assign(n, 0.0f);
  for (size_t i = 0; i < n; ++i) {
    const Vec3f p0 = t.V0(i), p1 = t.V1(i), p2 = t.V2(i);
    const Vec3f g = Cross(p1 - p0, p2 - p0);
    const float len = Length(g);
    const Vec3f ng = len > 0 && std::isfinite(len) ? g / len : Vec3f{0, 0, 1};
    Vec2f uv0{0, 0}, uv1{1, 0}, uv2{0, 1};  // barycentric: uv = (b1, b2)
    if (scene->meshes.has_uvs[sh.mesh[i]]) {
      const uint32_t a = sh.vertex0[i], b = sh.vertex1[i], c = sh.vertex2[i];
      uv0 = {v.u[a], v.v[a]}, uv1 = {v.u[b], v.v[b]}, uv2 = {v.u[c], v.v[c]};
    }
    Vec3f du, dv;
    TriangleTangents(p0, p1, p2, uv0, uv1, uv2, ng, &du, &dv);
    p.dp_du_x[i] = du.x, p.dp_du_y[i] = du.y, p.dp_du_z[i] = du.z;
    p.dp_dv_x[i] = dv.x, p.dp_dv_y[i] = dv.y, p.dp_dv_z[i] = dv.z;
  }
}

}  // namespace ptlab
