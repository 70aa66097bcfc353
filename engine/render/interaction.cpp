// The shading point of a ray hit: position, normals and the components the hit refers to.
#include "engine/render/interaction.h"

#include "engine/bvh/sphere_intersect.h"
#include "engine/light/area_light.h"

namespace ptlab {

namespace {

// A sphere hit: o + t d carries the error of t; re-projected onto the sphere (pbrt-v4,
// Physically Based Rendering 4th ed., §6.8.5) it is as exact as the surface allows.
SurfaceInteraction SphereInteraction(const Scene& scene, const Ray& ray, const Hit& hit) {
  const uint32_t i = SphereHitRow(hit.prim);
  const SphereTable& s = scene.spheres;
  SurfaceInteraction its;
  Vec3f n;
  its.p = ProjectOntoSphere(ray.At(hit.t), s.Center(i), s.radius[i], &n);
  its.prim = hit.prim;
  its.ng = n;
  its.frame = Frame(n);
  its.material = s.material[i];
  return its;
}

}  // namespace

SurfaceInteraction MakeInteraction(const Scene& scene, const Ray& ray, const Hit& hit) {
  if (IsSphereHit(hit.prim)) return SphereInteraction(scene, ray, hit);
  const uint32_t tri = hit.prim;
  const TriangleTable& t = scene.triangles;
  SurfaceInteraction its;
  its.prim = tri;
  const Vec3f v0 = t.V0(tri), v1 = t.V1(tri), v2 = t.V2(tri);
  its.p = v0 * (1.0f - hit.b1 - hit.b2) + v1 * hit.b1 + v2 * hit.b2;
  const Vec3f ng = Cross(v1 - v0, v2 - v0);
  const float len = Length(ng);
  its.ng = len > 0 ? ng / len : Vec3f{0, 0, 1};
  its.frame = Frame(ShadingNormalAt(scene, tri, hit.b1, hit.b2));
  its.material = scene.shading.material[tri];
  its.emitter = scene.meshes.emitter[scene.shading.mesh[tri]];
  return its;
}

}  // namespace ptlab
