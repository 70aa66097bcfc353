// Pixel reconstruction filters (Nori's box, tent and Gaussian), evaluated per axis through a
// table precomputed over [0, radius]: interpolated, or as Mitsuba's scalar variants a staircase.
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
    if (desc.steps > 0 && desc.steps <= kFilterTableSize) {
      // A staircase (FilterDesc::steps): step i holds the value at its inner end, the last
      // entry is 0 (reached only at |x| = radius), and next_ = table_ so that Eval's
      // interpolation adds nothing.
      const int n = desc.steps;
      for (int i = 0; i < n; ++i) table_[i] = EvalExact(desc.radius * float(i) / float(n));
      table_[n] = 0.0f;
      for (int i = 0; i <= n; ++i) next_[i] = table_[i];
      last_ = n;
      lookup_scale_ = desc.radius > 0 ? float(n) / desc.radius : 0.0f;
    } else {
      for (int i = 0; i <= kFilterTableSize; ++i)
        table_[i] = EvalExact(desc.radius * float(i) / float(kFilterTableSize));
      for (int i = 0; i < kFilterTableSize; ++i) next_[i] = table_[i + 1];
      next_[kFilterTableSize] = table_[kFilterTableSize];
      last_ = kFilterTableSize - 1;
      lookup_scale_ = desc.radius > 0 ? float(kFilterTableSize) / desc.radius : 0.0f;
    }
  }
  float radius() const { return desc_.radius; }
  /// What Eval reads, for kernels that evaluate many offsets at once with Eval's operations
  /// (simd/wavefront/splat8-inl.h): the table (entries 0 ..= last_index()), the entry each one
  /// interpolates towards (`next`: the following entry, or the same one for a staircase), and
  /// the scale from |x| to a table position.
  const float* table() const { return table_; }
  const float* next() const { return next_; }
  int last_index() const { return last_; }
  float lookup_scale() const { return lookup_scale_; }

  /// The filter at offset x (pixels) from the table: what the film splats with.
  float Eval(float x) const {
    const float ax = std::fabs(x);
    if (!(ax <= desc_.radius)) return 0.0f;
    const float t = ax * lookup_scale_;
    const int i = std::min(int(t), last_);
    const float frac = t - float(i);
    return table_[i] + frac * (next_[i] - table_[i]);
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
  int last_ = 0;
  float table_[kFilterTableSize + 1] = {};
  float next_[kFilterTableSize + 1] = {};
};

}  // namespace ptlab
