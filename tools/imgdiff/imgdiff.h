// imgdiff library: error metrics, block means, the parity criterion (docs/parity.md), heat map.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/image/image.h"

namespace ptlab {

/// ε in relative MSE = mean((a - b)^2 / (b^2 + ε)).
inline constexpr double kRelMseEpsilon = 1e-2;

/// Pixels of one image with a non-finite channel. A pixel with any NaN channel counts as NaN;
/// otherwise one with any ±Inf channel counts as Inf.
struct NonFiniteCounts {
  int64_t nan_pixels = 0;
  int64_t inf_pixels = 0;
  int64_t total() const { return nan_pixels + inf_pixels; }
};

/// Block-mean comparison of A against B. Blocks tile the image from the top-left corner; partial
/// blocks at the right and bottom edges are INCLUDED, their mean taken over the pixels they cover.
/// A block's mean is over its pixels and the three channels, skipping pixels with a non-finite
/// channel; a block of A that has any non-finite pixel never counts as within tolerance.
/// "Within" means |meanA - meanB| < tol * meanB (strict).
struct BlockComparison {
  int block_size = 32;
  double tol = 0.05;
  double min_mean = 0.01;  ///< only blocks whose mean in B is >= this are eligible
  int blocks_x = 0, blocks_y = 0;
  int64_t eligible = 0;            ///< blocks with mean in B >= min_mean
  int64_t within = 0;              ///< eligible blocks within tol
  double share = 1.0;              ///< within / eligible; 1 when no block is eligible
  int worst_x = -1, worst_y = -1;  ///< top-left pixel of the eligible block with largest rel err
  double worst_rel = 0.0;          ///< its (meanA - meanB) / meanB (+inf if A non-finite there)
};

/// Options of CompareImages.
struct ImageDiffOptions {
  bool flip_x = false;      ///< mirror A left-right before comparing
  int block_size = 32;      ///< block comparison: block edge in pixels (>= 1)
  double block_tol = 0.05;  ///< block comparison: relative tolerance
  double block_min = 0.01;  ///< block comparison: floor on B's block mean
  double psnr_peak = 0.0;   ///< > 0: PSNR peak; <= 0: the maximum finite value of B
};

/// Metrics of image A (test) against image B (reference); channels 0,1,2 = R,G,B.
/// Pixel errors (MAE, MSE, RMSE, relMSE, max abs error, PSNR) are over the pixels finite in BOTH
/// images ("compared" pixels). Means of each image are over that image's own finite pixels.
struct ImageDiff {
  int width = 0, height = 0;
  bool flip_x = false;
  int64_t compared_pixels = 0;
  std::array<double, 3> mae{}, mse{}, rmse{}, rel_mse{};
  double mae_all = 0, mse_all = 0, rmse_all = 0, rel_mse_all = 0;  ///< over all three channels
  double psnr_db = 0;    ///< 10 log10(peak^2 / mse_all); +inf when mse_all = 0
  double psnr_peak = 0;  ///< the peak used
  double max_abs_error = 0;
  int max_abs_x = -1, max_abs_y = -1, max_abs_channel = -1;  ///< where, in A's (flipped) frame
  NonFiniteCounts nonfinite_a, nonfinite_b;
  std::array<double, 3> mean_a{}, mean_b{};
  std::array<double, 3> mean_rel_diff{};  ///< (mean_a - mean_b) / mean_b per channel
  double max_abs_mean_rel = 0;            ///< max over channels of |mean_rel_diff|
  BlockComparison blocks;
};

/// Result of docs/parity.md's criterion P(f) for a render against a reference.
struct ParityResult {
  bool pass = false;
  bool size_ok = false;  ///< same width and height
  bool flip_x = false;   ///< the render was mirrored left-right first
  // 1. The mean of each channel of the render is within 1 % of the reference's (strict <).
  bool means_ok = false;
  double mean_tol = 0.01;
  std::array<double, 3> mean_render{}, mean_reference{}, mean_rel_diff{};
  // 2. No pixel of the render is NaN or Inf.
  bool finite_ok = false;
  NonFiniteCounts nonfinite_render;
  // 3. Share of 32x32 blocks (reference mean >= 0.01) within 5 % is >= min_block_share.
  bool blocks_ok = false;
  double min_block_share = 0;
  BlockComparison blocks;
  std::string summary;  ///< one line, e.g. "PASS P(0.97): means ... ; 0 NaN/Inf; blocks ..."
};

/// A copy of `image` mirrored left-right.
Image FlipX(const Image& image);

/// Pixels of `image` with a NaN or Inf channel.
NonFiniteCounts CountNonFinite(const Image& image);

/// Mean of each channel over the pixels whose three channels are finite (0 if none is).
std::array<double, 3> ChannelMeans(const Image& image);

/// Block-mean comparison (see BlockComparison). Precondition: same size, block_size >= 1.
BlockComparison CompareBlocks(const Image& a, const Image& b, int block_size, double tol,
                              double min_mean);

/// All metrics of A against B. Precondition: same size (check with SameSize first).
ImageDiff CompareImages(const Image& a, const Image& b, const ImageDiffOptions& options);

/// Whether a and b have the same width and height.
inline bool SameSize(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height;
}

/// docs/parity.md's criterion P(min_block_share): channel means within 1 %, no NaN/Inf in the
/// render, share of 32x32 blocks with reference mean >= 0.01 whose render mean is within 5 % >= f.
/// `flip_x` mirrors the render left-right first (for eth2015 references). A size mismatch fails.
ParityResult CheckParity(const Image& render, const Image& reference, double min_block_share,
                         bool flip_x);

/// Signed relative-error heat map in a blue-white-red diverging map. Per pixel, with a and b the
/// means of the three channels, e = (a - b) / sqrt(b^2 + kRelMseEpsilon); e = -scale is pure
/// blue, 0 white, +scale pure red (linear ramps in sRGB display values, clamped beyond ±scale);
/// pixels non-finite in A or B are green. Returned as linear RGB so that WritePng shows exactly
/// these display colours. Precondition: same size, scale > 0.
Image RelativeErrorHeatmap(const Image& a, const Image& b, double scale);

/// Pass/fail thresholds of the imgdiff CLI; unset ones are not checked.
struct DiffThresholds {
  std::optional<double> rmse;         ///< fail if rmse_all > X
  std::optional<double> rel_mse;      ///< fail if rel_mse_all > X
  std::optional<double> mean_rel;     ///< fail if max_abs_mean_rel > X
  std::optional<double> block_share;  ///< fail if blocks.share < F
  bool any() const { return rmse || rel_mse || mean_rel || block_share; }
};

/// The reasons `diff` fails `thresholds` (empty = pass). When any threshold is set, NaN/Inf
/// pixels in A are a failure too (the metrics skip them, so they could otherwise hide).
std::vector<std::string> CheckThresholds(const ImageDiff& diff, const DiffThresholds& thresholds);

/// A readable multi-line table of `diff` (and of `parity` if given).
std::string FormatDiffTable(const ImageDiff& diff, const ParityResult* parity);

/// One JSON object with every field of `diff`, `parity` (or null), the failures and "pass".
/// Non-finite numbers are written as null.
std::string FormatDiffJson(const std::string& path_a, const std::string& path_b,
                           const ImageDiff& diff, const ParityResult* parity,
                           const std::vector<std::string>& failures);

}  // namespace ptlab
