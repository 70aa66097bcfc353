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

/// The shading stage's rows, one per queue entry (row q = lane q % 8 of packet q / 8), each
/// array with room for 8 rows per packet: the interaction as MakeInteraction builds it, with
/// surface coordinates only in a scene with textures (they read them; otherwise uv (0, 0): no
/// other stage of the wavefront reads them), and wo, the
/// unit direction back along the ray, -d / |d|, in the interaction's shading frame.
struct InteractionRows {
  SurfaceInteraction* its;
  Vec3f* wo;
};

/// The BSDF stage's group of a hit's material: its tag, or kMaterialTagCount for a hit without
/// a material (MaterialRef::None's tag is 15). The wavefront batches each group's rows together.
inline constexpr int kMaterialGroups = kMaterialTagCount + 1;
inline uint32_t MaterialGroup(MaterialRef ref) {
  return std::min(uint32_t(ref.tag()), uint32_t(kMaterialTagCount));
}

/// The interaction stage's lists of a wave's hits, so that the shading stage visits only the
/// hits it has work for (emission) and the sampling stage gets its rows without a pass over the
/// hit masks. The caller gives the two arrays room for 8 entries per packet; the slot writes
/// the counts and entries [0, count) of each (a SIMD slot may write any entry of the room past
/// them).
struct HitLists {
  uint32_t* entries;       // every hit's queue entry, in queue order
  uint32_t* area_entries;  // the queue entries of hits on an area light (EmitterTag::kArea)
  uint32_t hits = 0, area_hits = 0;
  uint32_t group_hits[kMaterialGroups] = {};  // hits by MaterialGroup
};

/// The direction back along a ray of direction d (|d|² a normal float), in `frame`: the
/// operations of the wavefront's shading stage, in its order.
inline Vec3f LocalDirectionBack(const Frame& frame, const Vec3f& d) {
  return frame.ToLocal(-d / Length(d));
}

/// For every hit lane of `packets` ray/hit packets (bit j of hit_mask[k] set): row k * 8 + j of
/// out.its = MakeInteraction (uv only when scene.textures is not empty) and of out.wo = LocalDirectionBack(its.frame, d); other
/// rows are left as they are. And the lists of those hits (queue entry q = k * 8 + j): every q,
/// the q whose row's emitter tag is kArea, and the count per MaterialGroup of the row's
/// material. The wavefront's interaction slot, so the oracle table keeps the scalar path's
/// bits; SIMD twin: simd::MakeInteractionBatch (rows).
void MakeInteractionBatch(const Scene& scene, const RayPacket8* rays, const HitPacket8* hits,
                          const Mask8* hit_mask, size_t packets, const InteractionRows& out,
                          HitLists* lists);

}  // namespace ptlab
