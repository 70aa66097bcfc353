// Binned-SAH BVH build (Wald 2007, "On fast construction of SAH-based BVHs"), on one thread or
// more (the same tree for any count).
#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <thread>
#include <vector>

#include "engine/bvh/bvh.h"
#include "engine/bvh/bvh_build.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/core/check.h"

namespace ptlab {
namespace {

constexpr int kBins = 32;
static_assert(kBins <= 32, "Bins::used holds one bit a bin");
// Nodes of at least this many triangles are binned into two sets of bins (FindSplit).
constexpr uint32_t kTwoBinSetsFrom = 256;
// The parallel build's top nodes of at least this many triangles are binned by two threads (a
// thread started for fewer costs about as much as it saves).
constexpr uint32_t kHelperBinningFrom = 65536;
// Trees over fewer triangles are built on one thread whatever the thread count.
constexpr uint32_t kParallelFrom = 16384;
// BvhNode::axis of the parallel build's placeholder for a deferred subtree (Builder::Task).
constexpr uint16_t kTaskMark = 0xffff;
// Nodes of at most this many triangles always become leaves.
constexpr uint32_t kAlwaysLeafSize = 4;
// SAH costs of one node visit and one triangle test, in the same arbitrary unit.
constexpr float kTraversalCost = 1.0f;
constexpr float kTriangleCost = 1.0f;

// Four floats in one vector (GCC and Clang vector extensions: SSE on x86, NEON on ARM, plain
// code elsewhere); lanes x, y, z and a fourth that no result reads. Growing a box by another is
// then one min and one max instruction: with float[3] or Vec3f members the compilers emit six
// scalar minss/maxss, and binning is most of the build's time.
typedef float Float4 __attribute__((vector_size(16)));

typedef int32_t Int4 __attribute__((vector_size(16)));

// std::min / std::max lane by lane (b < a ? b : a: SSE's minps(b, a), exactly).
inline Float4 Min4(Float4 a, Float4 b) { return b < a ? b : a; }
inline Float4 Max4(Float4 a, Float4 b) { return a < b ? b : a; }

constexpr float kInf = std::numeric_limits<float>::infinity();

// An axis-aligned box; empty: lo = +inf, hi = -inf.
struct Box4 {
  Float4 lo = {kInf, kInf, kInf, kInf};
  Float4 hi = {-kInf, -kInf, -kInf, -kInf};

  void Grow(const Box4& b) {
    lo = Min4(lo, b.lo);
    hi = Max4(hi, b.hi);
  }
  void GrowPoint(Float4 p) {
    lo = Min4(lo, p);
    hi = Max4(hi, p);
  }
  // Half the surface area of a non-empty box.
  float HalfArea() const {
    const float ex = hi[0] - lo[0], ey = hi[1] - lo[1], ez = hi[2] - lo[2];
    return ex * ey + ey * ez + ez * ex;
  }
  Vec3f Lo() const { return {lo[0], lo[1], lo[2]}; }
  Vec3f Hi() const { return {hi[0], hi[1], hi[2]}; }
};

// A triangle's bounds and scene row: lanes 0-2 of `box` are its bounds, lane 3 of `lo` holds
// the row's bits (a denormal or small float that min and max carry along) and lane 3 of `hi`
// is 1. No result reads lane 3, but the centroid's sum and the bin index compute it: with the
// row in both, that lane's sums were denormal, which the FPU makes slow (a denormal result
// without flush-to-zero; on the Zen 5 VM the one-thread build took 1.2-1.5x as long). 32 bytes,
// so a binning step loads two aligned vectors.
struct alignas(32) PrimRef {
  Box4 box;

  uint32_t Row() const {
    const float lane = box.lo[3];
    uint32_t row;
    std::memcpy(&row, &lane, sizeof(row));
    return row;
  }
  // The doubled centroid (lo + hi): centroids are handled doubled to save a multiply;
  // binning only needs them consistently scaled.
  Float4 Centroid2() const { return box.lo + box.hi; }
  float Centroid2(int axis) const { return box.lo[axis] + box.hi[axis]; }
};
static_assert(sizeof(PrimRef) == 32);

// The chosen split, with what the children need: their bounds (unions of the bins on each
// side, equal to the bounds of their triangles since min and max are exact).
struct Split {
  int axis = -1;  // -1: no binned split found
  int bin = 0;    // left side = bins [0, bin]
  float cost = std::numeric_limits<float>::infinity();
  Box4 left, right;
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

// BinOf in each lane, bit for bit (the same float operations, and the conversion truncates
// as static_cast<int> does); no branch, so the binning loop does not mispredict.
inline Int4 BinOf4(Float4 c2, Float4 lo, Float4 scale) {
  const Float4 b = (c2 - lo) * scale;
  const Float4 zero = {0.0f, 0.0f, 0.0f, 0.0f};
  const Float4 last = zero + static_cast<float>(kBins - 1);
  const Float4 positive = zero < b ? b : zero;  // NaN too goes to bin 0
  return __builtin_convertvector(positive < last ? positive : last, Int4);
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
 private:
  // Counts and bounds of the references in each bin of each axis. Kept between calls with
  // every bin empty (FindSplit empties the bins it used), so a small node does not pay for
  // clearing all 3 x kBins of them.
  struct Bins {
    uint32_t counts[3][kBins] = {};
    Box4 boxes[3][kBins];
    uint32_t used[3] = {};  // bit b: bin b is not empty
  };

  // What each thread of the build has of its own: its bins and a count of the triangles its
  // leaves took.
  struct Worker {
    Bins bins[2];
    uint32_t leaf_triangles = 0;
  };

 public:
  Builder(const TriangleTable& triangles, int threads, Bvh* bvh)
      : triangles_(triangles), threads_(std::max(1, threads)), bvh_(bvh) {}

  void Build() {
    const size_t n = triangles_.size();
    PTLAB_CHECK(n < (size_t{1} << 31));
    refs_.reserve(n);
    for (size_t i = 0; i < n; ++i) {
      const Vec3f a = triangles_.V0(i), b = triangles_.V1(i), c = triangles_.V2(i);
      if (!IsHittable(a, b, c)) continue;
      const Vec3f lo = Min(a, Min(b, c)), hi = Max(a, Max(b, c));
      float row;
      const uint32_t row_bits = static_cast<uint32_t>(i);
      std::memcpy(&row, &row_bits, sizeof(row));
      PrimRef r;
      r.box.lo = Float4{lo.x, lo.y, lo.z, row};
      r.box.hi = Float4{hi.x, hi.y, hi.z, 1.0f};
      refs_.push_back(r);
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
    Box4 bounds, centroids;
    GrowBounds(0, count, &bounds, &centroids);
    Worker main;
    if (threads_ > 1 && count >= kParallelFrom) {
      BuildParallel(count, bounds, centroids, &main);
    } else {
      BuildNode(0, count, 0, bounds, centroids, &bvh_->nodes, &main, nullptr);
    }
    PTLAB_CHECK(main.leaf_triangles == count);
    // The reserve above is a guess (nodes ≈ 2 n / mean leaf size): give back what it or the
    // vector's doubling left unused (1 M-triangle terrain: 1.05 M slots for 0.61 M nodes).
    bvh_->nodes.shrink_to_fit();
  }

 private:
  // Grows *bounds by the triangles of refs_[begin, end) and *centroids by their centroids.
  void GrowBounds(uint32_t begin, uint32_t end, Box4* bounds, Box4* centroids) const {
    for (uint32_t i = begin; i < end; ++i) {
      const PrimRef& r = refs_[i];
      bounds->Grow(r.box);
      centroids->GrowPoint(r.Centroid2());
    }
  }

  // A subtree the parallel build defers to a worker thread: its range and what BuildNode
  // needs for its root; its nodes, indexed from 0, go to `nodes`.
  struct Task {
    uint32_t begin, end, depth;
    Box4 bounds, centroids;
    std::vector<BvhNode> nodes;
  };

  // The two-thread (or more) build, the same tree as BuildNode's: the top of the tree is built
  // here (its nodes of kHelperBinningFrom triangles or more binned by two threads), down to subtrees of at most 1/16 of the
  // triangles, which become Tasks; worker threads build the Tasks, largest first, into their
  // own node arrays, and Assemble splices them into bvh_->nodes in depth-first order. Leaves
  // write their triangles by leaf-order index, and tasks own disjoint ranges of refs_.
  void BuildParallel(uint32_t count, const Box4& bounds, const Box4& centroids, Worker* main) {
    task_size_ = std::max(count / 16, kParallelFrom / 4);
    std::vector<BvhNode> top;
    std::vector<Task> tasks;
    BuildNode(0, count, 0, bounds, centroids, &top, main, &tasks);
    std::vector<uint32_t> order(tasks.size());
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      return tasks[a].end - tasks[a].begin > tasks[b].end - tasks[b].begin;
    });
    std::atomic<uint32_t> next{0};
    std::vector<Worker> workers(static_cast<size_t>(threads_));
    auto work = [&](Worker* w) {
      for (uint32_t k; (k = next.fetch_add(1)) < order.size();) {
        Task& t = tasks[order[k]];
        BuildNode(t.begin, t.end, t.depth, t.bounds, t.centroids, &t.nodes, w, nullptr);
      }
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < threads_; ++i) pool.emplace_back(work, &workers[i]);
    work(&workers[0]);
    for (std::thread& t : pool) t.join();
    for (const Worker& w : workers) main->leaf_triangles += w.leaf_triangles;
    Assemble(top, tasks, 0);
  }

  // Appends top[i]'s subtree to bvh_->nodes (a task's nodes with their right-child indices
  // moved by where they land); returns its root's index there.
  uint32_t Assemble(const std::vector<BvhNode>& top, const std::vector<Task>& tasks, uint32_t i) {
    std::vector<BvhNode>& out = bvh_->nodes;
    const uint32_t index = static_cast<uint32_t>(out.size());
    const BvhNode& n = top[i];
    if (n.axis == kTaskMark) {
      for (BvhNode node : tasks[n.offset].nodes) {
        if (!node.IsLeaf()) node.offset += index;
        out.push_back(node);
      }
      return index;
    }
    out.push_back(n);
    if (n.IsLeaf()) return index;
    Assemble(top, tasks, i + 1);
    const uint32_t right = Assemble(top, tasks, n.offset);
    out[index].offset = right;
    return index;
  }

  // Emits the subtree over refs_[begin, end) in depth-first order into *nodes; returns its
  // root's index there. `bounds` and `centroids` are the bounds of these triangles and of
  // their (doubled) centroids, computed by the parent. With `tasks` (the parallel build's top),
  // a subtree of at most task_size_ triangles becomes a Task and a node marked kTaskMark whose
  // offset is the task's index.
  uint32_t BuildNode(uint32_t begin, uint32_t end, uint32_t depth, const Box4& bounds,
                     const Box4& centroids, std::vector<BvhNode>* nodes, Worker* w,
                     std::vector<Task>* tasks) {
    PTLAB_CHECK(depth < static_cast<uint32_t>(kBvhMaxDepth));
    const uint32_t index = static_cast<uint32_t>(nodes->size());
    nodes->emplace_back();
    (*nodes)[index].bounds_min = bounds.Lo();
    (*nodes)[index].bounds_max = bounds.Hi();
    const uint32_t count = end - begin;
    if (tasks != nullptr && count <= task_size_) {
      (*nodes)[index].axis = kTaskMark;
      (*nodes)[index].offset = static_cast<uint32_t>(tasks->size());
      tasks->push_back({begin, end, depth, bounds, centroids, {}});
      return index;
    }
    if (count <= kAlwaysLeafSize) return MakeLeaf(&(*nodes)[index], index, begin, end, w);

    uint32_t mid = begin;
    int axis = 0;
    Box4 left_bounds, right_bounds, left_centroids, right_centroids;
    const Vec3f extent = centroids.Hi() - centroids.Lo();
    // Past this depth SAH could exhaust the traversal stack; median splits halve the count,
    // so the remaining ceil(log2(count)) levels always fit.
    const bool depth_limited = depth + CeilLog2(count) + 1 >= static_cast<uint32_t>(kBvhMaxDepth);
    const Split split = depth_limited ? Split{} : FindSplit(begin, end, bounds, centroids, w, tasks != nullptr);
    if (split.axis >= 0) {
      const float leaf_cost = kTriangleCost * static_cast<float>(count);
      if (count <= static_cast<uint32_t>(kBvhMaxLeafSize) && leaf_cost <= split.cost) {
        return MakeLeaf(&(*nodes)[index], index, begin, end, w);
      }
      axis = split.axis;
      mid = Partition(begin, end, axis, centroids.lo[axis],
                      static_cast<float>(kBins) / extent[axis], split.bin, &left_centroids,
                      &right_centroids);
      left_bounds = split.left;
      right_bounds = split.right;
    } else if (count <= static_cast<uint32_t>(kBvhMaxLeafSize)) {
      // All centroids coincide (or cannot be binned), or the depth budget is spent.
      return MakeLeaf(&(*nodes)[index], index, begin, end, w);
    } else {
      // Object median along the widest centroid axis; ties broken by row so the order (and
      // the tree) is deterministic.
      axis = MaxDimension(extent);
      mid = begin + count / 2;
      std::nth_element(refs_.begin() + begin, refs_.begin() + mid, refs_.begin() + end,
                       [axis](const PrimRef& a, const PrimRef& b) {
                         const float ca = a.Centroid2(axis), cb = b.Centroid2(axis);
                         return ca < cb || (ca == cb && a.Row() < b.Row());
                       });
      GrowBounds(begin, mid, &left_bounds, &left_centroids);
      GrowBounds(mid, end, &right_bounds, &right_centroids);
    }
    PTLAB_CHECK(mid > begin && mid < end);
    (*nodes)[index].axis = static_cast<uint16_t>(axis);
    // The left child is always index + 1.
    BuildNode(begin, mid, depth + 1, left_bounds, left_centroids, nodes, w, tasks);
    const uint32_t right =
        BuildNode(mid, end, depth + 1, right_bounds, right_centroids, nodes, w, tasks);
    (*nodes)[index].offset = right;
    return index;
  }

  // Moves the references of refs_[begin, end) whose centroid falls in bins [0, split_bin] of
  // `axis` to the front (Hoare's two-ended scan) and returns the first one of the back. Grows
  // the two sides' centroid bounds on the way.
  uint32_t Partition(uint32_t begin, uint32_t end, int axis, float lo, float scale, int split_bin,
                     Box4* left_centroids, Box4* right_centroids) {
    auto is_left = [&](const PrimRef& r) {
      const Float4 c = r.Centroid2();
      const bool left = BinOf(c[axis], lo, scale) <= split_bin;
      (left ? left_centroids : right_centroids)->GrowPoint(c);
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

  // Adds refs_[begin, end) to *bins (every axis: a bin index is in range even for an axis
  // that cannot be binned, whose bins the sweep then ignores).
  static void Bin(const PrimRef* refs, uint32_t count, Float4 lo, Float4 scale, Bins* bins) {
    for (uint32_t i = 0; i < count; ++i) {
      const Int4 b = BinOf4(refs[i].Centroid2(), lo, scale);
      for (int a = 0; a < 3; ++a) AddToBin(refs[i], a, b[a], bins);
    }
  }

  // Adds reference r to bin b of axis a.
  static void AddToBin(const PrimRef& r, int a, int b, Bins* bins) {
    ++bins->counts[a][b];
    bins->boxes[a][b].Grow(r.box);
    bins->used[a] |= 1u << b;
  }

  // Bin with two sets of bins, even references into *even and odd ones into *odd, so that
  // consecutive references that fall in the same bin do not wait on each other's update
  // (MergeBins then adds *odd to *even: min, max and counts do not depend on the order, so the
  // bins are the same bit for bit as Bin's).
  static void BinPairs(const PrimRef* refs, uint32_t count, Float4 lo, Float4 scale, Bins* even,
                       Bins* odd) {
    uint32_t i = 0;
    for (; i + 1 < count; i += 2) {
      const PrimRef& r0 = refs[i];
      const PrimRef& r1 = refs[i + 1];
      const Int4 b0 = BinOf4(r0.Centroid2(), lo, scale);
      const Int4 b1 = BinOf4(r1.Centroid2(), lo, scale);
      for (int a = 0; a < 3; ++a) AddToBin(r0, a, b0[a], even), AddToBin(r1, a, b1[a], odd);
    }
    Bin(refs + i, count - i, lo, scale, even);
  }

  // Best SAH split over kBins centroid bins on each axis with a non-empty, finitely scalable
  // centroid extent. Cost = traversal + triangle * sum(area_child * count_child) / area.
  // `two_threads`: bin the first half of the range here and the second on a thread of its own
  // (the parallel build's top nodes).
  Split FindSplit(uint32_t begin, uint32_t end, const Box4& bounds, const Box4& centroids,
                  Worker* w, bool two_threads) {
    float lo[3], scale[3];
    bool binnable[3];
    const Vec3f extent = centroids.Hi() - centroids.Lo();
    for (int a = 0; a < 3; ++a) {
      lo[a] = centroids.lo[a];
      scale[a] = static_cast<float>(kBins) / extent[a];
      binnable[a] = extent[a] > 0.0f && std::isfinite(extent[a]) && std::isfinite(scale[a]);
    }
    if (!binnable[0] && !binnable[1] && !binnable[2]) return Split{};
    const Float4 lo4 = {lo[0], lo[1], lo[2], 0.0f};
    const Float4 scale4 = {scale[0], scale[1], scale[2], 0.0f};
    Bins& bins = w->bins[0];
    const uint32_t count = end - begin;
    if (count < kTwoBinSetsFrom) {
      Bin(refs_.data() + begin, count, lo4, scale4, &bins);
    } else if (two_threads && count >= kHelperBinningFrom) {
      const uint32_t half = count / 2;
      std::thread helper([&] {
        BinPairs(refs_.data() + begin + half, count - half, lo4, scale4, &helper_bins_[0],
                 &helper_bins_[1]);
      });
      BinPairs(refs_.data() + begin, half, lo4, scale4, &bins, &w->bins[1]);
      helper.join();
      MergeBins(&w->bins[1], &bins);
      MergeBins(&helper_bins_[0], &bins);
      MergeBins(&helper_bins_[1], &bins);
    } else {
      BinPairs(refs_.data() + begin, count, lo4, scale4, &bins, &w->bins[1]);
      MergeBins(&w->bins[1], &bins);
    }
    const float area = bounds.HalfArea();
    const float inv_area = area > 0.0f ? 1.0f / area : 0.0f;
    Split best;
    for (int a = 0; a < 3; ++a) {
      // Only non-empty bins can change a side: a split after an empty bin has the same sides
      // and the same cost (bit for bit: growing by an empty box changes nothing) as the
      // split after the last non-empty bin before it, which the scan meets first and keeps.
      int used[kBins];
      int num_used = 0;
      for (uint32_t m = bins.used[a]; m != 0; m &= m - 1) used[num_used++] = std::countr_zero(m);
      if (binnable[a]) Sweep(bins, a, used, num_used, inv_area, &best);
      for (int k = 0; k < num_used; ++k) {
        bins.counts[a][used[k]] = 0;
        bins.boxes[a][used[k]] = Box4{};
      }
      bins.used[a] = 0;
    }
    return best;
  }

  // Moves the bins of *from into *to and empties *from.
  static void MergeBins(Bins* from, Bins* to) {
    for (int a = 0; a < 3; ++a) {
      for (uint32_t m = from->used[a]; m != 0; m &= m - 1) {
        const int b = std::countr_zero(m);
        to->counts[a][b] += from->counts[a][b];
        to->boxes[a][b].Grow(from->boxes[a][b]);
        from->counts[a][b] = 0;
        from->boxes[a][b] = Box4{};
      }
      to->used[a] |= from->used[a];
      from->used[a] = 0;
    }
  }

  // The SAH sweep over the non-empty bins used[0, num_used) of axis a; updates *best.
  static void Sweep(const Bins& bins, int a, const int* used, int num_used, float inv_area,
                    Split* best_split) {
    Split& best = *best_split;
    // Sweep from the right to get each right side (bins from used[k] on), then from the
    // left, considering the split after each non-empty bin that leaves both sides non-empty.
    Box4 right_box[kBins];
    float right_cost[kBins];
    Box4 acc;
    uint32_t n = 0;
    for (int k = num_used - 1; k > 0; --k) {
      acc.Grow(bins.boxes[a][used[k]]);
      n += bins.counts[a][used[k]];
      right_box[k] = acc;
      right_cost[k] = acc.HalfArea() * static_cast<float>(n);
    }
    acc = Box4{};
    n = 0;
    for (int k = 0; k + 1 < num_used; ++k) {
      acc.Grow(bins.boxes[a][used[k]]);
      n += bins.counts[a][used[k]];
      const float sah = acc.HalfArea() * static_cast<float>(n) + right_cost[k + 1];
      const float cost = kTraversalCost + kTriangleCost * sah * inv_area;
      if (cost < best.cost) {
        best.axis = a;
        best.bin = used[k];
        best.cost = cost;
        best.left = acc;
        best.right = right_box[k + 1];
      }
    }
  }

  // Makes *node (at `index`) the leaf over refs_[begin, end), whose triangles take leaf order
  // [begin, end): the depth-first walk meets the leaves in the order of their ranges.
  uint32_t MakeLeaf(BvhNode* node, uint32_t index, uint32_t begin, uint32_t end, Worker* w) {
    TriangleTable& leaf = bvh_->leaf_triangles;
    node->offset = begin;
    node->count = static_cast<uint16_t>(end - begin);
    for (uint32_t k = begin; k < end; ++k) {
      const uint32_t row = refs_[k].Row();
      leaf.v0_x[k] = triangles_.v0_x[row], leaf.v0_y[k] = triangles_.v0_y[row];
      leaf.v0_z[k] = triangles_.v0_z[row], leaf.v1_x[k] = triangles_.v1_x[row];
      leaf.v1_y[k] = triangles_.v1_y[row], leaf.v1_z[k] = triangles_.v1_z[row];
      leaf.v2_x[k] = triangles_.v2_x[row], leaf.v2_y[k] = triangles_.v2_y[row];
      leaf.v2_z[k] = triangles_.v2_z[row];
      bvh_->prim_id[k] = row;
    }
    w->leaf_triangles += end - begin;
    return index;
  }

  const TriangleTable& triangles_;
  const int threads_;
  Bvh* bvh_;
  std::vector<PrimRef> refs_;
  uint32_t task_size_ = 0;
  Bins helper_bins_[2];  // the second binning thread's (FindSplit with two_threads)
};

}  // namespace

Bvh BuildBvh(const TriangleTable& triangles) { return BuildBvh(triangles, SphereTable{}, 1); }

Bvh BuildBvh(const TriangleTable& triangles, const SphereTable& spheres, int threads) {
  PTLAB_CHECK(spheres.size() < kMaxSpheres);
  Bvh bvh;
  Builder(triangles, threads, &bvh).Build();
  bvh.spheres = spheres;
  return bvh;
}

Bvh BuildBvh(const TriangleTable& triangles, const SphereTable& spheres) {
  return BuildBvh(triangles, spheres, 1);
}

}  // namespace ptlab
