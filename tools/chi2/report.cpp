// Chi-square lab reports: heat-map image (three panels) and CSV table of a test's cells.
#include "tools/chi2/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "engine/image/image_io.h"
#include "engine/image/srgb.h"

namespace ptlab {
namespace {

constexpr int kMargin = 6;
constexpr int kTargetPanelWidth = 360;
// Pearson residual (o - e) / sqrt(e) drawn at full colour: noise of a passing test stays pale.
constexpr double kFullResidual = 4.0;

Color3f FromSrgb8(int r, int g, int b) {
  return SrgbToLinear(Color3f{r / 255.0f, g / 255.0f, b / 255.0f});
}

Color3f Lerp(const Color3f& a, const Color3f& b, float t) { return a * (1 - t) + b * t; }

// Viridis (van der Walt & Smith, matplotlib), 9 stops, t in [0, 1].
Color3f Viridis(double t) {
  static const int kStops[9][3] = {{68, 1, 84},    {72, 40, 120},  {62, 74, 137},
                                   {49, 104, 142}, {38, 130, 142}, {31, 158, 137},
                                   {53, 183, 121}, {109, 205, 89}, {253, 231, 37}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 8.0;
  const int i = std::min(int(t), 7);
  const float f = float(t - i);
  const Color3f a = FromSrgb8(kStops[i][0], kStops[i][1], kStops[i][2]);
  const Color3f b = FromSrgb8(kStops[i + 1][0], kStops[i + 1][1], kStops[i + 1][2]);
  return Lerp(a, b, f);
}

// Blue - white - red for t in [-1, 1] (Moreland's cool-warm end points).
Color3f Diverging(double t) {
  t = std::clamp(std::isfinite(t) ? t : 0.0, -1.0, 1.0);
  const Color3f white = FromSrgb8(247, 247, 247);
  return t < 0 ? Lerp(white, FromSrgb8(59, 76, 192), float(-t))
               : Lerp(white, FromSrgb8(180, 4, 38), float(t));
}

}  // namespace

Image Chi2Heatmaps(const Chi2Result& r) {
  const int s = std::max(2, kTargetPanelWidth / std::max(1, r.xres));
  const int pw = r.xres * s, ph = r.yres * s;
  Image img(3 * pw + 4 * kMargin, ph + 2 * kMargin);
  const Color3f background = FromSrgb8(40, 40, 40);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) img.Set(x, y, background);
  double max_count = 0;
  for (size_t c = 0; c < r.observed.size(); ++c)
    max_count = std::max({max_count, r.observed[c], r.expected[c]});
  const double count_scale = max_count > 0 ? 1.0 / max_count : 0.0;
  for (int iy = 0; iy < r.yres; ++iy) {
    for (int ix = 0; ix < r.xres; ++ix) {
      const size_t c = size_t(iy) * size_t(r.xres) + size_t(ix);
      const double o = r.observed[c], e = r.expected[c];
      const Color3f colors[3] = {Viridis(o * count_scale), Viridis(e * count_scale),
                                 e > 0 ? Diverging((o - e) / (kFullResidual * std::sqrt(e)))
                                       : (o > 0 ? FromSrgb8(255, 0, 255) : Diverging(0))};
      const int py = kMargin + (r.yres - 1 - iy) * s;  // row 0 is the top: flip y
      for (int panel = 0; panel < 3; ++panel) {
        const int px = kMargin + panel * (pw + kMargin) + ix * s;
        for (int dy = 0; dy < s; ++dy)
          for (int dx = 0; dx < s; ++dx) img.Set(px + dx, py + dy, colors[panel]);
      }
    }
  }
  return img;
}

std::string Chi2FileStem(const std::string& name) {
  std::string stem = name;
  for (char& c : stem) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '.' || c == '_' || c == '-';
    if (!keep) c = '_';
  }
  return stem.empty() ? "_" : stem;
}

Status WriteChi2Report(const std::string& dir, const Chi2Result& r) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return Status::Error(dir + ": cannot create the image directory: " + ec.message());
  const std::string stem = (std::filesystem::path(dir) / Chi2FileStem(r.name)).string();
  PTLAB_RETURN_IF_ERROR(WritePng(stem + ".png", Chi2Heatmaps(r)));
  std::string csv = "ix,iy,x0,x1,y0,y1,observed,expected\n";
  const Chi2Domain& d = r.domain;
  char line[256];
  for (int iy = 0; iy < r.yres; ++iy) {
    for (int ix = 0; ix < r.xres; ++ix) {
      const size_t c = size_t(iy) * size_t(r.xres) + size_t(ix);
      std::snprintf(line, sizeof(line), "%d,%d,%.9g,%.9g,%.9g,%.9g,%.0f,%.6f\n", ix, iy,
                    d.x0 + (d.x1 - d.x0) * ix / r.xres, d.x0 + (d.x1 - d.x0) * (ix + 1) / r.xres,
                    d.y0 + (d.y1 - d.y0) * iy / r.yres, d.y0 + (d.y1 - d.y0) * (iy + 1) / r.yres,
                    r.observed[c], r.expected[c]);
      csv += line;
    }
  }
  return WriteFileAtomically(stem + ".csv", csv);
}

}  // namespace ptlab
