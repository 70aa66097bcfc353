// BVH8 collapse of the oracle's binary SAH tree, and the leaf-packed triangle copy.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <limits>
#include <new>
#include <vector>

#include "engine/core/check.h"
#include "simd/bvh8.h"

namespace ptlab::simd {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

float HalfArea(const BvhNode& n) {
  const Vec3f e = n.bounds_max - n.bounds_min;
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

class Collapser {
 public:
  Collapser(const Bvh& bvh, const Bvh8BuildOptions& options, Bvh8* out)
      : bvh_(bvh), options_(options), out_(out) {}

  void Run() {
    const size_t n = bvh_.nodes.size();
    // Leaf-order range of every binary subtree: children come after their parent in the
    // depth-first array, so one backward sweep sees both children first.
    first_.resize(n);
    count_.resize(n);
    for (size_t i = n; i-- > 0;) {
      const BvhNode& node = bvh_.nodes[i];
      if (node.IsLeaf()) {
        first_[i] = node.offset;
        count_[i] = node.count;
      } else {
        first_[i] = first_[i + 1];
        count_[i] = count_[i + 1] + count_[node.offset];
      }
    }
    if (Sah()) {
      choice_.resize(n);
      SlotCosts(0);
    }
    // The lines are counted first, so that the array is allocated once at its final size.
    // A line of padding at the end: an 8-float load at the last leaf's last column reads up
    // to 7 floats past it.
    const uint64_t lines =
        1 + (LeafLike(0) ? kBvh8NodeLines + Bvh8LeafLines(count_[0]) : SubtreeLines(0));
    PTLAB_CHECK(lines <= kBvh8MaxLines);
    out_->lines.resize(lines);
    if (LeafLike(0)) {
      // A tree that is a single leaf still gets an inner root, so traversal starts at a node.
      Bvh8Node& root = NewNode();
      root.num_children = 1;
      SetChild(&root, 0, 0);
      out_->depth = 1;
    } else {
      Collapse(0, 1);
    }
    // Every line but the padding is used, and the leaves partition the leaf order (each binary
    // leaf lies in exactly one BVH8 leaf).
    PTLAB_CHECK(cursor_ + 1 == out_->lines.size());
    PTLAB_CHECK(covered_ == out_->num_triangles);
  }

 private:
  bool Sah() const { return options_.sah_leaf_cost > 0; }

  // The SAH-optimal collapse (the dynamic programme of Ylitie, Karras and Laine 2017, "Efficient
  // incoherent ray traversal on GPUs through compressed wide BVHs"), bottom-up over the binary
  // tree. Cost model: an inner node costs its box's half area (one test of eight boxes), a leaf
  // sah_leaf_cost times its half area (one 8-wide triangle test, whatever its count up to
  // kBvh8MaxLeafSize). Returns cost[j - 1], the least cost of binary subtree b as at most j
  // child slots of its parent, and records the choices behind it in choice_[b] (SlotChoice).
  // Recursive (depth ≤ kBvhMaxDepth), so that the costs live on the stack and only the choices
  // in memory.
  std::array<float, 8> SlotCosts(uint32_t b) {
    const BvhNode& node = bvh_.nodes[b];
    SlotChoice& c = choice_[b];
    const float area = HalfArea(node);
    float one_slot = kInf;
    c.as_leaf = count_[b] <= kBvh8MaxLeafSize;
    if (c.as_leaf) one_slot = area * options_.sah_leaf_cost;
    std::array<float, 8> cost;
    if (node.IsLeaf()) {
      cost.fill(one_slot);
      std::fill(std::begin(c.split), std::end(c.split), uint8_t{0});
      return cost;
    }
    const std::array<float, 8> left = SlotCosts(b + 1);
    const std::array<float, 8> right = SlotCosts(node.offset);
    float inner = kInf;
    for (uint32_t k = 1; k < 8; ++k) {
      const float sum = left[k - 1] + right[8 - k - 1];
      if (sum < inner) inner = sum, c.inner_split = uint8_t(k);
    }
    inner += area;
    if (inner < one_slot) one_slot = inner, c.as_leaf = 0;
    for (uint32_t j = 1; j <= 8; ++j) {
      float best = one_slot;
      uint8_t split = 0;
      for (uint32_t k = 1; k < j; ++k) {
        const float sum = left[k - 1] + right[j - k - 1];
        if (sum < best) best = sum, split = uint8_t(k);
      }
      cost[j - 1] = best, c.split[j - 1] = split;
    }
    return cost;
  }

  // The slots of binary subtree b given at most j of them (SlotCosts' choice), appended to kids.
  void ExpandSlots(uint32_t b, uint32_t j, uint32_t* kids, uint32_t* num) const {
    const uint8_t split = choice_[b].split[j - 1];
    if (split == 0) {
      kids[(*num)++] = b;
      return;
    }
    ExpandSlots(b + 1, split, kids, num);
    ExpandSlots(bvh_.nodes[b].offset, j - split, kids, num);
  }

  bool LeafLike(uint32_t b) const {
    if (Sah()) return choice_[b].as_leaf != 0;
    return bvh_.nodes[b].IsLeaf() ||
           (options_.merge_leaf_size > 0 &&
            count_[b] <= std::min(options_.merge_leaf_size, kBvh8MaxLeafSize));
  }

  // The child slots of the BVH8 node made for inner binary node b, in *kids; returns their
  // number (2 to 8).
  uint32_t Kids(uint32_t b, uint32_t* kids) const {
    kids[0] = b + 1, kids[1] = bvh_.nodes[b].offset;
    uint32_t num = 2;
    if (Sah()) {
      num = 0;
      const uint32_t k = choice_[b].inner_split;
      ExpandSlots(b + 1, k, kids, &num);
      ExpandSlots(bvh_.nodes[b].offset, 8 - k, kids, &num);
      return num;
    }
    while (num < 8) {
      // Open the inner child with the largest surface area: it is the one most rays reach.
      int best = -1;
      float best_area = -1.0f;
      for (uint32_t i = 0; i < num; ++i) {
        if (LeafLike(kids[i])) continue;
        const float area = HalfArea(bvh_.nodes[kids[i]]);
        if (area > best_area) best = static_cast<int>(i), best_area = area;
      }
      if (best < 0) break;
      const uint32_t k = kids[best];
      for (uint32_t i = num; i > static_cast<uint32_t>(best) + 1; --i) kids[i] = kids[i - 1];
      kids[best] = k + 1;
      kids[best + 1] = bvh_.nodes[k].offset;
      ++num;
    }
    return num;
  }

  // Lines of the subtree Collapse(b) emits: its node, its leaves, its inner children's subtrees.
  uint64_t SubtreeLines(uint32_t b) const {
    uint32_t kids[8];
    const uint32_t num = Kids(b, kids);
    uint64_t lines = kBvh8NodeLines;
    for (uint32_t i = 0; i < num; ++i) {
      lines += LeafLike(kids[i]) ? Bvh8LeafLines(count_[kids[i]]) : SubtreeLines(kids[i]);
    }
    return lines;
  }

  // The next four lines as an empty node (every slot the empty box).
  Bvh8Node& NewNode() {
    Bvh8Node* node = new (out_->lines.data() + cursor_) Bvh8Node;
    cursor_ += kBvh8NodeLines;
    ++out_->num_nodes;
    std::fill(std::begin(node->lo_x), std::end(node->lo_x), kInf);
    std::fill(std::begin(node->lo_y), std::end(node->lo_y), kInf);
    std::fill(std::begin(node->lo_z), std::end(node->lo_z), kInf);
    std::fill(std::begin(node->hi_x), std::end(node->hi_x), -kInf);
    std::fill(std::begin(node->hi_y), std::end(node->hi_y), -kInf);
    std::fill(std::begin(node->hi_z), std::end(node->hi_z), -kInf);
    std::fill(std::begin(node->child), std::end(node->child), 0u);
    std::fill(std::begin(node->pad_), std::end(node->pad_), 0u);
    node->num_children = 0;
    node->leaf_children = 0;
    return *node;
  }

  // Packs the triangles of leaf-like binary subtree b into the next lines; returns its reference.
  Bvh8Ref PackLeaf(uint32_t b) {
    const uint32_t first = first_[b], count = count_[b];
    PTLAB_CHECK(count >= 1 && count <= kBvh8MaxLeafSize);
    const Bvh8Ref ref = MakeLeafRef(static_cast<uint32_t>(cursor_), count);
    float* dst = reinterpret_cast<float*>(out_->lines.data() + cursor_);
    cursor_ += Bvh8LeafLines(count);
    const TriangleTable& t = bvh_.leaf_triangles;
    const float* cols[9] = {t.v0_x.data(), t.v0_y.data(), t.v0_z.data(),
                            t.v1_x.data(), t.v1_y.data(), t.v1_z.data(),
                            t.v2_x.data(), t.v2_y.data(), t.v2_z.data()};
    for (int c = 0; c < 9; ++c) {
      for (uint32_t j = 0; j < count; ++j) dst[c * count + j] = cols[c][first + j];
    }
    std::memcpy(dst + 9 * count, bvh_.prim_id.data() + first, count * sizeof(uint32_t));
    covered_ += count;
    return ref;
  }

  // Slot `slot` of *node gets binary node b's box and, for a leaf-like b, its packed leaf.
  // Inner children are filled in by Collapse.
  void SetChild(Bvh8Node* node, uint32_t slot, uint32_t b) {
    const BvhNode& src = bvh_.nodes[b];
    node->lo_x[slot] = src.bounds_min.x;
    node->lo_y[slot] = src.bounds_min.y;
    node->lo_z[slot] = src.bounds_min.z;
    node->hi_x[slot] = src.bounds_max.x;
    node->hi_y[slot] = src.bounds_max.y;
    node->hi_z[slot] = src.bounds_max.z;
    if (LeafLike(b)) {
      node->child[slot] = PackLeaf(b);
      node->leaf_children |= 1u << slot;
    }
  }

  // Emits the BVH8 node for inner binary node b, then its leaves, then its inner children's
  // subtrees; returns the node's reference.
  Bvh8Ref Collapse(uint32_t b, uint32_t depth) {
    out_->depth = std::max(out_->depth, depth);
    uint32_t kids[8];
    const uint32_t num = Kids(b, kids);
    // The children by their boxes' surface area, the largest last: the any-hit walks visit a
    // node's children from the last to the first (simd/traverse8_single-inl.h,
    // traverse8_packet_walk-inl.h), so a ray meets first the subtree it is most likely to enter,
    // and in it, e.g., a floor whose two triangles span the scene (the rock field's ground: its
    // camera rays' Occluded8 went from 0.52 to 1.22 of Embree; docs/traversal.md). Closest
    // hits sort by distance and do not depend on the order.
    std::stable_sort(kids, kids + num, [&](uint32_t x, uint32_t y) {
      return HalfArea(bvh_.nodes[x]) < HalfArea(bvh_.nodes[y]);
    });
    const Bvh8Ref ref = static_cast<Bvh8Ref>(cursor_);
    Bvh8Node& node = NewNode();  // the lines are allocated: the reference stays valid
    node.num_children = num;
    for (uint32_t i = 0; i < num; ++i) SetChild(&node, i, kids[i]);
    for (uint32_t i = 0; i < num; ++i) {
      if (!LeafLike(kids[i])) node.child[i] = Collapse(kids[i], depth + 1);
    }
    return ref;
  }

  const Bvh& bvh_;
  const Bvh8BuildOptions& options_;
  Bvh8* out_;
  std::vector<uint32_t> first_, count_;
  // The SAH collapse's choice for a binary subtree: split[j - 1], how many of its at most j
  // slots its left child takes (0: the subtree is one slot); as_leaf, whether that one slot is a
  // leaf; inner_split, the left child's share of the eight slots when it is an inner node.
  struct SlotChoice {
    uint8_t split[8];
    uint8_t as_leaf = 0, inner_split = 0;
  };
  AlignedVector<SlotChoice> choice_;
  uint64_t cursor_ = 0;   // the next free line
  uint64_t covered_ = 0;  // triangles packed so far
};

}  // namespace

Bvh8 BuildBvh8(const Bvh& bvh, const Bvh8BuildOptions& options) {
  Bvh8 out;
  out.spheres = bvh.spheres;
  out.sdf_grids = bvh.sdf_grids;
  out.instances = bvh.instances;
  for (const Bvh& g : bvh.groups) out.groups.push_back(BuildBvh8(g, options));
  if (bvh.empty()) return out;
  PTLAB_CHECK(bvh.leaf_triangles.size() < kBvh8MaxTriangles);
  out.num_triangles = static_cast<uint32_t>(bvh.leaf_triangles.size());
  Collapser(bvh, options, &out).Run();
  const Vec3f side = bvh.nodes[0].bounds_max - bvh.nodes[0].bounds_min;
  out.extent = std::max(side.x, std::max(side.y, side.z));
  return out;
}

}  // namespace ptlab::simd
