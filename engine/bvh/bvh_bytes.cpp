// Heap bytes of a binary BVH.
#include "engine/bvh/bvh.h"
#include "engine/core/memory.h"
#include "engine/scene/scene_bytes.h"

namespace ptlab {

static_assert(sizeof(Bvh) == sizeof(std::vector<BvhNode>) + sizeof(TriangleTable) +
                                 sizeof(AlignedVector<uint32_t>) + sizeof(SphereTable) +
                                 sizeof(SdfGridTable) +
                                 sizeof(InstanceLevel) + sizeof(std::vector<Bvh>),
              "a member added to Bvh must be counted in BvhBytes");

size_t BvhBytes(const Bvh& bvh) {
  return VectorsBytes(bvh.nodes, bvh.prim_id) + TableBytes(bvh.leaf_triangles) +
         TableBytes(bvh.spheres) + TableBytes(bvh.sdf_grids) +
         VectorsBytes(bvh.instances.nodes, bvh.instances.order, bvh.instances.world_to_group,
                      bvh.instances.group, bvh.instances.first_prim, bvh.groups) +
         [&] {
           size_t groups = 0;
           for (const Bvh& g : bvh.groups) groups += BvhBytes(g);
           return groups;
         }();
}

}  // namespace ptlab
