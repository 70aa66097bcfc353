// The light image of light tracing (see light_film.h).
#include "engine/render/light_film.h"

#include <algorithm>
#include <cmath>

namespace ptlab {
namespace {

// 1 / ∫ f(x - c) dx over [0, extent] for each pixel centre c = i + 0.5 (midpoint rule, 64
// intervals per pixel: the filter is smooth or piecewise linear, so the sums agree with the
// integral to ~1e-4, far below any render's noise).
std::vector<float> InverseIntegrals(const PixelFilter& filter, int extent) {
  constexpr int kSteps = 64;
  const float r = filter.radius();
  std::vector<float> inv(size_t(extent), 0.0f);
  for (int i = 0; i < extent; ++i) {
    const float c = float(i) + 0.5f;
    const float a = std::max(0.0f, c - r), b = std::min(float(extent), c + r);
    const int n = std::max(1, int(std::ceil((b - a) * kSteps)));
    const double h = double(b - a) / n;
    double sum = 0;
    for (int k = 0; k < n; ++k) sum += filter.Eval(float(a + (k + 0.5) * h) - c);
    sum *= h;
    inv[size_t(i)] = sum > 0 ? float(1.0 / sum) : 0.0f;
  }
  return inv;
}

}  // namespace

LightFilm::LightFilm(const PixelFilter& filter, int width, int height)
    : filter_(&filter),
      width_(width),
      height_(height),
      inv_zx_(InverseIntegrals(filter, width)),
      inv_zy_(InverseIntegrals(filter, height)),
      sum_(size_t(width) * size_t(height) * 3, 0.0f) {}

void LightFilm::Splat(float sx, float sy, const Color3f& value) {
  if (!(sx >= 0 && sx < float(width_) && sy >= 0 && sy < float(height_))) return;
  const float r = filter_->radius();
  const int ix0 = std::max(0, int(std::ceil(sx - 0.5f - r)));
  const int ix1 = std::min(width_ - 1, int(std::floor(sx - 0.5f + r)));
  const int iy0 = std::max(0, int(std::ceil(sy - 0.5f - r)));
  const int iy1 = std::min(height_ - 1, int(std::floor(sy - 0.5f + r)));
  for (int j = iy0; j <= iy1; ++j) {
    const float wy = filter_->Eval(float(j) + 0.5f - sy) * inv_zy_[size_t(j)];
    if (wy == 0.0f) continue;
    for (int i = ix0; i <= ix1; ++i) {
      const float w = filter_->Eval(float(i) + 0.5f - sx) * inv_zx_[size_t(i)] * wy;
      float* p = &sum_[(size_t(j) * size_t(width_) + size_t(i)) * 3];
      p[0] += w * value.r;
      p[1] += w * value.g;
      p[2] += w * value.b;
    }
  }
}

void LightFilm::Add(const LightFilm& other) {
  for (size_t k = 0; k < sum_.size(); ++k) sum_[k] += other.sum_[k];
}

void LightFilm::Clear() { std::fill(sum_.begin(), sum_.end(), 0.0f); }

void LightFilm::ComposeInto(const FilmBlock& camera, uint32_t spp, FilmBlock* out) const {
  *out = camera;
  const float inv_spp = spp > 0 ? 1.0f / float(spp) : 0.0f;
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      float* p = out->PixelSums(x, y);
      const float* s = &sum_[(size_t(y) * size_t(width_) + size_t(x)) * 3];
      const float k = p[3] * inv_spp;
      p[0] += s[0] * k, p[1] += s[1] * k, p[2] += s[2] * k;
    }
  }
}

}  // namespace ptlab
