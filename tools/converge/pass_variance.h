// PassVariance: a render's per-pixel per-sample variance, estimated from its passes (batch means).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/image/image.h"
#include "engine/render/film.h"

namespace ptlab {

/// Accumulates the passes of a render (RenderPass::blocks, each pass's tile blocks) and estimates
/// each pixel's per-sample variance by batch means, in XYZ, for Mitsuba's Z test
/// (docs/mitsuba-tests.md). Pass k gives pixel value m_k = Σ w·L / W_k (W_k = Σ w, its filter
/// weight; the number of samples with a box filter), converted to XYZ. With K passes and the
/// weighted mean m = Σ W_k m_k / Σ W_k (the image's pixel),
///   s² = Σ W_k (m_k - m)² / (K - 1)
/// is unbiased for σ² when the passes are independent and Var(m_k) = σ² / W_k (independent
/// samples of one distribution; exact for a box filter), with K - 1 degrees of freedom. The
/// variance of the image's pixel is then s² / Σ W_k, and the per-sample variance written is
/// spp · s² / Σ W_k (= s² for a box filter), so that z = |mean - ref| sqrt(spp / var) uses
/// exactly the estimated variance of the pixel.
class PassVariance {
 public:
  /// Samples per pass of a render whose variance this estimates: 16, or fewer so that there
  /// are at least kMinPasses passes (spp / kMinPasses, at least 1): the estimate has K - 1
  /// degrees of freedom, and a few (61 spp in 16-sample passes: 3) leave the Z test at the
  /// mercy of the variance estimate's own noise.
  static constexpr uint32_t kMinPasses = 32;
  static uint32_t PassSamples(uint32_t spp) {
    const uint32_t n = spp / kMinPasses;
    return n < 1 ? 1 : (n > 16 ? 16 : n);
  }

  PassVariance(int width, int height);
  /// Adds one completed pass: its tile blocks (any rectangles of the image, merged here).
  void AddPass(const std::vector<FilmBlock>& blocks);
  uint32_t passes() const { return passes_; }
  /// The per-sample variance of each pixel for an image of `spp` samples per pixel, in XYZ,
  /// stored as Mitsuba stores its `_var.exr` (through kXyzToRgb, tools/imgdiff/ztest.h) so that
  /// `imgdiff --ztest` reads both alike. NaN where a pixel had weight in fewer than 2 passes.
  Image PerSampleVariance(uint32_t spp) const;

 private:
  int width_, height_;
  uint32_t passes_ = 0;
  FilmBlock scratch_;
  // Per pixel: passes with weight, Σ W, weighted mean and Σ W (m - mean)² (West 1979) per
  // XYZ channel.
  std::vector<uint32_t> count_;
  std::vector<double> weight_, mean_, m2_;
};

}  // namespace ptlab
