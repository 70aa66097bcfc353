// Heap bytes of a binary BVH.
#include "engine/bvh/bvh.h"
#include "engine/core/memory.h"
#include "engine/scene/scene_bytes.h"

namespace ptlab {

static_assert(sizeof(Bvh) == sizeof(std::vector<BvhNode>) + sizeof(TriangleTable) +
                                 sizeof(AlignedVector<uint32_t>) + sizeof(SphereTable),
              "a member added to Bvh must be counted in BvhBytes");

size_t BvhBytes(const Bvh& bvh) {
  return VectorsBytes(bvh.nodes, bvh.prim_id) + TableBytes(bvh.leaf_triangles) +
         TableBytes(bvh.spheres);
}

}  // namespace ptlab
