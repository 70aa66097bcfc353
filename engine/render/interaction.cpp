// The shading point of a ray hit: position, normals and the components the hit refers to.
#include "engine/render/interaction.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "engine/bvh/sdf_grid_intersect.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/render/sdf_grid_normal.h"
#include "engine/light/area_light.h"

namespace ptlab {

namespace {

// A sphere hit: o + t d carries the error of t; re-projected onto the sphere (pbrt-v4,
// Physically Based Rendering 4th ed., §6.8.5) it is as exact as the surface allows.
void SphereInteraction(const Scene& scene, const Ray& ray, const Hit& hit, bool with_uv,
                       SurfaceInteraction& its) {
  const uint32_t i = SphereHitRow(hit.prim);
  const SphereTable& s = scene.spheres;
  Vec3f n;
  its.p = ProjectOntoSphere(ray.At(hit.t), s.Center(i), s.radius[i], &n);
  its.prim = hit.prim;
  its.ng = n;
  its.frame = Frame(n);
  if (with_uv) {
    // In the sphere's own frame (Mitsuba's to_object), then SphereUv.
    const SphereUvFrame& q = s.uv_frame[i];
    its.uv = SphereUv({q[0] * n.x + q[1] * n.y + q[2] * n.z, q[3] * n.x + q[4] * n.y + q[5] * n.z,
                       q[6] * n.x + q[7] * n.y + q[8] * n.z});
  }
  its.material = s.material[i];
}

// An sdfgrid hit: p = o + t d (t is the cubic's root to double precision, rounded), the
// normals of SdfGridNormals, uv (0, 0) as Mitsuba's sdfgrid (it has no parameterization).
void SdfGridInteraction(const Scene& scene, const Ray& ray, const Hit& hit,
                        SurfaceInteraction& its) {
  const uint32_t i = SdfGridHitRow(hit.prim);
  its.p = ray.At(hit.t);
  Vec3f ng, ns;
  SdfGridNormals(scene.sdf_grids, i, its.p, &ng, &ns);
  its.prim = hit.prim;
  its.ng = ng;
  its.frame = Frame(ns);
  its.uv = {0.0f, 0.0f};
  its.material = scene.sdf_grids.material[i];
}

}  // namespace

Vec2f SurfaceUvAt(const Scene& scene, uint32_t tri, float b1, float b2) {
  const TriangleShadingTable& sh = scene.shading;
  if (!scene.meshes.has_uvs[sh.mesh[tri]]) return {b1, b2};
  const VertexTable& v = scene.vertices;
  const uint32_t i0 = sh.vertex0[tri], i1 = sh.vertex1[tri], i2 = sh.vertex2[tri];
  const float b0 = 1.0f - b1 - b2;
  return {b0 * v.u[i0] + b1 * v.u[i1] + b2 * v.u[i2], b0 * v.v[i0] + b1 * v.v[i1] + b2 * v.v[i2]};
}

Vec2f SphereUv(const Vec3f& n) {
  float phi = std::atan2(n.y, n.x);
  if (phi < 0) phi += 2 * kPi;
  // atan2 of a tiny negative y rounds phi + 2π up to 2π; u stays in [0, 1).
  const float u = std::min(phi * kInv2Pi, kOneMinusEpsilon);
  return {u, std::acos(std::clamp(n.z, -1.0f, 1.0f)) * kInvPi};
}

namespace {

void TriangleInteraction(const Scene& scene, uint32_t tri, const Hit& hit, bool with_uv,
                         SurfaceInteraction& its);

// A hit on an instanced triangle: the interaction of its group row in group space, then its
// point through the instance's to_world and both normals through its inverse transpose
// (renormalized), as Mitsuba transforms them. Groups hold no emitters.
void InstanceInteraction(const Scene& scene, const Hit& hit, bool with_uv,
                         SurfaceInteraction& its) {
  const InstancedRow at = FindInstancedRow(scene.instances, scene.triangles.size(), hit.prim);
  TriangleInteraction(scene, at.row, hit, with_uv, its);
  const Transform& to_world = scene.instances.to_world[at.instance];
  its.prim = hit.prim;
  its.p = to_world.ApplyPoint(its.p);
  const Vec3f ng = to_world.ApplyNormal(its.ng), n = to_world.ApplyNormal(its.frame.n);
  const float ng_len = Length(ng), n_len = Length(n);
  its.ng = ng_len > 0 ? ng / ng_len : Vec3f{0, 0, 1};
  its.frame = Frame(n_len > 0 ? n / n_len : its.ng);
  its.emitter = EmitterRef::None();
}

// A hit on scene triangle row `tri` (in the space its vertices are stored in).
void TriangleInteraction(const Scene& scene, uint32_t tri, const Hit& hit, bool with_uv,
                         SurfaceInteraction& its) {
  const TriangleTable& t = scene.triangles;
  its.prim = tri;
  const Vec3f v0 = t.V0(tri), v1 = t.V1(tri), v2 = t.V2(tri);
  its.p = v0 * (1.0f - hit.b1 - hit.b2) + v1 * hit.b1 + v2 * hit.b2;
  const Vec3f ng = Cross(v1 - v0, v2 - v0);
  const float len = Length(ng);
  its.ng = len > 0 ? ng / len : Vec3f{0, 0, 1};
  its.frame = Frame(ShadingNormalAt(scene, tri, hit.b1, hit.b2));
  if (with_uv) its.uv = SurfaceUvAt(scene, tri, hit.b1, hit.b2);
  its.material = scene.shading.material[tri];
  its.emitter = scene.meshes.emitter[scene.shading.mesh[tri]];
}

}  // namespace

void MakeInteractionAt(const Scene& scene, const Ray& ray, const Hit& hit, bool with_uv,
                       SurfaceInteraction* its) {
  // Every field of a default interaction first: each kind sets the fields it has.
  *its = SurfaceInteraction{};
  if (IsSphereHit(hit.prim)) return SphereInteraction(scene, ray, hit, with_uv, *its);
  if (IsSdfGridHit(hit.prim)) return SdfGridInteraction(scene, ray, hit, *its);
  if (IsInstancedHit(hit.prim, scene.triangles.size()))
    return InstanceInteraction(scene, hit, with_uv, *its);
  TriangleInteraction(scene, hit.prim, hit, with_uv, *its);
}

SurfaceInteraction MakeInteraction(const Scene& scene, const Ray& ray, const Hit& hit) {
  SurfaceInteraction its;
  MakeInteractionAt(scene, ray, hit, /*with_uv=*/true, &its);
  return its;
}

SurfaceInteraction MakeInteraction(const Scene& scene, const Ray& ray, const Hit& hit,
                                   bool with_uv) {
  SurfaceInteraction its;
  MakeInteractionAt(scene, ray, hit, with_uv, &its);
  return its;
}

}  // namespace ptlab
