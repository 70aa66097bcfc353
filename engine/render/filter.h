// Pixel reconstruction filters (Nori's box, tent and Gaussian), evaluated per axis.
#pragma once

#include <algorithm>
#include <cmath>

#include "engine/scene/scene.h"

namespace ptlab {

/// Separable filter: weight(dx, dy) = Eval(dx) * Eval(dy), zero beyond radius.
class PixelFilter {
 public:
  explicit PixelFilter(const FilterDesc& desc) : desc_(desc) {
    if (desc.type == FilterDesc::Type::kGaussian) {
      alpha_ = -1.0f / (2.0f * desc.stddev * desc.stddev);
      tail_ = std::exp(alpha_ * desc.radius * desc.radius);
    }
  }
  float radius() const { return desc_.radius; }
  /// Nori's definitions: box 1; tent max(0, 1 - |x|/r); Gaussian exp(αx²) - exp(αr²),
  /// α = -1/(2σ²), clamped at 0 (the shift makes it reach zero at the radius).
  float Eval(float x) const {
    const float ax = std::fabs(x);
    if (ax > desc_.radius) return 0.0f;
    switch (desc_.type) {
      case FilterDesc::Type::kBox: return 1.0f;
      case FilterDesc::Type::kTent: return std::max(0.0f, 1.0f - ax / desc_.radius);
      case FilterDesc::Type::kGaussian: return std::max(0.0f, std::exp(alpha_ * x * x) - tail_);
    }
    return 0.0f;
  }

 private:
  FilterDesc desc_;
  float alpha_ = 0, tail_ = 0;
};

}  // namespace ptlab
