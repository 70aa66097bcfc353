// Mitsuba 3's per-pixel Z test of a render against a reference and a per-sample variance image.
#pragma once

#include <cstdint>
#include <string>

#include "engine/image/image.h"

namespace ptlab {

/// Linear Rec. 709 RGB -> CIE XYZ (D65), the matrix Mitsuba 3's Bitmap::convert applies (its
/// srgb_to_xyz, written to 6 digits there). Row i gives output channel i.
inline constexpr double kRgbToXyz[3][3] = {
    {0.412453, 0.357580, 0.180423}, {0.212671, 0.715160, 0.072169}, {0.019334, 0.119193, 0.950227}};
/// CIE XYZ -> linear Rec. 709 RGB, Mitsuba 3's xyz_to_srgb (the inverse of kRgbToXyz to ~1e-6).
inline constexpr double kXyzToRgb[3][3] = {{3.240479, -1.537150, -0.498535},
                                           {-0.969256, 1.875991, 0.041556},
                                           {0.055648, -0.204043, 1.057311}};

/// `image` with every pixel multiplied by kRgbToXyz (channels become X, Y, Z).
Image RgbToXyz(const Image& image);
/// `image` with every pixel multiplied by kXyzToRgb (channels X, Y, Z become R, G, B).
Image XyzToRgb(const Image& image);

/// Parameters of ZTest; the defaults are Mitsuba 3's (src/render/tests/test_renders.py).
struct ZTestOptions {
  uint32_t spp = 0;                ///< samples per pixel of the tested image (> 0)
  double significance = 0.01;      ///< family-wise level before the Šidák correction
  double min_pass_share = 0.9975;  ///< pass when this share of pixel channels has p > alpha
  double variance_floor = 1e-4;    ///< the variance is clamped below at this (in XYZ)
};

/// Outcome of ZTest. Channels are X, Y, Z throughout.
struct ZTestResult {
  int width = 0, height = 0;
  uint32_t spp = 0;
  int64_t channels = 0;         ///< 3 · width · height
  int64_t channels_passed = 0;  ///< channels with p > alpha (a NaN p never passes)
  double pass_share = 0;        ///< channels_passed / channels
  double alpha = 0;             ///< Šidák level 1 - (1 - significance)^(1 / pixels)
  double min_p = 1;             ///< smallest p (NaN p counts as 0 here)
  int min_p_x = -1, min_p_y = -1, min_p_channel = -1;
  bool pass = false;
  Image p_value;  ///< per pixel channel two-sided p (channels X, Y, Z; NaN where undefined)
  /// Mitsuba's error image: the tested RGB image times 0.02, and 1 in every channel whose XYZ
  /// counterpart (same index) failed.
  Image failed_pixels;
};

/// Mitsuba 3's Z test. `image`, `reference` and `variance` are linear RGB images of one size, as
/// read from EXR; all three are converted to XYZ with kRgbToXyz — the variance too, because
/// Mitsuba stores a per-sample variance computed in XYZ through kXyzToRgb (its `_var.exr`; see
/// docs/mitsuba-tests.md). Per pixel channel, with v = max(variance, variance_floor) (NaN stays
/// NaN): z = |image - reference| · sqrt(spp / v), p = 2 (1 - Φ(z)) = erfc(z / √2). The test
/// passes when channels_passed / 3 >= min_pass_share · pixels, where a channel passes when
/// p > alpha = 1 - (1 - significance)^(1 / pixels) (Šidák). p is computed in double precision.
/// Preconditions: same size, spp > 0.
ZTestResult ZTest(const Image& image, const Image& reference, const Image& variance,
                  const ZTestOptions& options);

/// A readable multi-line summary of `result`.
std::string FormatZTestTable(const ZTestResult& result);

/// One JSON object with the scalar fields of `result` (non-finite numbers as null).
std::string FormatZTestJson(const std::string& reference, const std::string& variance,
                            const std::string& image, const ZTestResult& result);

}  // namespace ptlab
