// Eight-wide BVH (BVH8) collapsed from the oracle's binary SAH tree, laid out for SIMD traversal.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "engine/bvh/bvh.h"
#include "engine/core/aligned.h"

namespace ptlab::simd {

/// Reference to a child of a Bvh8Node: an inner node index (bit 31 clear), or a leaf (bit 31
/// set) covering leaf-ordered triangles [first, first + count) with
/// ref = 0x80000000 | first << 3 | (count - 1).
using Bvh8Ref = uint32_t;
inline constexpr Bvh8Ref kBvh8LeafBit = 0x80000000u;
inline constexpr uint32_t kBvh8MaxLeafSize = 8;
inline constexpr uint32_t kBvh8MaxTriangles = 1u << 28;

inline bool IsLeaf(Bvh8Ref r) { return (r & kBvh8LeafBit) != 0; }
inline uint32_t LeafFirst(Bvh8Ref r) { return (r & ~kBvh8LeafBit) >> 3; }
inline uint32_t LeafCount(Bvh8Ref r) { return (r & 7u) + 1; }
inline Bvh8Ref MakeLeafRef(uint32_t first, uint32_t count) {
  return kBvh8LeafBit | (first << 3) | (count - 1);
}

/// One node: the world-space boxes of up to eight children as SoA columns (one 8-float load
/// per plane tests a ray against all children at once), then the child references. Children
/// are packed to the front; unused slots hold the empty box (lo = +inf, hi = -inf), which
/// every slab test rejects, so the kernels need no slot mask. 256 bytes = 4 cache lines.
struct alignas(64) Bvh8Node {
  float lo_x[8], lo_y[8], lo_z[8];
  float hi_x[8], hi_y[8], hi_z[8];
  Bvh8Ref child[8];
  uint32_t num_children;
  uint32_t leaf_children;  // bit c: child c is a leaf (its reference's leaf bit, as a mask)
  uint32_t pad_[6];
};
static_assert(sizeof(Bvh8Node) == 256, "Bvh8Node must stay 4 cache lines");

/// Options of the collapse.
struct Bvh8BuildOptions {
  /// Greedy collapse only (sah_leaf_cost 0): a binary subtree with at most this many triangles
  /// becomes one leaf (≤ kBvh8MaxLeafSize), so that one 8-wide triangle test replaces the box
  /// tests below it. 0 keeps the binary tree's leaves as they are. Measured
  /// (benchmarks/traverse_bench.cpp, BM_Tune_Merge): 8 is as fast or faster than 0 and 4 for
  /// every ray kind and scene.
  uint32_t merge_leaf_size = 8;
  /// Above 0: the collapse that minimizes the SAH cost, with a leaf costing this many times an
  /// inner node of the same area (see bvh8_build.cpp), choosing which subtrees become leaves
  /// and how each node's eight slots are shared. 0: the greedy collapse (each node opens its
  /// largest inner child until it has eight). Measured (traverse_bench, BM_Tune_CollapsePaired:
  /// both trees timed in alternation on the same rays, AMD EPYC Zen 5): 1.5 against greedy,
  /// Intersect8 / Occluded8 table +3 % / +3 to 4 %, veach +1 % (camera and bounce rays) and
  /// +5 % (shadow rays), terrain +2 to 3 %, bounce rays +8 % / +9 %; no row slower. Leaf costs
  /// 1.0 and 2.0 were at most 0.01 faster than 1.5 on any row, and slower on terrain's bounce
  /// rays' Intersect8 (+3 % and +4 % instead of +8 %).
  float sah_leaf_cost = 1.5f;
};

/// Columns of a packed leaf: the nine vertex coordinates, then the triangles' scene rows.
inline constexpr uint32_t kBvh8LeafColumns = 10;

/// A BVH8 over the triangles of a binary Bvh, with its own copy of the positions packed leaf
/// by leaf: the leaf [first, first + n) stores ten columns of n values at
/// tris[10 * first + c * n + j] (c = v0.x, v0.y, v0.z, v1.x, ..., v2.z, then the scene row's
/// bits; j < n), so a leaf is contiguous and an unaligned 8-float load at any column reads only
/// this leaf's values in its first n lanes (the array is padded at the end). The scene rows sit
/// beside the positions because a hit reads its row right after the test: from a separate
/// array that was one more cache miss per hit (perf: a tenth of Bvh8Intersect1's time on
/// terrain bounce rays went to that load; they traverse 5 % faster without it).
struct Bvh8 {
  AlignedVector<Bvh8Node> nodes;  // nodes[0] is the root (empty: nothing can be hit)
  AlignedVector<float> tris;
  uint32_t num_triangles = 0;
  uint32_t depth = 0;  // nodes on the longest root-to-leaf path
  float extent = 0.0f;  // largest side of the triangles' bounding box
  SphereTable spheres;  // the Bvh's spheres, tested beside the tree by every ray

  /// No triangle can be hit (spheres may still be).
  bool empty() const { return nodes.empty(); }

  /// The packed columns of the leaf whose first triangle (in leaf order) is `first`.
  const float* Leaf(uint32_t first) const { return tris.data() + size_t{kBvh8LeafColumns} * first; }
  /// Scene row of triangle j of the leaf [first, first + n).
  uint32_t LeafPrim(uint32_t first, uint32_t n, uint32_t j) const {
    uint32_t prim;
    std::memcpy(&prim, Leaf(first) + (kBvh8LeafColumns - 1) * n + j, sizeof(prim));
    return prim;
  }
};

/// Collapses `bvh` into a BVH8: each node takes up to eight descendants of a binary node,
/// opening the inner child of largest surface area first (Wald et al. 2008, "Getting rid of
/// packets"). Child boxes are the binary nodes' boxes bit for bit, and the binary leaves (or
/// merged subtrees) keep their triangles, so traversal visits the same triangles the oracle
/// would; its spheres are copied. O(nodes); keeps no reference to `bvh`.
Bvh8 BuildBvh8(const Bvh& bvh, const Bvh8BuildOptions& options = {});

/// Heap bytes the BVH8 holds: capacity × element size of its nodes, packed leaves and spheres
/// (simd/bvh8_bytes.cpp).
size_t Bvh8Bytes(const Bvh8& bvh8);

}  // namespace ptlab::simd
