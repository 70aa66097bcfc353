// The shading point of a ray hit: position, normals and the components the hit refers to.
#pragma once

#include "engine/bvh/bvh.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/core/frame.h"
#include "engine/core/packet8.h"
#include "engine/core/ray.h"
#include "engine/scene/scene.h"

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

/// Builds the interaction for a hit of `ray` (hit.prim must be valid). A sphere hit's shading
/// normal is (p - c)/r; spheres never emit.
SurfaceInteraction MakeInteraction(const Scene& scene, const Ray& ray, const Hit& hit);

/// The shading stage's rows, one per queue entry (row q = lane q % 8 of packet q / 8), each
/// array with room for 8 rows per packet: the interaction as MakeInteraction builds it but
/// without surface coordinates (uv (0, 0): no stage of the wavefront reads them), and wo, the
/// unit direction back along the ray, -d / |d|, in the interaction's shading frame.
struct InteractionRows {
  SurfaceInteraction* its;
  Vec3f* wo;
};

/// The direction back along a ray of direction d (|d|² a normal float), in `frame`: the
/// operations of the wavefront's shading stage, in its order.
inline Vec3f LocalDirectionBack(const Frame& frame, const Vec3f& d) {
  return frame.ToLocal(-d / Length(d));
}

/// For every hit lane of `packets` ray/hit packets (bit j of hit_mask[k] set): row k * 8 + j of
/// out.its = MakeInteraction without uv and of out.wo = LocalDirectionBack(its.frame, d); other
/// rows are left as they are. The wavefront's interaction slot, so the oracle table keeps the
/// scalar path's bits; SIMD twin: simd::MakeInteractionBatch (rows).
void MakeInteractionBatch(const Scene& scene, const RayPacket8* rays, const HitPacket8* hits,
                          const Mask8* hit_mask, size_t packets, const InteractionRows& out);

}  // namespace ptlab
