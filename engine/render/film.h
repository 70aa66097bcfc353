// Film: weighted radiance sums per pixel, filled by splatting samples through the pixel filter.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "engine/core/aligned.h"
#include "engine/core/memory.h"
#include "engine/core/vec.h"
#include "engine/image/image.h"
#include "engine/render/filter.h"
#include "engine/scene/scene_limits.h"

namespace ptlab {

/// Pixels a sample may touch along one axis; filters are limited to radius < kMaxFilterTaps / 2.
inline constexpr int kMaxFilterTaps = 32;
static_assert(2 * kMaxFilterRadius + 1 <= kMaxFilterTaps, "the largest filter must fit its taps");

/// The pixels of a block one sample touches: [ix0, ix1] x [iy0, iy1], image coordinates (empty
/// when ix1 < ix0 or iy1 < iy0).
struct SplatFootprint {
  int ix0 = 0, ix1 = -1, iy0 = 0, iy1 = -1;
};

/// A rectangle of pixel accumulators (sum of w·L and of w). A tile block covers its tile plus
/// a border of the filter radius; blocks are merged into the full film in a fixed order so
/// the result does not depend on the number of threads.
class FilmBlock {
 public:
  FilmBlock() = default;
  /// Pixels [x0, x0 + width) x [y0, y0 + height) of the image (may extend outside it).
  FilmBlock(int x0, int y0, int width, int height) { Reset(x0, y0, width, height); }
  /// A copy holds its accumulators itself (whatever the storage of `other`).
  FilmBlock(const FilmBlock& other) { *this = other; }
  FilmBlock& operator=(const FilmBlock& other);
  FilmBlock(FilmBlock&& other) noexcept { *this = std::move(other); }
  FilmBlock& operator=(FilmBlock&& other) noexcept;

  /// Zeroed accumulators of its own for the rectangle.
  void Reset(int x0, int y0, int width, int height);
  /// Zeroed accumulators for the rectangle in `storage` (width * height * 4 floats, which must
  /// outlive the block's use): the render keeps its tiles' blocks in one arena, on huge pages
  /// (AlignedVector), as each block's own 20 KiB cost five page faults (~15 µs each on a VM:
  /// 45 ms of a 1.8 s table render).
  void Reset(int x0, int y0, int width, int height, std::span<float> storage);
  void Clear();

  /// Splats radiance L of a sample at continuous image position (sx, sy); pixel (i, j) has its
  /// centre at (i + 0.5, j + 0.5).
  void Splat(const PixelFilter& filter, float sx, float sy, const Color3f& radiance);
  /// The pixels of this block whose centre lies within `radius` of (sx, sy) on both axes.
  /// Inline: the SIMD splat calls it per sample.
  SplatFootprint Footprint(float radius, float sx, float sy) const {
    // Pixels whose centre lies within the radius: i + 0.5 in [sx - r, sx + r].
    SplatFootprint f;
    f.ix0 = std::max(x0_, int(std::ceil(sx - 0.5f - radius)));
    f.ix1 = std::min(x0_ + width_ - 1, int(std::floor(sx - 0.5f + radius)));
    f.iy0 = std::max(y0_, int(std::ceil(sy - 0.5f - radius)));
    f.iy1 = std::min(y0_ + height_ - 1, int(std::floor(sy - 0.5f + radius)));
    return f;
  }
  /// The r, g, b, w accumulators of pixel (x, y) (image coordinates, inside the block) and the
  /// pixels after it in its row.
  float* PixelSums(int x, int y) {
    return &sum_[(size_t(y - y0_) * size_t(width_) + size_t(x - x0_)) * 4];
  }
  /// Adds the overlapping part of other into this block.
  void Merge(const FilmBlock& other);
  /// Normalised image (sum w·L / sum w; 0 where no weight) of this block.
  Image Resolve() const;

  int x0() const { return x0_; }
  int y0() const { return y0_; }
  int width() const { return width_; }
  int height() const { return height_; }
  /// The accumulators, r, g, b, w per pixel in rows: what a block sends to another process.
  std::span<const float> sums() const { return sum_; }
  std::span<float> sums() { return sum_; }
  /// Heap bytes of its own accumulators (capacity × element size; none in outside storage).
  size_t Bytes() const { return VectorBytes(own_); }

 private:
  int x0_ = 0, y0_ = 0, width_ = 0, height_ = 0;
  std::span<float> sum_;  // r, g, b, w per pixel: own_, or the storage given to Reset
  // An image-sized film on huge pages (AlignedVector): on a VM where a page fault costs ~15 µs,
  // first touching 800 x 600 pixels' 7.3 MiB in 4 KiB pages took 25 ms.
  AlignedVector<float> own_;
};

}  // namespace ptlab
