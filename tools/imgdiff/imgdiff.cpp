// imgdiff library: metrics, block parity (docs/parity.md), heat map, and the table/JSON reports.
#include "tools/imgdiff/imgdiff.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/core/check.h"
#include "engine/image/srgb.h"
#include "tools/common/json_line.h"

namespace ptlab {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

bool PixelFinite(const float* p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// "Within relative tolerance": strict, except that exact equality always passes (so a channel
// whose reference mean is 0 passes only if the other mean is 0 too).
bool WithinRelative(double value, double reference, double tol) {
  const double d = std::fabs(value - reference);
  return d == 0 || d < tol * reference;
}

double RelDiff(double value, double reference) {
  if (value == reference) return 0;
  if (reference == 0) return value > 0 ? kInf : -kInf;
  return (value - reference) / reference;
}

std::string Format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), fmt, v);
  return buf;
}

std::string Percent(double v) { return Format("%+.3f%%", 100 * v); }

std::string BlockLine(const BlockComparison& b) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), "%lld/%lld blocks = %.2f%% within %g%%",
                static_cast<long long>(b.within), static_cast<long long>(b.eligible), 100 * b.share,
                100 * b.tol);
  return buf;
}

// --- minimal JSON writer ---

Json JsonArray(const std::array<double, 3>& v) {
  Json a = Json::array();
  for (int c = 0; c < 3; ++c) a.push_back(JsonNumberOrNull(v[c]));
  return a;
}

Json JsonNonFinite(const NonFiniteCounts& n) {
  Json j;
  j["nan_pixels"] = n.nan_pixels;
  j["inf_pixels"] = n.inf_pixels;
  return j;
}

Json JsonBlocks(const BlockComparison& b) {
  Json j;
  j["block_size"] = b.block_size;
  j["tol"] = JsonNumberOrNull(b.tol);
  j["min_mean"] = JsonNumberOrNull(b.min_mean);
  j["partial_edge_blocks"] = "included";
  j["blocks_x"] = b.blocks_x;
  j["blocks_y"] = b.blocks_y;
  j["eligible"] = b.eligible;
  j["within"] = b.within;
  j["share"] = JsonNumberOrNull(b.share);
  Json worst;
  worst["x"] = b.worst_x;
  worst["y"] = b.worst_y;
  worst["rel"] = JsonNumberOrNull(b.worst_rel);
  j["worst_block"] = worst;
  return j;
}

}  // namespace

Image FlipX(const Image& image) {
  Image out(image.width, image.height);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) out.Set(image.width - 1 - x, y, image.At(x, y));
  }
  return out;
}

NonFiniteCounts CountNonFinite(const Image& image) {
  NonFiniteCounts n;
  for (size_t i = 0; i + 2 < image.rgb.size(); i += 3) {
    const float* p = &image.rgb[i];
    if (std::isnan(p[0]) || std::isnan(p[1]) || std::isnan(p[2])) {
      ++n.nan_pixels;
    } else if (!PixelFinite(p)) {
      ++n.inf_pixels;
    }
  }
  return n;
}

std::array<double, 3> ChannelMeans(const Image& image) {
  std::array<double, 3> sum{};
  int64_t count = 0;
  for (size_t i = 0; i + 2 < image.rgb.size(); i += 3) {
    const float* p = &image.rgb[i];
    if (!PixelFinite(p)) continue;
    for (int c = 0; c < 3; ++c) sum[c] += p[c];
    ++count;
  }
  if (count > 0) {
    for (double& s : sum) s /= double(count);
  }
  return sum;
}

BlockComparison CompareBlocks(const Image& a, const Image& b, int block_size, double tol,
                              double min_mean) {
  PTLAB_CHECK(SameSize(a, b) && block_size >= 1);
  BlockComparison r;
  r.block_size = block_size;
  r.tol = tol;
  r.min_mean = min_mean;
  r.blocks_x = (a.width + block_size - 1) / block_size;
  r.blocks_y = (a.height + block_size - 1) / block_size;
  double worst_abs = -1;
  for (int by = 0; by < r.blocks_y; ++by) {
    for (int bx = 0; bx < r.blocks_x; ++bx) {
      const int x0 = bx * block_size, y0 = by * block_size;
      const int x1 = std::min(x0 + block_size, a.width), y1 = std::min(y0 + block_size, a.height);
      double sum_a = 0, sum_b = 0;
      int64_t n_a = 0, n_b = 0;
      bool a_nonfinite = false;
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          const size_t i = (size_t(y) * size_t(a.width) + size_t(x)) * 3;
          const float* pa = &a.rgb[i];
          const float* pb = &b.rgb[i];
          if (PixelFinite(pa)) {
            sum_a += double(pa[0]) + pa[1] + pa[2];
            ++n_a;
          } else {
            a_nonfinite = true;
          }
          if (PixelFinite(pb)) {
            sum_b += double(pb[0]) + pb[1] + pb[2];
            ++n_b;
          }
        }
      }
      if (n_b == 0) continue;
      const double mean_b = sum_b / (3.0 * double(n_b));
      if (!(mean_b >= min_mean)) continue;
      ++r.eligible;
      double rel = kInf;
      if (!a_nonfinite) {
        const double mean_a = sum_a / (3.0 * double(n_a));
        rel = RelDiff(mean_a, mean_b);
        if (WithinRelative(mean_a, mean_b, tol)) ++r.within;
      }
      if (std::fabs(rel) > worst_abs) {
        worst_abs = std::fabs(rel);
        r.worst_x = x0, r.worst_y = y0, r.worst_rel = rel;
      }
    }
  }
  r.share = r.eligible > 0 ? double(r.within) / double(r.eligible) : 1.0;
  return r;
}

ImageDiff CompareImages(const Image& a_in, const Image& b, const ImageDiffOptions& options) {
  PTLAB_CHECK(SameSize(a_in, b));
  Image flipped;
  if (options.flip_x) flipped = FlipX(a_in);
  const Image& a = options.flip_x ? flipped : a_in;

  ImageDiff d;
  d.width = a.width;
  d.height = a.height;
  d.flip_x = options.flip_x;
  std::array<double, 3> sum_abs{}, sum_sq{}, sum_rel{};
  double max_b = -kInf;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      const size_t i = (size_t(y) * size_t(a.width) + size_t(x)) * 3;
      const float* pa = &a.rgb[i];
      const float* pb = &b.rgb[i];
      if (!PixelFinite(pa) || !PixelFinite(pb)) continue;
      ++d.compared_pixels;
      for (int c = 0; c < 3; ++c) {
        const double va = pa[c], vb = pb[c], diff = va - vb, abs_diff = std::fabs(diff);
        sum_abs[c] += abs_diff;
        sum_sq[c] += diff * diff;
        sum_rel[c] += diff * diff / (vb * vb + kRelMseEpsilon);
        max_b = std::max(max_b, vb);
        if (abs_diff > d.max_abs_error || d.max_abs_x < 0) {
          d.max_abs_error = abs_diff;
          d.max_abs_x = x, d.max_abs_y = y, d.max_abs_channel = c;
        }
      }
    }
  }
  const double n = double(d.compared_pixels);
  for (int c = 0; c < 3; ++c) {
    d.mae[c] = n > 0 ? sum_abs[c] / n : kNaN;
    d.mse[c] = n > 0 ? sum_sq[c] / n : kNaN;
    d.rmse[c] = std::sqrt(d.mse[c]);
    d.rel_mse[c] = n > 0 ? sum_rel[c] / n : kNaN;
  }
  auto all = [&](const std::array<double, 3>& s) {
    return n > 0 ? (s[0] + s[1] + s[2]) / (3 * n) : kNaN;
  };
  d.mae_all = all(sum_abs);
  d.mse_all = all(sum_sq);
  d.rmse_all = std::sqrt(d.mse_all);
  d.rel_mse_all = all(sum_rel);
  if (n == 0) d.max_abs_error = kNaN;
  d.psnr_peak = options.psnr_peak > 0 ? options.psnr_peak : (n > 0 ? max_b : kNaN);
  d.psnr_db = d.mse_all == 0 ? kInf : 10 * std::log10(d.psnr_peak * d.psnr_peak / d.mse_all);

  d.nonfinite_a = CountNonFinite(a);
  d.nonfinite_b = CountNonFinite(b);
  d.mean_a = ChannelMeans(a);
  d.mean_b = ChannelMeans(b);
  for (int c = 0; c < 3; ++c) {
    d.mean_rel_diff[c] = RelDiff(d.mean_a[c], d.mean_b[c]);
    d.max_abs_mean_rel = std::max(d.max_abs_mean_rel, std::fabs(d.mean_rel_diff[c]));
  }
  d.blocks = CompareBlocks(a, b, options.block_size, options.block_tol, options.block_min);
  return d;
}

ParityResult CheckParity(const Image& render_in, const Image& reference, double min_block_share,
                         bool flip_x) {
  ParityResult r;
  r.flip_x = flip_x;
  r.min_block_share = min_block_share;
  const std::string tag = Format("P(%g)", min_block_share) + (flip_x ? " flip-x" : "");
  r.size_ok = SameSize(render_in, reference);
  if (!r.size_ok) {
    r.summary = "FAIL " + tag + ": size " + std::to_string(render_in.width) + "x" +
                std::to_string(render_in.height) + " vs reference " +
                std::to_string(reference.width) + "x" + std::to_string(reference.height);
    return r;
  }
  Image flipped;
  if (flip_x) flipped = FlipX(render_in);
  const Image& render = flip_x ? flipped : render_in;

  r.mean_render = ChannelMeans(render);
  r.mean_reference = ChannelMeans(reference);
  r.means_ok = true;
  for (int c = 0; c < 3; ++c) {
    r.mean_rel_diff[c] = RelDiff(r.mean_render[c], r.mean_reference[c]);
    r.means_ok = r.means_ok && WithinRelative(r.mean_render[c], r.mean_reference[c], r.mean_tol);
  }
  r.nonfinite_render = CountNonFinite(render);
  r.finite_ok = r.nonfinite_render.total() == 0;
  r.blocks = CompareBlocks(render, reference, 32, 0.05, 0.01);
  r.blocks_ok = r.blocks.share >= min_block_share;
  r.pass = r.means_ok && r.finite_ok && r.blocks_ok;

  r.summary = std::string(r.pass ? "PASS " : "FAIL ") + tag + ": means " +
              Percent(r.mean_rel_diff[0]) + " " + Percent(r.mean_rel_diff[1]) + " " +
              Percent(r.mean_rel_diff[2]) + (r.means_ok ? " (ok, <1%)" : " (FAIL, >=1%)") + "; " +
              std::to_string(r.nonfinite_render.nan_pixels) + " NaN + " +
              std::to_string(r.nonfinite_render.inf_pixels) + " Inf pixels" +
              (r.finite_ok ? " (ok)" : " (FAIL)") + "; " + BlockLine(r.blocks) +
              (r.blocks_ok ? " (ok, >= " : " (FAIL, < ") + Format("%.2f%%)", 100 * min_block_share);
  return r;
}

Image RelativeErrorHeatmap(const Image& a, const Image& b, double scale) {
  PTLAB_CHECK(SameSize(a, b) && scale > 0);
  Image out(a.width, a.height);
  for (size_t i = 0; i + 2 < a.rgb.size(); i += 3) {
    const float* pa = &a.rgb[i];
    const float* pb = &b.rgb[i];
    float* po = &out.rgb[i];
    if (!PixelFinite(pa) || !PixelFinite(pb)) {
      po[0] = 0.0f, po[1] = 1.0f, po[2] = 0.0f;
      continue;
    }
    const double ma = (double(pa[0]) + pa[1] + pa[2]) / 3, mb = (double(pb[0]) + pb[1] + pb[2]) / 3;
    const double e = std::clamp((ma - mb) / std::sqrt(mb * mb + kRelMseEpsilon) / scale, -1.0, 1.0);
    const float fade = SrgbToLinear(float(1 - std::fabs(e)));  // display value of the other two
    if (e < 0) {
      po[0] = fade, po[1] = fade, po[2] = 1.0f;
    } else {
      po[0] = 1.0f, po[1] = fade, po[2] = fade;
    }
  }
  return out;
}

std::vector<std::string> CheckThresholds(const ImageDiff& d, const DiffThresholds& t) {
  std::vector<std::string> fails;
  if (!t.any()) return fails;
  if (d.nonfinite_a.total() > 0) {
    fails.push_back("A has " + std::to_string(d.nonfinite_a.nan_pixels) + " NaN and " +
                    std::to_string(d.nonfinite_a.inf_pixels) + " Inf pixels");
  }
  // Written as !(value <= limit) so that an undefined (NaN) metric fails too.
  if (t.rmse && !(d.rmse_all <= *t.rmse)) {
    fails.push_back(Format("RMSE %g", d.rmse_all) + Format(" > %g", *t.rmse));
  }
  if (t.rel_mse && !(d.rel_mse_all <= *t.rel_mse)) {
    fails.push_back(Format("relMSE %g", d.rel_mse_all) + Format(" > %g", *t.rel_mse));
  }
  if (t.mean_rel && !(d.max_abs_mean_rel <= *t.mean_rel)) {
    fails.push_back(Format("max |mean rel diff| %g", d.max_abs_mean_rel) +
                    Format(" > %g", *t.mean_rel));
  }
  if (t.block_share && !(d.blocks.share >= *t.block_share)) {
    fails.push_back(Format("block share %g", d.blocks.share) + Format(" < %g", *t.block_share));
  }
  return fails;
}

std::string FormatDiffTable(const ImageDiff& d, const ParityResult* parity) {
  std::string s;
  char buf[256];
  std::snprintf(buf, sizeof(buf), "size %dx%d, %lld pixels compared (finite in both)%s\n", d.width,
                d.height, static_cast<long long>(d.compared_pixels),
                d.flip_x ? ", A mirrored left-right (--flip-x)" : "");
  s += buf;
  s += "                        R              G              B            all\n";
  auto row = [&](const char* name, const std::array<double, 3>& v, double all) {
    std::snprintf(buf, sizeof(buf), "%-14s %14.6g %14.6g %14.6g", name, v[0], v[1], v[2]);
    s += buf;
    if (!std::isnan(all)) {
      std::snprintf(buf, sizeof(buf), " %14.6g", all);
      s += buf;
    }
    s += "\n";
  };
  row("mean A", d.mean_a, kNaN);
  row("mean B", d.mean_b, kNaN);
  row("mean rel diff", d.mean_rel_diff, kNaN);
  row("MAE", d.mae, d.mae_all);
  row("MSE", d.mse, d.mse_all);
  row("RMSE", d.rmse, d.rmse_all);
  row("relMSE", d.rel_mse, d.rel_mse_all);
  static const char* kChannel[] = {"R", "G", "B"};
  std::snprintf(buf, sizeof(buf), "max abs error  %.6g at (x=%d, y=%d) channel %s\n",
                d.max_abs_error, d.max_abs_x, d.max_abs_y,
                d.max_abs_channel >= 0 ? kChannel[d.max_abs_channel] : "-");
  s += buf;
  std::snprintf(buf, sizeof(buf), "PSNR           %.3f dB (peak %.6g)\n", d.psnr_db, d.psnr_peak);
  s += buf;
  std::snprintf(buf, sizeof(buf), "NaN/Inf pixels A: %lld/%lld   B: %lld/%lld\n",
                static_cast<long long>(d.nonfinite_a.nan_pixels),
                static_cast<long long>(d.nonfinite_a.inf_pixels),
                static_cast<long long>(d.nonfinite_b.nan_pixels),
                static_cast<long long>(d.nonfinite_b.inf_pixels));
  s += buf;
  const BlockComparison& b = d.blocks;
  std::snprintf(buf, sizeof(buf),
                "blocks %dx%d (%dx%d, partial edge blocks included), B mean >= %g: %s;"
                " worst %+.2f%% at (%d, %d)\n",
                b.block_size, b.block_size, b.blocks_x, b.blocks_y, b.min_mean,
                BlockLine(b).c_str(), 100 * b.worst_rel, b.worst_x, b.worst_y);
  s += buf;
  if (parity) s += "parity " + parity->summary + "\n";
  return s;
}

std::string FormatDiffJson(const std::string& path_a, const std::string& path_b, const ImageDiff& d,
                           const ParityResult* parity, const std::vector<std::string>& failures) {
  Json j;
  j["a"] = path_a;
  j["b"] = path_b;
  j["width"] = d.width;
  j["height"] = d.height;
  j["flip_x"] = d.flip_x;
  j["compared_pixels"] = d.compared_pixels;
  j["mean_a"] = JsonArray(d.mean_a);
  j["mean_b"] = JsonArray(d.mean_b);
  j["mean_rel_diff"] = JsonArray(d.mean_rel_diff);
  j["max_abs_mean_rel"] = JsonNumberOrNull(d.max_abs_mean_rel);
  j["mae"] = JsonArray(d.mae);
  j["mae_all"] = JsonNumberOrNull(d.mae_all);
  j["mse"] = JsonArray(d.mse);
  j["mse_all"] = JsonNumberOrNull(d.mse_all);
  j["rmse"] = JsonArray(d.rmse);
  j["rmse_all"] = JsonNumberOrNull(d.rmse_all);
  j["rel_mse"] = JsonArray(d.rel_mse);
  j["rel_mse_all"] = JsonNumberOrNull(d.rel_mse_all);
  j["rel_mse_epsilon"] = JsonNumberOrNull(kRelMseEpsilon);
  j["psnr_db"] = JsonNumberOrNull(d.psnr_db);
  j["psnr_peak"] = JsonNumberOrNull(d.psnr_peak);
  Json max_abs;
  max_abs["value"] = JsonNumberOrNull(d.max_abs_error);
  max_abs["x"] = d.max_abs_x;
  max_abs["y"] = d.max_abs_y;
  max_abs["channel"] = d.max_abs_channel;
  j["max_abs_error"] = max_abs;
  j["nonfinite_a"] = JsonNonFinite(d.nonfinite_a);
  j["nonfinite_b"] = JsonNonFinite(d.nonfinite_b);
  j["blocks"] = JsonBlocks(d.blocks);
  if (parity) {
    const ParityResult& p = *parity;
    Json q;
    q["pass"] = p.pass;
    q["size_ok"] = p.size_ok;
    q["flip_x"] = p.flip_x;
    q["means_ok"] = p.means_ok;
    q["mean_tol"] = JsonNumberOrNull(p.mean_tol);
    q["mean_render"] = JsonArray(p.mean_render);
    q["mean_reference"] = JsonArray(p.mean_reference);
    q["mean_rel_diff"] = JsonArray(p.mean_rel_diff);
    q["finite_ok"] = p.finite_ok;
    q["nonfinite_render"] = JsonNonFinite(p.nonfinite_render);
    q["blocks_ok"] = p.blocks_ok;
    q["min_block_share"] = JsonNumberOrNull(p.min_block_share);
    q["blocks"] = JsonBlocks(p.blocks);
    q["summary"] = p.summary;
    j["parity"] = q;
  } else {
    j["parity"] = nullptr;
  }
  j["failures"] = failures;
  j["pass"] = failures.empty();
  return DumpJsonLine(j);
}

}  // namespace ptlab
