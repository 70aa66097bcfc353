// Pixel reconstruction filters (Nori's box, tent and Gaussian), evaluated per axis through a
// table precomputed over [0, radius].
#pragma once

#include <algorithm>
#include <cmath>

#include "engine/scene/scene.h"

namespace ptlab {

/// Intervals of the filter table over [0, radius] (kFilterTableSize + 1 samples).
inline constexpr int kFilterTableSize = 256;

/// Separable filter: weight(dx, dy) = Eval(dx) * Eval(dy), zero beyond radius.
/// As in Nori, the film does not evaluate the filter per tap: the constructor tabulates it once
/// over [0, radius] and Eval looks it up, here interpolating linearly between the samples. The
/// error against EvalExact is ≤ h²/8 · max|EvalExact''| (h = radius / kFilterTableSize) plus
/// rounding: 0 for the box, rounding only for the tent, ≤ h²/(8σ²) for the Gaussian (3.1e-5 at
/// Nori's radius 2, σ 0.5); tests/engine/render/film_test.cpp checks it.
class PixelFilter {
 public:
  explicit PixelFilter(const FilterDesc& desc) : desc_(desc) {
    if (desc.type == FilterDesc::Type::kGaussian) {
      alpha_ = -1.0f / (2.0f * desc.stddev * desc.stddev);
      tail_ = std::exp(alpha_ * desc.radius * desc.radius);
    }
    for (int i = 0; i <= kFilterTableSize; ++i)
      table_[i] = EvalExact(desc.radius * float(i) / float(kFilterTableSize));
    lookup_scale_ = desc.radius > 0 ? float(kFilterTableSize) / desc.radius : 0.0f;
  }
  float radius() const { return desc_.radius; }
  /// The table Eval interpolates: kFilterTableSize + 1 samples over [0, radius], and the scale
  /// from |x| to a table position (kFilterTableSize / radius); for kernels that evaluate many
  /// offsets at once with Eval's operations (simd/wavefront/splat8-inl.h).
  const float* table() const { return table_; }
  float lookup_scale() const { return lookup_scale_; }

  /// The filter at offset x (pixels) from the table: what the film splats with.
  float Eval(float x) const {
    const float ax = std::fabs(x);
    if (!(ax <= desc_.radius)) return 0.0f;
    const float t = ax * lookup_scale_;
    const int i = std::min(int(t), kFilterTableSize - 1);
    const float frac = t - float(i);
    return table_[i] + frac * (table_[i + 1] - table_[i]);
  }

  /// Nori's definitions: box 1; tent max(0, 1 - |x|/r); Gaussian exp(αx²) - exp(αr²),
  /// α = -1/(2σ²), clamped at 0 (the shift makes it reach zero at the radius).
  float EvalExact(float x) const {
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
  float lookup_scale_ = 0;
  float table_[kFilterTableSize + 1] = {};
};

}  // namespace ptlab
