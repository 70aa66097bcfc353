// BVH8 collapse of the oracle's binary SAH tree, and the leaf-packed triangle copy.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
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
    out_->nodes.reserve(n / 4 + 1);
    if (LeafLike(0)) {
      // A tree that is a single leaf still gets an inner root, so traversal starts at a node.
      const uint32_t root = NewNode();
      SetChild(root, 0, 0);
      out_->nodes[root].num_children = 1;
      out_->depth = 1;
    } else {
      Collapse(0, 1);
    }
    PackTriangles();
    // The reserve above bounds the node count from above: give back what is unused (1 M-triangle
    // terrain: 152 k slots for 46 k nodes).
    out_->nodes.shrink_to_fit();
  }

 private:
  bool LeafLike(uint32_t b) const {
    return bvh_.nodes[b].IsLeaf() ||
           (options_.merge_leaf_size > 0 &&
            count_[b] <= std::min(options_.merge_leaf_size, kBvh8MaxLeafSize));
  }

  uint32_t NewNode() {
    const uint32_t index = static_cast<uint32_t>(out_->nodes.size());
    Bvh8Node& node = out_->nodes.emplace_back();
    std::fill(std::begin(node.lo_x), std::end(node.lo_x), kInf);
    std::fill(std::begin(node.lo_y), std::end(node.lo_y), kInf);
    std::fill(std::begin(node.lo_z), std::end(node.lo_z), kInf);
    std::fill(std::begin(node.hi_x), std::end(node.hi_x), -kInf);
    std::fill(std::begin(node.hi_y), std::end(node.hi_y), -kInf);
    std::fill(std::begin(node.hi_z), std::end(node.hi_z), -kInf);
    std::fill(std::begin(node.child), std::end(node.child), 0u);
    std::fill(std::begin(node.pad_), std::end(node.pad_), 0u);
    node.num_children = 0;
    node.leaf_children = 0;
    return index;
  }

  // Slot `slot` of node `index` gets binary node b: its box and, for a leaf-like b, its
  // triangle range. Inner children are filled in by Collapse.
  void SetChild(uint32_t index, uint32_t slot, uint32_t b) {
    Bvh8Node& node = out_->nodes[index];
    const BvhNode& src = bvh_.nodes[b];
    node.lo_x[slot] = src.bounds_min.x;
    node.lo_y[slot] = src.bounds_min.y;
    node.lo_z[slot] = src.bounds_min.z;
    node.hi_x[slot] = src.bounds_max.x;
    node.hi_y[slot] = src.bounds_max.y;
    node.hi_z[slot] = src.bounds_max.z;
    if (LeafLike(b)) {
      PTLAB_CHECK(count_[b] >= 1 && count_[b] <= kBvh8MaxLeafSize);
      node.child[slot] = MakeLeafRef(first_[b], count_[b]);
      node.leaf_children |= 1u << slot;
      leaves_.push_back(node.child[slot]);
    }
  }

  // Emits the BVH8 node for inner binary node b (and, recursively, its subtree); returns its
  // index.
  uint32_t Collapse(uint32_t b, uint32_t depth) {
    out_->depth = std::max(out_->depth, depth);
    uint32_t kids[8] = {b + 1, bvh_.nodes[b].offset};
    uint32_t num = 2;
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
    const uint32_t index = NewNode();
    out_->nodes[index].num_children = num;
    for (uint32_t i = 0; i < num; ++i) {
      SetChild(index, i, kids[i]);
      if (!LeafLike(kids[i])) {
        const uint32_t child = Collapse(kids[i], depth + 1);
        out_->nodes[index].child[i] = child;  // re-index: Collapse may reallocate nodes
      }
    }
    return index;
  }

  void PackTriangles() {
    const TriangleTable& t = bvh_.leaf_triangles;
    const uint32_t n = static_cast<uint32_t>(t.size());
    out_->num_triangles = n;
    // Padding: an 8-float load at the last column of the last leaf reads 7 floats past it.
    out_->tris.assign(size_t{kBvh8LeafColumns} * n + 16, 0.0f);
    const float* cols[9] = {t.v0_x.data(), t.v0_y.data(), t.v0_z.data(),
                            t.v1_x.data(), t.v1_y.data(), t.v1_z.data(),
                            t.v2_x.data(), t.v2_y.data(), t.v2_z.data()};
    uint64_t covered = 0;
    for (const Bvh8Ref leaf : leaves_) {
      const uint32_t first = LeafFirst(leaf), count = LeafCount(leaf);
      float* dst = out_->tris.data() + size_t{kBvh8LeafColumns} * first;
      for (int c = 0; c < 9; ++c) {
        for (uint32_t j = 0; j < count; ++j) dst[c * count + j] = cols[c][first + j];
      }
      std::memcpy(dst + 9 * count, bvh_.prim_id.data() + first, count * sizeof(uint32_t));
      covered += count;
    }
    // The leaves partition the leaf order (each binary leaf lies in exactly one BVH8 leaf).
    PTLAB_CHECK(covered == n);
  }

  const Bvh& bvh_;
  const Bvh8BuildOptions& options_;
  Bvh8* out_;
  std::vector<uint32_t> first_, count_;
  std::vector<Bvh8Ref> leaves_;
};

}  // namespace

Bvh8 BuildBvh8(const Bvh& bvh, const Bvh8BuildOptions& options) {
  Bvh8 out;
  out.spheres = bvh.spheres;
  if (bvh.empty()) return out;
  PTLAB_CHECK(bvh.leaf_triangles.size() < kBvh8MaxTriangles);
  Collapser(bvh, options, &out).Run();
  const Vec3f side = bvh.nodes[0].bounds_max - bvh.nodes[0].bounds_min;
  out.extent = std::max(side.x, std::max(side.y, side.z));
  return out;
}

}  // namespace ptlab::simd
