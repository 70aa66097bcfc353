// Heap bytes of a BVH8 (plain C++: no Highway code here).
#include "engine/core/memory.h"
#include "engine/scene/scene_bytes.h"
#include "simd/bvh8.h"

namespace ptlab::simd {

// The scalar members (num_triangles, num_nodes, depth, extent) are padded to the next 8 bytes.
static_assert(sizeof(Bvh8) == sizeof(AlignedVector<Bvh8Line>) +
                                  (3 * sizeof(uint32_t) + sizeof(float) + 7) / 8 * 8 +
                                  sizeof(SphereTable) + sizeof(SdfGridTable) + sizeof(InstanceLevel) +
                                  sizeof(std::vector<Bvh8>),
              "a member added to Bvh8 must be counted in Bvh8Bytes");

size_t Bvh8Bytes(const Bvh8& bvh8) {
  const InstanceLevel& in = bvh8.instances;
  size_t bytes = VectorsBytes(bvh8.lines) + TableBytes(bvh8.spheres) + TableBytes(bvh8.sdf_grids) +
                 VectorsBytes(in.nodes, in.order, in.world_to_group, in.group, in.first_prim,
                              bvh8.groups);
  for (const Bvh8& g : bvh8.groups) bytes += Bvh8Bytes(g);
  return bytes;
}

}  // namespace ptlab::simd
