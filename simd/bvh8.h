// Eight-wide BVH (BVH8) collapsed from the oracle's binary SAH tree, laid out for SIMD traversal.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>
#include <vector>

#include "engine/bvh/bvh.h"
#include "engine/core/aligned.h"

namespace ptlab::simd {

/// Reference to a child of a Bvh8Node, in 64-byte lines of Bvh8::lines: an inner node's first
/// line (bit 31 clear), or a leaf (bit 31 set) of `count` triangles packed from line `line` on,
/// ref = 0x80000000 | line << 3 | (count - 1).
using Bvh8Ref = uint32_t;
inline constexpr Bvh8Ref kBvh8LeafBit = 0x80000000u;
inline constexpr uint32_t kBvh8MaxLeafSize = 8;
inline constexpr uint32_t kBvh8MaxTriangles = 1u << 28;
/// Lines a leaf reference can address (BuildBvh8 checks that the tree fits).
inline constexpr uint64_t kBvh8MaxLines = uint64_t{1} << 28;

inline bool IsLeaf(Bvh8Ref r) { return (r & kBvh8LeafBit) != 0; }
inline uint32_t LeafLine(Bvh8Ref r) { return (r & ~kBvh8LeafBit) >> 3; }
inline uint32_t LeafCount(Bvh8Ref r) { return (r & 7u) + 1; }
inline Bvh8Ref MakeLeafRef(uint32_t line, uint32_t count) {
  return kBvh8LeafBit | (line << 3) | (count - 1);
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

/// One cache line of a BVH8's memory, which holds its nodes (four lines each) and its packed
/// leaves (Bvh8LeafLines each) side by side.
struct alignas(64) Bvh8Line {
  std::byte bytes[64];
};
inline constexpr uint32_t kBvh8NodeLines = sizeof(Bvh8Node) / sizeof(Bvh8Line);

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

/// Lines a packed leaf of `count` triangles takes (its columns, rounded up to whole lines).
inline constexpr uint32_t Bvh8LeafLines(uint32_t count) {
  return (kBvh8LeafColumns * count * uint32_t{sizeof(float)} + sizeof(Bvh8Line) - 1) /
         sizeof(Bvh8Line);
}

/// A BVH8 over the triangles of a binary Bvh, in one array of cache lines laid out depth
/// first: a node, then its leaf children's packed triangles, then its inner children's subtrees
/// in slot order. A leaf of n triangles stores ten columns of n values from its first line on
/// (c = v0.x, v0.y, v0.z, v1.x, ..., v2.z, then the scene row's bits), so an unaligned 8-float
/// load at any column reads only this leaf's values in its first n lanes (the array ends with a
/// line of padding). A node's leaves lie right after it, each from a line of its own, as
/// Embree's allocator places them, where separate node and leaf arrays put them megabytes apart
/// (measured on the 1 M-triangle terrain's bounce rays: 1-3 % faster, 8 % more bytes; see
/// docs/traversal.md). The scene rows sit beside the positions because a hit reads its row
/// right after the test: from a separate array that was one more cache miss per hit.
struct Bvh8 {
  AlignedVector<Bvh8Line> lines;  // the root node is lines [0, 4) (empty: nothing can be hit)
  uint32_t num_triangles = 0;
  uint32_t num_nodes = 0;
  uint32_t depth = 0;  // nodes on the longest root-to-leaf path
  float extent = 0.0f;  // largest side of the triangles' bounding box
  SphereTable spheres;  // the Bvh's spheres, tested beside the tree by every ray
  SdfGridTable sdf_grids;  // the Bvh's sdfgrids, likewise (lane by lane, the oracle's code)
  /// Instancing: the Bvh's instance level (copied) and one BVH8 per shape group, collapsed
  /// from the Bvh's group trees. Empty without instances.
  InstanceLevel instances;
  std::vector<Bvh8> groups;

  /// No triangle can be hit (spheres may still be).
  bool empty() const { return lines.empty(); }

  /// The node an inner reference names (the root is Node(0)).
  const Bvh8Node& Node(Bvh8Ref ref) const {
    return *std::launder(reinterpret_cast<const Bvh8Node*>(lines.data() + ref));
  }
  /// The packed columns of a leaf.
  const float* Leaf(Bvh8Ref leaf) const {
    return reinterpret_cast<const float*>(lines.data() + LeafLine(leaf));
  }
  /// Scene row of triangle j of a leaf.
  uint32_t LeafPrim(Bvh8Ref leaf, uint32_t j) const {
    uint32_t prim;
    std::memcpy(&prim, Leaf(leaf) + (kBvh8LeafColumns - 1) * LeafCount(leaf) + j, sizeof(prim));
    return prim;
  }
};

/// Collapses `bvh` into a BVH8: each node takes up to eight descendants of a binary node,
/// opening the inner child of largest surface area first (Wald et al. 2008, "Getting rid of
/// packets"). Child boxes are the binary nodes' boxes bit for bit, and the binary leaves (or
/// merged subtrees) keep their triangles, so traversal visits the same triangles the oracle
/// would; its spheres and instance level are copied and its group trees collapsed likewise.
/// O(nodes); keeps no reference to `bvh`.
Bvh8 BuildBvh8(const Bvh& bvh, const Bvh8BuildOptions& options = {});

/// Heap bytes the BVH8 holds: capacity × element size of its lines and spheres
/// (simd/bvh8_bytes.cpp).
size_t Bvh8Bytes(const Bvh8& bvh8);

}  // namespace ptlab::simd
