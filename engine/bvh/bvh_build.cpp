// Binned-SAH BVH build (Wald 2007, "On fast construction of SAH-based BVHs"), single-threaded.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "engine/bvh/bvh.h"
#include "engine/bvh/sphere_intersect.h"
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
  float lo[3];
  float hi[3];
  uint32_t row;

  float Centroid2(int axis) const { return lo[axis] + hi[axis]; }
};

// A bin's bounds. Plain float arrays rather than Box's Vec3f: with Vec3f members the binning
// loop GCC 12 generates made the whole build 1.7-1.9x slower (measured on the bench scenes).
struct BinBox {
  float lo[3] = {kEmpty, kEmpty, kEmpty};
  float hi[3] = {-kEmpty, -kEmpty, -kEmpty};

  static constexpr float kEmpty = std::numeric_limits<float>::infinity();

  void Grow(const PrimRef& r) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], r.lo[k]);
      hi[k] = std::max(hi[k], r.hi[k]);
    }
  }
  void Grow(const BinBox& b) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], b.lo[k]);
      hi[k] = std::max(hi[k], b.hi[k]);
    }
  }
  // Half the surface area of a non-empty box.
  float HalfArea() const {
    const float ex = hi[0] - lo[0], ey = hi[1] - lo[1], ez = hi[2] - lo[2];
    return ex * ey + ey * ez + ez * ex;
  }
  Box ToBox() const { return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}}; }
};

// The chosen split, with what the children need: their bounds (unions of the bins on each
// side, equal to the bounds of their triangles since min and max are exact).
struct Split {
  int axis = -1;  // -1: no binned split found
  int bin = 0;    // left side = bins [0, bin]
  float cost = std::numeric_limits<float>::infinity();
  Box left, right;
};

// Bin index of a doubled centroid; shared by the binning pass and the partition so both put
// every reference on the same side.
// Clamped in float before the conversion, so an overflowing or NaN position (bounds near
// FLT_MAX) still gives a bin in [0, kBins) instead of an undefined int.
inline int BinOf(float c2, float lo, float scale) {
  const float b = (c2 - lo) * scale;
  if (!(b > 0.0f)) return 0;
  return b < static_cast<float>(kBins - 1) ? static_cast<int>(b) : kBins - 1;
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
      const Vec3f lo = Min(a, Min(b, c)), hi = Max(a, Max(b, c));
      refs_.push_back({{lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z}, static_cast<uint32_t>(i)});
    }
    if (refs_.empty()) return;
    // Leaves write their triangles by index (every reference lands in exactly one leaf).
    TriangleTable& leaf = bvh_->leaf_triangles;
    for (AlignedVector<float>* col : {&leaf.v0_x, &leaf.v0_y, &leaf.v0_z, &leaf.v1_x, &leaf.v1_y,
                                      &leaf.v1_z, &leaf.v2_x, &leaf.v2_y, &leaf.v2_z}) {
      col->resize(refs_.size());
    }
    bvh_->prim_id.resize(refs_.size());
    bvh_->nodes.reserve(refs_.size() / 2 + 1);
    const uint32_t count = static_cast<uint32_t>(refs_.size());
    Box bounds, centroids;
    GrowBounds(0, count, &bounds, &centroids);
    BuildNode(0, count, 0, bounds, centroids);
    PTLAB_CHECK(num_leaf_triangles_ == count);
    // The reserve above is a guess (nodes ≈ 2 n / mean leaf size): give back what it or the
    // vector's doubling left unused (1 M-triangle terrain: 1.05 M slots for 0.61 M nodes).
    bvh_->nodes.shrink_to_fit();
  }

 private:
  // Grows *bounds by the triangles of refs_[begin, end) and *centroids by their centroids.
  void GrowBounds(uint32_t begin, uint32_t end, Box* bounds, Box* centroids) const {
    for (uint32_t i = begin; i < end; ++i) {
      const PrimRef& r = refs_[i];
      const Vec3f lo{r.lo[0], r.lo[1], r.lo[2]}, hi{r.hi[0], r.hi[1], r.hi[2]};
      bounds->lo = Min(bounds->lo, lo);
      bounds->hi = Max(bounds->hi, hi);
      centroids->Grow(lo + hi);
    }
  }

  // Emits the subtree over refs_[begin, end) in depth-first order; returns its root index.
  // `bounds` and `centroids` are the bounds of these triangles and of their (doubled)
  // centroids, computed by the parent.
  uint32_t BuildNode(uint32_t begin, uint32_t end, uint32_t depth, const Box& bounds,
                     const Box& centroids) {
    PTLAB_CHECK(depth < static_cast<uint32_t>(kBvhMaxDepth));
    const uint32_t index = static_cast<uint32_t>(bvh_->nodes.size());
    bvh_->nodes.emplace_back();
    bvh_->nodes[index].bounds_min = bounds.lo;
    bvh_->nodes[index].bounds_max = bounds.hi;
    const uint32_t count = end - begin;
    if (count <= kAlwaysLeafSize) return MakeLeaf(index, begin, end);

    uint32_t mid = begin;
    int axis = 0;
    Box left_bounds, right_bounds, left_centroids, right_centroids;
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
      mid =
          Partition(begin, end, axis, centroids.lo[axis], static_cast<float>(kBins) / extent[axis],
                    split.bin, &left_centroids, &right_centroids);
      left_bounds = split.left;
      right_bounds = split.right;
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
      GrowBounds(begin, mid, &left_bounds, &left_centroids);
      GrowBounds(mid, end, &right_bounds, &right_centroids);
    }
    PTLAB_CHECK(mid > begin && mid < end);
    bvh_->nodes[index].axis = static_cast<uint16_t>(axis);
    // The left child is always index + 1.
    BuildNode(begin, mid, depth + 1, left_bounds, left_centroids);
    const uint32_t right = BuildNode(mid, end, depth + 1, right_bounds, right_centroids);
    bvh_->nodes[index].offset = right;
    return index;
  }

  // Moves the references of refs_[begin, end) whose centroid falls in bins [0, split_bin] of
  // `axis` to the front (Hoare's two-ended scan) and returns the first one of the back. Grows
  // the two sides' centroid bounds on the way.
  uint32_t Partition(uint32_t begin, uint32_t end, int axis, float lo, float scale, int split_bin,
                     Box* left_centroids, Box* right_centroids) {
    auto is_left = [&](const PrimRef& r) {
      const Vec3f c{r.lo[0] + r.hi[0], r.lo[1] + r.hi[1], r.lo[2] + r.hi[2]};
      const bool left = BinOf(c[axis], lo, scale) <= split_bin;
      (left ? left_centroids : right_centroids)->Grow(c);
      return left;
    };
    uint32_t first = begin, last = end;
    for (;;) {
      for (;;) {
        if (first == last) return first;
        if (!is_left(refs_[first])) break;
        ++first;
      }
      --last;
      for (;;) {
        if (first == last) return first;
        if (is_left(refs_[last])) break;
        --last;
      }
      std::swap(refs_[first], refs_[last]);
      ++first;
    }
  }

  // Best SAH split over kBins centroid bins on each axis with a non-empty, finitely scalable
  // centroid extent. Cost = traversal + triangle * sum(area_child * count_child) / area.
  Split FindSplit(uint32_t begin, uint32_t end, const Box& bounds, const Box& centroids) const {
    uint32_t counts[3][kBins] = {};
    BinBox boxes[3][kBins];
    float scale[3];
    bool binnable[3];
    const Vec3f extent = centroids.hi - centroids.lo;
    for (int a = 0; a < 3; ++a) {
      scale[a] = static_cast<float>(kBins) / extent[a];
      binnable[a] = extent[a] > 0.0f && std::isfinite(extent[a]) && std::isfinite(scale[a]);
    }
    if (!binnable[0] && !binnable[1] && !binnable[2]) return Split{};
    for (uint32_t i = begin; i < end; ++i) {
      const PrimRef& r = refs_[i];
      for (int a = 0; a < 3; ++a) {
        if (!binnable[a]) continue;
        const int b = BinOf(r.Centroid2(a), centroids.lo[a], scale[a]);
        ++counts[a][b];
        boxes[a][b].Grow(r);
      }
    }
    const float area = bounds.HalfArea();
    const float inv_area = area > 0.0f ? 1.0f / area : 0.0f;
    Split best;
    for (int a = 0; a < 3; ++a) {
      if (!binnable[a]) continue;
      // Only non-empty bins can change a side: a split after an empty bin has the same sides
      // and the same cost (bit for bit: growing by an empty box changes nothing) as the
      // split after the last non-empty bin before it, which the scan meets first and keeps.
      int used[kBins];
      int num_used = 0;
      for (int b = 0; b < kBins; ++b) {
        if (counts[a][b] != 0) used[num_used++] = b;
      }
      // Sweep from the right to get each right side (bins from used[k] on), then from the
      // left, considering the split after each non-empty bin that leaves both sides non-empty.
      BinBox right_box[kBins];
      float right_cost[kBins];
      BinBox acc;
      uint32_t n = 0;
      for (int k = num_used - 1; k > 0; --k) {
        acc.Grow(boxes[a][used[k]]);
        n += counts[a][used[k]];
        right_box[k] = acc;
        right_cost[k] = acc.HalfArea() * static_cast<float>(n);
      }
      acc = BinBox{};
      n = 0;
      for (int k = 0; k + 1 < num_used; ++k) {
        acc.Grow(boxes[a][used[k]]);
        n += counts[a][used[k]];
        const float sah = acc.HalfArea() * static_cast<float>(n) + right_cost[k + 1];
        const float cost = kTraversalCost + kTriangleCost * sah * inv_area;
        if (cost < best.cost) {
          best.axis = a;
          best.bin = used[k];
          best.cost = cost;
          best.left = acc.ToBox();
          best.right = right_box[k + 1].ToBox();
        }
      }
    }
    return best;
  }

  uint32_t MakeLeaf(uint32_t index, uint32_t begin, uint32_t end) {
    TriangleTable& leaf = bvh_->leaf_triangles;
    BvhNode& node = bvh_->nodes[index];
    node.offset = num_leaf_triangles_;
    node.count = static_cast<uint16_t>(end - begin);
    for (uint32_t i = begin; i < end; ++i) {
      const uint32_t row = refs_[i].row;
      const uint32_t k = num_leaf_triangles_++;
      leaf.v0_x[k] = triangles_.v0_x[row], leaf.v0_y[k] = triangles_.v0_y[row];
      leaf.v0_z[k] = triangles_.v0_z[row], leaf.v1_x[k] = triangles_.v1_x[row];
      leaf.v1_y[k] = triangles_.v1_y[row], leaf.v1_z[k] = triangles_.v1_z[row];
      leaf.v2_x[k] = triangles_.v2_x[row], leaf.v2_y[k] = triangles_.v2_y[row];
      leaf.v2_z[k] = triangles_.v2_z[row];
      bvh_->prim_id[k] = row;
    }
    return index;
  }

  const TriangleTable& triangles_;
  Bvh* bvh_;
  std::vector<PrimRef> refs_;
  uint32_t num_leaf_triangles_ = 0;
};

}  // namespace

Bvh BuildBvh(const TriangleTable& triangles) {
  Bvh bvh;
  Builder(triangles, &bvh).Build();
  return bvh;
}

Bvh BuildBvh(const TriangleTable& triangles, const SphereTable& spheres) {
  PTLAB_CHECK(spheres.size() < kMaxSpheres);
  Bvh bvh = BuildBvh(triangles);
  bvh.spheres = spheres;
  return bvh;
}

}  // namespace ptlab
