// Mitsuba 3's per-pixel Z test (see ztest.h and docs/mitsuba-tests.md).
#include "tools/imgdiff/ztest.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "engine/core/check.h"
#include "tools/common/json_line.h"

namespace ptlab {
namespace {

Image Transform(const Image& image, const double (&m)[3][3]) {
  Image out(image.width, image.height);
  for (size_t i = 0; i < image.rgb.size(); i += 3) {
    const double c[3] = {image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]};
    for (int r = 0; r < 3; ++r)
      out.rgb[i + size_t(r)] = float(m[r][0] * c[0] + m[r][1] * c[1] + m[r][2] * c[2]);
  }
  return out;
}

}  // namespace

Image RgbToXyz(const Image& image) { return Transform(image, kRgbToXyz); }
Image XyzToRgb(const Image& image) { return Transform(image, kXyzToRgb); }

ZTestResult ZTest(const Image& image, const Image& reference, const Image& variance,
                  const ZTestOptions& options) {
  PTLAB_CHECK(image.width == reference.width && image.height == reference.height);
  PTLAB_CHECK(image.width == variance.width && image.height == variance.height);
  PTLAB_CHECK(options.spp > 0);
  const Image mean = RgbToXyz(image), ref = RgbToXyz(reference), var = RgbToXyz(variance);
  ZTestResult r;
  r.width = image.width;
  r.height = image.height;
  r.spp = options.spp;
  const int64_t pixels = int64_t(image.width) * int64_t(image.height);
  r.channels = 3 * pixels;
  r.alpha = pixels > 0 ? -std::expm1(std::log1p(-options.significance) / double(pixels)) : 0.0;
  r.p_value = Image(image.width, image.height);
  r.failed_pixels = Image(image.width, image.height);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (size_t i = 0; i < mean.rgb.size(); ++i) {
    const double v_raw = var.rgb[i];
    // Mitsuba clamps with np.maximum, which keeps NaN.
    const double v = std::isnan(v_raw) ? nan : std::max(v_raw, options.variance_floor);
    const double z =
        std::abs(double(mean.rgb[i]) - double(ref.rgb[i])) * std::sqrt(double(options.spp) / v);
    const double p = std::erfc(z / std::sqrt(2.0));  // 2 (1 - Φ(z)); NaN when z is NaN
    r.p_value.rgb[i] = float(p);
    const bool passed = p > r.alpha;
    r.channels_passed += passed;
    r.failed_pixels.rgb[i] = passed ? 0.02f * image.rgb[i] : 1.0f;
    const double p_rank = std::isnan(p) ? 0.0 : p;
    if (r.min_p_channel < 0 || p_rank < r.min_p) {
      r.min_p = p_rank;
      const size_t pixel = i / 3;
      r.min_p_x = int(pixel % size_t(image.width));
      r.min_p_y = int(pixel / size_t(image.width));
      r.min_p_channel = int(i % 3);
    }
  }
  r.pass_share = r.channels > 0 ? double(r.channels_passed) / double(r.channels) : 1.0;
  // Mitsuba's rule: count_nonzero(p > alpha) / 3 >= 0.9975 · pixel_count.
  r.pass = double(r.channels_passed) / 3.0 >= options.min_pass_share * double(pixels);
  return r;
}

std::string FormatZTestTable(const ZTestResult& r) {
  std::ostringstream o;
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "Z test (XYZ): %dx%d pixels, %u spp, alpha %.6g (Sidak of 0.01 over %lld pixels)\n",
                r.width, r.height, r.spp, r.alpha, (long long)(int64_t(r.width) * r.height));
  o << buf;
  std::snprintf(buf, sizeof buf,
                "  pixel channels with p > alpha: %lld of %lld (%.4f %%; needed %.2f %%)\n",
                (long long)r.channels_passed, (long long)r.channels, 100.0 * r.pass_share, 99.75);
  o << buf;
  std::snprintf(buf, sizeof buf, "  min p: %.6g at pixel (%d, %d) channel %c\n", r.min_p, r.min_p_x,
                r.min_p_y, r.min_p_channel >= 0 ? "XYZ"[r.min_p_channel] : '-');
  o << buf;
  return o.str();
}

std::string FormatZTestJson(const std::string& reference, const std::string& variance,
                            const std::string& image, const ZTestResult& r) {
  Json j;
  j["reference"] = reference;
  j["variance"] = variance;
  j["image"] = image;
  j["width"] = r.width;
  j["height"] = r.height;
  j["spp"] = r.spp;
  j["alpha"] = JsonNumberOrNull(r.alpha);
  j["channels"] = r.channels;
  j["channels_passed"] = r.channels_passed;
  j["pass_share"] = JsonNumberOrNull(r.pass_share);
  j["min_p"] = JsonNumberOrNull(r.min_p);
  j["min_p_x"] = r.min_p_x;
  j["min_p_y"] = r.min_p_y;
  j["min_p_channel"] = r.min_p_channel;
  j["pass"] = r.pass;
  return DumpJsonLine(j);
}

}  // namespace ptlab
