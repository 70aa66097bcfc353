// Binned-SAH BVH build (Wald 2007, "On fast construction of SAH-based BVHs"), single-threaded.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "engine/bvh/bvh.h"
#include "engine/core/check.h"

namespace ptlab {
namespace {

constexpr int kBins = 32;
// Nodes of at most this many triangles always become leaves.
constexpr uint32_t kAlwaysLeafSize = 4;
// SAH costs of one node visit and one triangle test, in the same arbitrary unit.
constexpr float kTraversalCost = 1.0f;
constexpr float kTriangleCost = 1.0f;

struct Box {
  Vec3f lo{std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
           std::numeric_limits<float>::infinity()};
  Vec3f hi{-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
           -std::numeric_limits<float>::infinity()};

  void Grow(const Vec3f& p) {
    lo = Min(lo, p);
    hi = Max(hi, p);
  }
  void Grow(const Box& b) {
    lo = Min(lo, b.lo);
    hi = Max(hi, b.hi);
  }
  // Half the surface area; 0 for an empty box.
  float HalfArea() const {
    if (!(lo.x <= hi.x)) return 0.0f;
    const Vec3f e = hi - lo;
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
};

// A triangle's bounds and scene row. Centroids are handled doubled (lo + hi) to save a
// multiply; binning only needs them consistently scaled.
struct PrimRef {
  Vec3f lo;
  uint32_t row;
  Vec3f hi;

  float Centroid2(int axis) const { return lo[axis] + hi[axis]; }
};

struct Split {
  int axis = -1;  // -1: no binned split found
  int bin = 0;    // left side = bins [0, bin]
  float cost = std::numeric_limits<float>::infinity();
};

// Bin index of a doubled centroid; shared by the binning pass and the partition so both put
// every reference on the same side.
inline int BinOf(float c2, float lo, float scale) {
  const int b = static_cast<int>((c2 - lo) * scale);
  return std::min(b, kBins - 1);
}

// Triangles that can never be hit are left out: non-finite coordinates (they would poison
// the bounds) and zero area. The cross product is taken in double, where it is exact for
// repeated vertices and for collinear vertices with modest coordinates.
bool IsHittable(const Vec3f& a, const Vec3f& b, const Vec3f& c) {
  for (const Vec3f& v : {a, b, c}) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) return false;
  }
  const double e1x = static_cast<double>(b.x) - a.x, e1y = static_cast<double>(b.y) - a.y,
               e1z = static_cast<double>(b.z) - a.z;
  const double e2x = static_cast<double>(c.x) - a.x, e2y = static_cast<double>(c.y) - a.y,
               e2z = static_cast<double>(c.z) - a.z;
  const double nx = e1y * e2z - e1z * e2y;
  const double ny = e1z * e2x - e1x * e2z;
  const double nz = e1x * e2y - e1y * e2x;
  return nx != 0.0 || ny != 0.0 || nz != 0.0;
}

uint32_t CeilLog2(uint32_t n) {
  uint32_t r = 0;
  while ((uint64_t{1} << r) < n) ++r;
  return r;
}

class Builder {
 public:
  Builder(const TriangleTable& triangles, Bvh* bvh) : triangles_(triangles), bvh_(bvh) {}

  void Build() {
    const size_t n = triangles_.size();
    PTLAB_CHECK(n < (size_t{1} << 31));
    refs_.reserve(n);
    for (size_t i = 0; i < n; ++i) {
      const Vec3f a = triangles_.V0(i), b = triangles_.V1(i), c = triangles_.V2(i);
      if (!IsHittable(a, b, c)) continue;
      PrimRef r;
      r.lo = Min(a, Min(b, c));
      r.hi = Max(a, Max(b, c));
      r.row = static_cast<uint32_t>(i);
      refs_.push_back(r);
    }
    if (refs_.empty()) return;
    TriangleTable& leaf = bvh_->leaf_triangles;
    for (AlignedVector<float>* col : {&leaf.v0_x, &leaf.v0_y, &leaf.v0_z, &leaf.v1_x, &leaf.v1_y,
                                      &leaf.v1_z, &leaf.v2_x, &leaf.v2_y, &leaf.v2_z}) {
      col->reserve(refs_.size());
    }
    bvh_->prim_id.reserve(refs_.size());
    bvh_->nodes.reserve(refs_.size() / 2 + 1);
    BuildNode(0, static_cast<uint32_t>(refs_.size()), 0);
  }

 private:
  // Emits the subtree over refs_[begin, end) in depth-first order; returns its root index.
  uint32_t BuildNode(uint32_t begin, uint32_t end, uint32_t depth) {
    PTLAB_CHECK(depth < static_cast<uint32_t>(kBvhMaxDepth));
    const uint32_t index = static_cast<uint32_t>(bvh_->nodes.size());
    bvh_->nodes.emplace_back();
    Box bounds, centroids;
    for (uint32_t i = begin; i < end; ++i) {
      const PrimRef& r = refs_[i];
      bounds.lo = Min(bounds.lo, r.lo);
      bounds.hi = Max(bounds.hi, r.hi);
      centroids.Grow(r.lo + r.hi);
    }
    bvh_->nodes[index].bounds_min = bounds.lo;
    bvh_->nodes[index].bounds_max = bounds.hi;
    const uint32_t count = end - begin;
    if (count <= kAlwaysLeafSize) return MakeLeaf(index, begin, end);

    uint32_t mid = begin;
    int axis = 0;
    const Vec3f extent = centroids.hi - centroids.lo;
    // Past this depth SAH could exhaust the traversal stack; median splits halve the count,
    // so the remaining ceil(log2(count)) levels always fit.
    const bool depth_limited = depth + CeilLog2(count) + 1 >= static_cast<uint32_t>(kBvhMaxDepth);
    const Split split = depth_limited ? Split{} : FindSplit(begin, end, bounds, centroids);
    if (split.axis >= 0) {
      const float leaf_cost = kTriangleCost * static_cast<float>(count);
      if (count <= static_cast<uint32_t>(kBvhMaxLeafSize) && leaf_cost <= split.cost) {
        return MakeLeaf(index, begin, end);
      }
      axis = split.axis;
      const float lo = centroids.lo[axis];
      const float scale = static_cast<float>(kBins) / extent[axis];
      const int split_bin = split.bin;
      auto it = std::partition(refs_.begin() + begin, refs_.begin() + end,
                               [axis, lo, scale, split_bin](const PrimRef& r) {
                                 return BinOf(r.Centroid2(axis), lo, scale) <= split_bin;
                               });
      mid = static_cast<uint32_t>(it - refs_.begin());
    } else if (count <= static_cast<uint32_t>(kBvhMaxLeafSize)) {
      // All centroids coincide (or cannot be binned), or the depth budget is spent.
      return MakeLeaf(index, begin, end);
    } else {
      // Object median along the widest centroid axis; ties broken by row so the order (and
      // the tree) is deterministic.
      axis = MaxDimension(extent);
      mid = begin + count / 2;
      std::nth_element(refs_.begin() + begin, refs_.begin() + mid, refs_.begin() + end,
                       [axis](const PrimRef& a, const PrimRef& b) {
                         const float ca = a.Centroid2(axis), cb = b.Centroid2(axis);
                         return ca < cb || (ca == cb && a.row < b.row);
                       });
    }
    PTLAB_CHECK(mid > begin && mid < end);
    bvh_->nodes[index].axis = static_cast<uint16_t>(axis);
    BuildNode(begin, mid, depth + 1);  // the left child is always index + 1
    const uint32_t right = BuildNode(mid, end, depth + 1);
    bvh_->nodes[index].offset = right;
    return index;
  }

  // Best SAH split over kBins centroid bins on each axis with a non-empty, finitely scalable
  // centroid extent. Cost = traversal + triangle * sum(area_child * count_child) / area.
  Split FindSplit(uint32_t begin, uint32_t end, const Box& bounds, const Box& centroids) const {
    uint32_t counts[3][kBins] = {};
    Box boxes[3][kBins];
    float scale[3];
    bool binnable[3];
    const Vec3f extent = centroids.hi - centroids.lo;
    for (int a = 0; a < 3; ++a) {
      scale[a] = static_cast<float>(kBins) / extent[a];
      binnable[a] = extent[a] > 0.0f && std::isfinite(scale[a]);
    }
    if (!binnable[0] && !binnable[1] && !binnable[2]) return Split{};
    for (uint32_t i = begin; i < end; ++i) {
      const PrimRef& r = refs_[i];
      for (int a = 0; a < 3; ++a) {
        if (!binnable[a]) continue;
        const int b = BinOf(r.Centroid2(a), centroids.lo[a], scale[a]);
        ++counts[a][b];
        boxes[a][b].lo = Min(boxes[a][b].lo, r.lo);
        boxes[a][b].hi = Max(boxes[a][b].hi, r.hi);
      }
    }
    const float area = bounds.HalfArea();
    const float inv_area = area > 0.0f ? 1.0f / area : 0.0f;
    Split best;
    for (int a = 0; a < 3; ++a) {
      if (!binnable[a]) continue;
      // Sweep from the right to get the cost of each right side, then from the left.
      float right_cost[kBins];
      uint32_t right_count[kBins];
      Box acc;
      uint32_t n = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc.Grow(boxes[a][b]);
        n += counts[a][b];
        right_cost[b] = acc.HalfArea() * static_cast<float>(n);
        right_count[b] = n;
      }
      acc = Box{};
      n = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        acc.Grow(boxes[a][b]);
        n += counts[a][b];
        if (n == 0 || right_count[b + 1] == 0) continue;
        const float sah = acc.HalfArea() * static_cast<float>(n) + right_cost[b + 1];
        const float cost = kTraversalCost + kTriangleCost * sah * inv_area;
        if (cost < best.cost) {
          best.axis = a;
          best.bin = b;
          best.cost = cost;
        }
      }
    }
    return best;
  }

  uint32_t MakeLeaf(uint32_t index, uint32_t begin, uint32_t end) {
    TriangleTable& leaf = bvh_->leaf_triangles;
    BvhNode& node = bvh_->nodes[index];
    node.offset = static_cast<uint32_t>(leaf.size());
    node.count = static_cast<uint16_t>(end - begin);
    for (uint32_t i = begin; i < end; ++i) {
      const uint32_t row = refs_[i].row;
      leaf.Append(triangles_.V0(row), triangles_.V1(row), triangles_.V2(row));
      bvh_->prim_id.push_back(row);
    }
    return index;
  }

  const TriangleTable& triangles_;
  Bvh* bvh_;
  std::vector<PrimRef> refs_;
};

}  // namespace

Bvh BuildBvh(const TriangleTable& triangles) {
  Bvh bvh;
  Builder(triangles, &bvh).Build();
  return bvh;
}

}  // namespace ptlab
