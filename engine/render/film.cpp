// Film: weighted radiance sums per pixel, filled by splatting samples through the pixel filter.
#include "engine/render/film.h"

#include <algorithm>
#include <cmath>

#include "engine/core/check.h"

namespace ptlab {

FilmBlock& FilmBlock::operator=(const FilmBlock& other) {
  if (this == &other) return *this;
  x0_ = other.x0_, y0_ = other.y0_, width_ = other.width_, height_ = other.height_;
  own_.assign(other.sum_.begin(), other.sum_.end());
  sum_ = own_;
  return *this;
}

FilmBlock& FilmBlock::operator=(FilmBlock&& other) noexcept {
  if (this == &other) return *this;
  x0_ = other.x0_, y0_ = other.y0_, width_ = other.width_, height_ = other.height_;
  const bool owned = other.sum_.data() == other.own_.data();
  own_ = std::move(other.own_);  // the buffer moves with it: an own sum_ stays valid
  sum_ = owned ? std::span<float>(own_) : other.sum_;
  other.sum_ = {}, other.own_.clear();
  other.x0_ = other.y0_ = other.width_ = other.height_ = 0;
  return *this;
}

void FilmBlock::Reset(int x0, int y0, int width, int height) {
  x0_ = x0, y0_ = y0, width_ = width, height_ = height;
  own_.assign(size_t(width) * size_t(height) * 4, 0.0f);
  sum_ = own_;
}

void FilmBlock::Reset(int x0, int y0, int width, int height, std::span<float> storage) {
  PTLAB_CHECK(storage.size() == size_t(width) * size_t(height) * 4);
  x0_ = x0, y0_ = y0, width_ = width, height_ = height;
  own_ = {};
  sum_ = storage;
  std::fill(sum_.begin(), sum_.end(), 0.0f);
}

void FilmBlock::Clear() { std::fill(sum_.begin(), sum_.end(), 0.0f); }

void FilmBlock::Splat(const PixelFilter& filter, float sx, float sy, const Color3f& radiance) {
  const SplatFootprint f = Footprint(filter.radius(), sx, sy);
  const int nx = std::min(kMaxFilterTaps, f.ix1 - f.ix0 + 1);
  if (nx <= 0) return;
  float wx[kMaxFilterTaps];
  for (int i = 0; i < nx; ++i) wx[i] = filter.Eval(float(f.ix0 + i) + 0.5f - sx);
  for (int j = f.iy0; j <= f.iy1; ++j) {
    const float wy = filter.Eval(float(j) + 0.5f - sy);
    if (wy == 0.0f) continue;
    float* row = PixelSums(f.ix0, j);
    for (int i = 0; i < nx; ++i) {
      const float w = wx[i] * wy;
      row[4 * i + 0] += w * radiance.r;
      row[4 * i + 1] += w * radiance.g;
      row[4 * i + 2] += w * radiance.b;
      row[4 * i + 3] += w;
    }
  }
}

void FilmBlock::Merge(const FilmBlock& other) {
  const int xa = std::max(x0_, other.x0_), xb = std::min(x0_ + width_, other.x0_ + other.width_);
  const int ya = std::max(y0_, other.y0_), yb = std::min(y0_ + height_, other.y0_ + other.height_);
  for (int y = ya; y < yb; ++y) {
    float* dst = &sum_[(size_t(y - y0_) * size_t(width_) + size_t(xa - x0_)) * 4];
    const float* src =
        &other.sum_[(size_t(y - other.y0_) * size_t(other.width_) + size_t(xa - other.x0_)) * 4];
    for (int i = 0; i < (xb - xa) * 4; ++i) dst[i] += src[i];
  }
}

Image FilmBlock::Resolve() const {
  Image image(width_, height_);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const float* p = &sum_[(size_t(y) * size_t(width_) + size_t(x)) * 4];
      if (p[3] > 0) image.Set(x, y, Color3f{p[0], p[1], p[2]} / p[3]);
    }
  return image;
}

}  // namespace ptlab
