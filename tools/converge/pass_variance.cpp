// PassVariance: batch-means variance of a render's pixels (see pass_variance.h).
#include "tools/converge/pass_variance.h"

#include <limits>

#include "tools/imgdiff/ztest.h"

namespace ptlab {

PassVariance::PassVariance(int width, int height)
    : width_(width),
      height_(height),
      scratch_(0, 0, width, height),
      count_(size_t(width) * size_t(height), 0),
      weight_(count_.size(), 0.0),
      mean_(count_.size() * 3, 0.0),
      m2_(count_.size() * 3, 0.0) {}

void PassVariance::AddPass(const std::vector<FilmBlock>& blocks) {
  scratch_.Clear();
  for (const FilmBlock& b : blocks) scratch_.Merge(b);
  ++passes_;
  for (int y = 0; y < height_; ++y) {
    const float* s = scratch_.PixelSums(0, y);
    for (int x = 0; x < width_; ++x, s += 4) {
      const double w = s[3];
      if (!(w > 0)) continue;
      const double rgb[3] = {s[0] / w, s[1] / w, s[2] / w};
      const size_t p = size_t(y) * size_t(width_) + size_t(x);
      ++count_[p];
      const double total = weight_[p] + w;
      for (int c = 0; c < 3; ++c) {
        const double v =
            kRgbToXyz[c][0] * rgb[0] + kRgbToXyz[c][1] * rgb[1] + kRgbToXyz[c][2] * rgb[2];
        // West's weighted update: stable where Σ W m² - (Σ W m)² / Σ W would cancel.
        double& mean = mean_[p * 3 + size_t(c)];
        const double delta = v - mean;
        mean += delta * (w / total);
        m2_[p * 3 + size_t(c)] += w * delta * (v - mean);
      }
      weight_[p] = total;
    }
  }
}

Image PassVariance::PerSampleVariance(uint32_t spp) const {
  Image xyz(width_, height_);
  for (size_t p = 0; p < count_.size(); ++p) {
    for (int c = 0; c < 3; ++c) {
      xyz.rgb[p * 3 + size_t(c)] =
          count_[p] >= 2
              ? float(double(spp) * m2_[p * 3 + size_t(c)] / (double(count_[p] - 1) * weight_[p]))
              : std::numeric_limits<float>::quiet_NaN();
    }
  }
  return XyzToRgb(xyz);
}

}  // namespace ptlab
