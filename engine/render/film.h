// Film: weighted radiance sums per pixel, filled by splatting samples through the pixel filter.
#pragma once

#include <vector>

#include "engine/core/vec.h"
#include "engine/image/image.h"
#include "engine/render/filter.h"
#include "engine/scene/scene_limits.h"

namespace ptlab {

/// Pixels a sample may touch along one axis; filters are limited to radius < kMaxFilterTaps / 2.
inline constexpr int kMaxFilterTaps = 32;
static_assert(2 * kMaxFilterRadius + 1 <= kMaxFilterTaps, "the largest filter must fit its taps");

/// A rectangle of pixel accumulators (sum of w·L and of w). A tile block covers its tile plus
/// a border of the filter radius; blocks are merged into the full film in a fixed order so
/// the result does not depend on the number of threads.
class FilmBlock {
 public:
  FilmBlock() = default;
  /// Pixels [x0, x0 + width) x [y0, y0 + height) of the image (may extend outside it).
  FilmBlock(int x0, int y0, int width, int height) { Reset(x0, y0, width, height); }
  void Reset(int x0, int y0, int width, int height);
  void Clear();

  /// Splats radiance L of a sample at continuous image position (sx, sy); pixel (i, j) has its
  /// centre at (i + 0.5, j + 0.5).
  void Splat(const PixelFilter& filter, float sx, float sy, const Color3f& radiance);
  /// Adds the overlapping part of other into this block.
  void Merge(const FilmBlock& other);
  /// Normalised image (sum w·L / sum w; 0 where no weight) of this block.
  Image Resolve() const;

  int x0() const { return x0_; }
  int y0() const { return y0_; }
  int width() const { return width_; }
  int height() const { return height_; }
  /// The accumulators, r, g, b, w per pixel in rows: what a block sends to another process.
  const std::vector<float>& sums() const { return sum_; }
  std::vector<float>& sums() { return sum_; }

 private:
  int x0_ = 0, y0_ = 0, width_ = 0, height_ = 0;
  std::vector<float> sum_;  // r, g, b, w per pixel
};

}  // namespace ptlab
