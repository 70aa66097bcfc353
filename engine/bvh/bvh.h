// Bounding volume hierarchy over the scene's triangles: flat node array and binned-SAH build.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/core/aligned.h"
#include "engine/core/ray.h"
#include "engine/core/vec.h"
#include "engine/scene/geometry_tables.h"
#include "engine/scene/sdf_grid_table.h"
#include "engine/scene/sphere_table.h"

namespace ptlab {

inline constexpr uint32_t kNoHit = 0xffffffffu;

/// Closest hit of a ray: distance along the ray (in units of |d|), barycentrics of v1 and v2
/// (the hit point is (1-b1-b2) v0 + b1 v1 + b2 v2), and the triangle's row in the scene's
/// TriangleTable (kNoHit when nothing was hit).
struct Hit {
  float t = 0.0f;
  float b1 = 0.0f, b2 = 0.0f;
  uint32_t prim = kNoHit;
};

/// Deepest node of any Bvh (root depth 0) is below this, so traversal stacks of this many
/// entries never overflow.
inline constexpr int kBvhMaxDepth = 64;
/// Largest number of triangles in one leaf.
inline constexpr int kBvhMaxLeafSize = 8;

/// One node of the flattened tree, 32 bytes, in depth-first order. An interior node's left
/// child is the next node in the array and `offset` is its right child's index; a leaf covers
/// the leaf-ordered triangles [offset, offset + count). Bounds are world space and contain
/// every vertex below the node exactly (no padding).
struct alignas(32) BvhNode {
  Vec3f bounds_min;
  uint32_t offset = 0;
  Vec3f bounds_max;
  uint16_t count = 0;  // triangles in a leaf; 0 marks an interior node
  uint16_t axis = 0;   // interior: the axis (0 x, 1 y, 2 z) the children were split along

  bool IsLeaf() const { return count != 0; }
};
static_assert(sizeof(BvhNode) == 32, "BvhNode must stay 32 bytes");

/// The top level of a two-level BVH (instancing, engine/scene/instance_table.h): a binary tree
/// over the instances' world boxes (BvhNode; a leaf covers [offset, offset + count) of `order`),
/// and per instance its world-to-group transform (3x4, row-major), its group and its first hit
/// id (the scene's triangle count plus InstanceTable::first_prim). Empty without instances.
/// Traversal: engine/bvh/instance_level.h.
struct InstanceLevel {
  std::vector<BvhNode> nodes;
  std::vector<uint32_t> order;           // leaf order -> instance
  std::vector<float> world_to_group;     // 12 per instance
  std::vector<uint32_t> group;           // per instance
  std::vector<uint32_t> first_prim;      // per instance

  bool empty() const { return nodes.empty(); }
};

/// A BVH that owns a leaf-ordered copy of the triangle positions (so traversal reads leaves
/// contiguously) and the map from leaf order back to scene triangle rows.
/// An empty `nodes` means no triangle can be hit. Triangles with a non-finite coordinate or
/// zero area (repeated or collinear vertices) are left out: they can never be hit. The scene's
/// analytic spheres ride along outside the tree (a scene holds a handful; every ray tests all).
struct Bvh {
  std::vector<BvhNode> nodes;       // nodes[0] is the root
  TriangleTable leaf_triangles;     // positions in leaf order
  AlignedVector<uint32_t> prim_id;  // leaf order -> scene TriangleTable row
  SphereTable spheres;              // copy of the scene's spheres (rows = sphere hit ids)
  SdfGridTable sdf_grids;           // copy of the scene's sdfgrids (BuildSceneBvh), beside too
  /// Instancing (BuildSceneBvh): the instance tree and one BVH per shape group, over the
  /// group's triangles in group space (prim_id = the triangle's index within its group).
  InstanceLevel instances;
  std::vector<Bvh> groups;

  bool empty() const { return nodes.empty(); }
};

/// Builds a BVH over `triangles` with binned SAH (32 centroid bins per axis), leaves of at
/// most kBvhMaxLeafSize triangles and depth below kBvhMaxDepth. Single-threaded, O(n log n);
/// deterministic for a given table.
Bvh BuildBvh(const TriangleTable& triangles);
/// The same with the scene's analytic spheres beside the tree (fewer than kMaxSpheres).
Bvh BuildBvh(const TriangleTable& triangles, const SphereTable& spheres);

/// Heap bytes the BVH holds: capacity × element size of its nodes, leaf-ordered triangles,
/// prim ids and spheres (engine/bvh/bvh_bytes.cpp).
size_t BvhBytes(const Bvh& bvh);

}  // namespace ptlab
