// Interaction stage, the scalar oracle (engine/wavefront/interaction.h).
#include "engine/wavefront/interaction.h"

#include <algorithm>
#include <bit>
#include <iterator>

namespace ptlab {

void MakeInteractionBatch(const Scene& scene, const RayPacket8* rays, const HitPacket8* hits,
                          const Mask8* hit_mask, size_t packets, const InteractionRows& out,
                          HitLists* lists) {
  HitLists& l = *lists;
  // Surface coordinates only for the textures that read them (TextureSiteOf).
  const bool with_uv = !scene.textures.empty();
  l.hits = l.area_hits = 0;
  std::fill(std::begin(l.group_hits), std::end(l.group_hits), 0u);
  for (size_t k = 0; k < packets; ++k) {
    for (Mask8 todo = hit_mask[k] & kAllLanes; todo != 0; todo &= todo - 1) {
      const int j = std::countr_zero(todo);
      const HitPacket8& h = hits[k];
      const Ray ray = GetLaneRay(rays[k], j);
      const size_t q = k * kPacketWidth + size_t(j);
      SurfaceInteraction& its = out.its[q];
      MakeInteractionAt(scene, ray, {h.t[j], h.b1[j], h.b2[j], h.prim[j]}, with_uv, &its);
      out.wo[q] = LocalDirectionBack(its.frame, ray.d);
      l.entries[l.hits++] = uint32_t(q);
      if (its.emitter.tag() == EmitterTag::kArea) l.area_entries[l.area_hits++] = uint32_t(q);
      ++l.group_hits[MaterialGroup(its.material)];
    }
  }
}

}  // namespace ptlab
