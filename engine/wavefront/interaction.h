// Interaction stage: a wave's hits into shading points (the rows it writes, the lists of hits
// the later stages read) and the scalar oracle, MakeInteraction (engine/render/interaction.h)
// per hit lane; SIMD twin simd::MakeInteractionBatch (simd/wavefront/interaction8.h).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "engine/core/frame.h"
#include "engine/core/packet8.h"
#include "engine/render/interaction.h"
#include "engine/scene/scene.h"

namespace ptlab {

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
