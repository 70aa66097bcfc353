// The shading point of a ray hit: position, normals and the components the hit refers to.
#pragma once

#include <algorithm>
#include <cstdint>

#include "engine/bvh/bvh.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/core/frame.h"
#include "engine/core/packet8.h"
#include "engine/core/ray.h"
#include "engine/scene/scene.h"
#include "engine/texture/texture_site.h"

namespace ptlab {

struct SurfaceInteraction {
  Vec3f p;        // world-space hit point: from barycentrics (not o + t d); on a sphere
                  // o + t d projected onto the surface
  Vec3f ng;       // unit geometric normal, (v1 - v0) x (v2 - v0); a sphere's outward normal
  Frame frame;    // shading frame, z = shading normal
  Vec2f uv;       // surface coordinates: SurfaceUvAt on a triangle, SphereUv on a sphere
  uint32_t prim = kNoHit;  // Hit::prim: a triangle row, or kSphereHitBit | sphere row
  MaterialRef material;
  EmitterRef emitter;
};

/// Surface uv of triangle `tri` at barycentrics (b1, b2), as Nori's Mesh::setHitInformation
/// computes it: the mesh's texture coordinates interpolated, b0 uv0 + b1 uv1 + b2 uv2 in that
/// order, when its mesh has them (MeshTable::has_uvs), else the barycentrics (b1, b2).
Vec2f SurfaceUvAt(const Scene& scene, uint32_t tri, float b1, float b2);

/// Surface uv of a sphere at unit outward normal n (world axes): (φ/2π, θ/π) with φ = atan2(y,
/// x) ∈ [0, 2π) from +x towards +y and θ = acos(z) ∈ [0, π] from +z, the convention of the
/// tessellated MakeSphere (engine/io/shapes.h).
Vec2f SphereUv(const Vec3f& n);

/// The scene's textures at `its` (its uv, p and prim): what a textured material parameter
/// reads; no textures (nullptr) in a scene without any.
inline TextureSite TextureSiteOf(const Scene& scene, const SurfaceInteraction& its) {
  if (scene.textures.empty()) return {};
  return {&scene.textures, {its.uv, its.p, its.prim}, &its.frame, &its.ng};
}

/// Builds the interaction for a hit of `ray` (hit.prim must be valid). A sphere hit's shading
/// normal is (p - c)/r; spheres never emit.
SurfaceInteraction MakeInteraction(const Scene& scene, const Ray& ray, const Hit& hit);

/// MakeInteraction with the surface coordinates only when `with_uv` (otherwise uv is (0, 0)):
/// the wavefront's interaction stage computes them only for a scene with textures.
SurfaceInteraction MakeInteraction(const Scene& scene, const Ray& ray, const Hit& hit,
                                   bool with_uv);

/// MakeInteraction(scene, ray, hit, with_uv) built in place in *its, every field written (the
/// wavefront's interaction stage fills its rows so, without a copy of the interaction).
void MakeInteractionAt(const Scene& scene, const Ray& ray, const Hit& hit, bool with_uv,
                       SurfaceInteraction* its);

}  // namespace ptlab
