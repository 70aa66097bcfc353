// Environment map emitter: building the table row, bilinear lookup, sampling, pdf, debug image.
#include "engine/light/environment_map.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/image/image_io.h"
#include "engine/image/srgb.h"
#include "engine/sampling/warp.h"
#include "engine/scene/scene_limits.h"

namespace ptlab {
namespace {

const char* ChannelName(int c) { return c == 0 ? "R" : (c == 1 ? "G" : "B"); }

std::string FormatValue(float v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%g", double(v));
  return buffer;
}

// First offending pixel of the policy "finite and >= 0", and how many pixels offend.
Status CheckPixels(const Image& image, float scale, const std::string& name) {
  int64_t bad = 0, overflow = 0;
  int first_x = -1, first_y = -1, first_c = 0;
  float first_value = 0;
  int over_x = -1, over_y = -1;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const float* p = &image.rgb[(size_t(y) * size_t(image.width) + size_t(x)) * 3];
      bool pixel_bad = false, pixel_overflow = false;
      for (int c = 0; c < 3; ++c) {
        // !(v >= 0) catches NaN and negatives (not -0); isinf catches +Inf.
        if (!(p[c] >= 0.0f) || std::isinf(p[c])) {
          if (!pixel_bad && bad == 0) first_x = x, first_y = y, first_c = c, first_value = p[c];
          pixel_bad = true;
        } else if (!(p[c] * scale <= kMaxRadiance)) {
          pixel_overflow = true;
        }
      }
      bad += pixel_bad;
      if (pixel_overflow && overflow++ == 0) over_x = x, over_y = y;
    }
  }
  if (bad > 0) {
    const char* what = std::isnan(first_value)   ? "NaN"
                       : std::isinf(first_value) ? "infinite"
                                                 : "negative";
    return Status::Error(name + ": environment map pixel (" + std::to_string(first_x) + ", " +
                         std::to_string(first_y) + ") has a " + what + " " + ChannelName(first_c) +
                         " value (" + FormatValue(first_value) + "); " + std::to_string(bad) +
                         " of " + std::to_string(int64_t(image.width) * image.height) +
                         " pixels are NaN, infinite or negative; expected finite values >= 0 "
                         "(such pixels are rejected, not clamped)");
  }
  if (overflow > 0)
    return Status::Error(name + ": environment map pixel (" + std::to_string(over_x) + ", " +
                         std::to_string(over_y) + ") times scale " + FormatValue(scale) +
                         " exceeds the largest radiance ptlab accepts, " +
                         FormatValue(kMaxRadiance) + " (" + std::to_string(overflow) +
                         " pixels); expected smaller values or a smaller scale");
  return Status::Ok();
}

struct PixelView {
  const float* texels;
  int w, h;
  float v_scale, v_offset;  // EnvironmentRowCoordinate
  Color3f At(int x, int y) const {
    const float* t = texels + (size_t(y) * size_t(w) + size_t(x)) * kEnvironmentTexel;
    return {t[0], t[1], t[2]};
  }
};

PixelView Pixels(const EnvironmentMapTable& t, uint32_t row) {
  PixelView p{t.texels.data() + size_t(t.pixel_offset[row]) * kEnvironmentTexel, t.width[row],
              t.height[row], 0.0f, 0.0f};
  EnvironmentRowCoordinate(t, row, &p.v_scale, &p.v_offset);
  return p;
}

// Bilinear interpolation of the pixel points at (u, v): wraps in u, clamps in v.
Color3f Lookup(const PixelView& p, const Vec2f& uv) {
  const float x = uv.x * float(p.w) - 0.5f, y = uv.y * p.v_scale + p.v_offset;
  if (!(std::isfinite(x) && std::isfinite(y))) return {};
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  int x0 = int(fx) % p.w;
  if (x0 < 0) x0 += p.w;
  const int x1 = x0 + 1 == p.w ? 0 : x0 + 1;
  const int y0 = std::clamp(int(fy), 0, p.h - 1), y1 = std::clamp(int(fy) + 1, 0, p.h - 1);
  return (1 - ty) * ((1 - tx) * p.At(x0, y0) + tx * p.At(x1, y0)) +
         ty * ((1 - tx) * p.At(x0, y1) + tx * p.At(x1, y1));
}

// sinθ and cosθ at θ = πv, measured from the nearer pole so that both stay accurate near
// θ = π as well (1 - v is exact in float for v >= 1/2).
void SinCosTheta(float v, float* sin_theta, float* cos_theta) {
  const bool south = v > 0.5f;
  const float from_pole = kPi * (south ? 1.0f - v : v);
  *sin_theta = std::sin(from_pole);
  *cos_theta = south ? -std::cos(from_pole) : std::cos(from_pole);
}

}  // namespace

int EnvironmentCellRows(const EnvironmentMapTable& t, uint32_t row) {
  return t.rows[row] == EnvironmentRows::kAtPoles ? std::max(t.height[row] - 1, 1) : t.height[row];
}

void EnvironmentRowCoordinate(const EnvironmentMapTable& t, uint32_t row, float* scale,
                              float* offset) {
  const bool at_poles = t.rows[row] == EnvironmentRows::kAtPoles;
  *scale = float(at_poles ? t.height[row] - 1 : t.height[row]);
  *offset = at_poles ? 0.0f : -0.5f;
}

Vec2f EnvironmentDirectionToUv(const Vec3f& d) {
  float phi = std::atan2(d.x, -d.z);
  if (phi < 0) phi += 2 * kPi;
  const float theta = std::atan2(std::sqrt(d.x * d.x + d.z * d.z), d.y);
  return {std::clamp(phi * kInv2Pi, 0.0f, 1.0f), std::clamp(theta * kInvPi, 0.0f, 1.0f)};
}

Vec3f EnvironmentUvToDirection(const Vec2f& uv) {
  float sin_theta, cos_theta;
  SinCosTheta(uv.y, &sin_theta, &cos_theta);
  const float phi = 2 * kPi * uv.x;
  return {sin_theta * std::sin(phi), cos_theta, -sin_theta * std::cos(phi)};
}

StatusOr<uint32_t> AddEnvironmentMap(const Image& image, const EnvironmentMapDesc& desc,
                                     const std::string& name, EnvironmentMapTable* table) {
  if (image.width < 1 || image.height < 1 ||
      image.rgb.size() != size_t(image.width) * size_t(image.height) * 3)
    return Status::Error(name + ": the environment map is empty; expected at least 1x1 pixels");
  if (!(desc.scale >= 0.0f) || std::isinf(desc.scale))
    return Status::Error(name + ": environment map scale " + FormatValue(desc.scale) +
                         " is out of range; expected a finite value >= 0");
  PTLAB_RETURN_IF_ERROR(CheckPixels(image, desc.scale, name));

  EnvironmentMapTable& t = *table;
  const int w = image.width, h = image.height;
  const uint32_t row = uint32_t(t.size());
  const size_t offset = t.texels.size() / kEnvironmentTexel, count = size_t(w) * size_t(h);
  t.width.push_back(w);
  t.height.push_back(h);
  t.pixel_offset.push_back(uint32_t(offset));
  t.sampling.push_back(desc.sampling);
  t.rows.push_back(desc.rows);
  t.to_world.push_back(desc.to_world);
  t.texels.resize((offset + count) * kEnvironmentTexel, 0.0f);
  std::vector<double> luminance(count);
  for (size_t k = 0; k < count; ++k) {
    const Color3f c = {image.rgb[3 * k] * desc.scale, image.rgb[3 * k + 1] * desc.scale,
                       image.rgb[3 * k + 2] * desc.scale};
    float* texel = &t.texels[(offset + k) * kEnvironmentTexel];
    texel[0] = c.r, texel[1] = c.g, texel[2] = c.b;
    luminance[k] = Luminance(c);
  }

  // Cell weight: the mean of the bilinear luminance over the cell, × sinθ at the cell centre.
  // In 1-D the mean of the interpolant over [i, i+1] (centres at i + 1/2) is
  // f[i-1]/8 + 3 f[i]/4 + f[i+1]/8, with the same wrap (u) and clamp (v) as Lookup; over the
  // band between two pixel rows j and j + 1 (kAtPoles) it is (f[j] + f[j+1])/2.
  static constexpr double kStencil[3] = {0.125, 0.75, 0.125};
  static constexpr double kBand[3] = {0.0, 0.5, 0.5};
  const bool at_poles = desc.rows == EnvironmentRows::kAtPoles;
  const double* v_stencil = at_poles ? kBand : kStencil;
  const int nv = EnvironmentCellRows(t, row);
  std::vector<double> weights(size_t(nv) * size_t(w));
  double integral = 0;
  for (int j = 0; j < nv; ++j) {
    const double sin_theta = std::sin(3.14159265358979323846 * (j + 0.5) / nv);
    for (int i = 0; i < w; ++i) {
      double mean = 0;
      for (int dj = -1; dj <= 1; ++dj) {
        const int y = std::clamp(j + dj, 0, h - 1);
        for (int di = -1; di <= 1; ++di) {
          const int x = (i + di + w) % w;
          mean +=
              v_stencil[dj + 1] * kStencil[di + 1] * luminance[size_t(y) * size_t(w) + size_t(x)];
        }
      }
      weights[size_t(j) * size_t(w) + size_t(i)] = mean * sin_theta;
      integral += mean * sin_theta;
    }
  }
  // Σ weight × (2π/W)(π/nv) ≈ ∫ luminance dω.
  t.luminance_integral.push_back(float(integral * 2 * 9.8696044010893586 / (double(w) * nv)));

  t.marginal_offset.push_back(uint32_t(t.marginal_cdf.size()));
  t.conditional_offset.push_back(uint32_t(t.conditional_cdf.size()));
  if (desc.sampling == EnvironmentSampling::kImportance) {
    const size_t m = t.marginal_cdf.size(), c = t.conditional_cdf.size();
    t.marginal_cdf.resize(m + size_t(nv) + 1);
    t.conditional_cdf.resize(c + size_t(nv) * (size_t(w) + 1));
    BuildDistribution2D(weights.data(), w, nv, t.marginal_cdf.data() + m,
                        t.conditional_cdf.data() + c);
    t.marginal_guide.resize(t.marginal_cdf.size());
    t.conditional_guide.resize(t.conditional_cdf.size());
    BuildDistribution2DGuides(EnvironmentDistribution(t, row), t.marginal_guide.data() + m,
                              t.conditional_guide.data() + c);
  }
  return row;
}

Distribution2DView EnvironmentDistribution(const EnvironmentMapTable& t, uint32_t row) {
  Distribution2DView view{t.marginal_cdf.data() + t.marginal_offset[row],
                          t.conditional_cdf.data() + t.conditional_offset[row], t.width[row],
                          EnvironmentCellRows(t, row)};
  if (t.marginal_guide.size() == t.marginal_cdf.size() &&
      t.conditional_guide.size() == t.conditional_cdf.size() && !t.marginal_guide.empty()) {
    view.marginal_guide = t.marginal_guide.data() + t.marginal_offset[row];
    view.conditional_guide = t.conditional_guide.data() + t.conditional_offset[row];
  }
  return view;
}

Color3f EnvironmentRadiance(const EnvironmentMapTable& t, uint32_t row, const Vec3f& w_world) {
  return Lookup(Pixels(t, row), EnvironmentDirectionToUv(t.to_world[row].ToLocal(w_world)));
}

bool SampleEnvironment(const EnvironmentMapTable& t, uint32_t row, const Vec2f& u,
                       EnvironmentSample* out) {
  if (t.sampling[row] == EnvironmentSampling::kUniform) {
    if (!(t.luminance_integral[row] > 0)) return false;
    const Vec3f wi = SampleUniformSphere(u);
    *out = {wi, EnvironmentRadiance(t, row, wi), kInv4Pi};
    return true;
  }
  Vec2f uv;
  float pdf_uv;
  if (!SampleDistribution2D(EnvironmentDistribution(t, row), u, &uv, &pdf_uv)) return false;
  // v = 0 exactly (u.y = 0) is the pole, where the density is infinite; moving that single
  // point (measure zero, still in row 0) off the pole keeps every returned pdf finite.
  uv.y = std::max(uv.y, 0x1p-24f);
  float sin_theta, cos_theta;
  SinCosTheta(uv.y, &sin_theta, &cos_theta);
  const float phi = 2 * kPi * uv.x;
  const Vec3f d{sin_theta * std::sin(phi), cos_theta, -sin_theta * std::cos(phi)};
  *out = {t.to_world[row].ToWorld(d), Lookup(Pixels(t, row), uv),
          pdf_uv / (kEnvironmentTwoPiSquared * sin_theta)};
  return true;
}

namespace {

// EnvironmentPdf at local direction d; *uv is d's (u, v) when the caller has it already, else
// null (computed here only where it is needed).
float PdfAtLocal(const EnvironmentMapTable& t, uint32_t row, const Vec3f& d, const Vec2f* uv) {
  if (t.sampling[row] == EnvironmentSampling::kUniform)
    return t.luminance_integral[row] > 0 ? kInv4Pi : 0.0f;
  const float r = std::sqrt(d.x * d.x + d.z * d.z);
  if (!(r > 0)) return 0.0f;
  const float sin_theta = r / std::sqrt(r * r + d.y * d.y);
  const float pdf_uv =
      Distribution2DPdf(EnvironmentDistribution(t, row), uv ? *uv : EnvironmentDirectionToUv(d));
  return pdf_uv / (kEnvironmentTwoPiSquared * sin_theta);
}

}  // namespace

float EnvironmentPdf(const EnvironmentMapTable& t, uint32_t row, const Vec3f& w_world) {
  return PdfAtLocal(t, row, t.to_world[row].ToLocal(w_world), nullptr);
}

float EnvironmentRadianceAndPdf(const EnvironmentMapTable& t, uint32_t row, const Vec3f& w_world,
                                Color3f* radiance) {
  // EnvironmentRadiance's and EnvironmentPdf's operations, (u, v) computed once for both.
  const Vec3f d = t.to_world[row].ToLocal(w_world);
  const Vec2f uv = EnvironmentDirectionToUv(d);
  *radiance = Lookup(Pixels(t, row), uv);
  return PdfAtLocal(t, row, d, &uv);
}

Image EnvironmentPdfDebugImage(const EnvironmentMapTable& t, uint32_t row) {
  PTLAB_CHECK(t.sampling[row] == EnvironmentSampling::kImportance);
  const Distribution2DView d = EnvironmentDistribution(t, row);
  Image image(d.nu, d.nv);
  float max_p = 0;
  for (int j = 0; j < d.nv; ++j)
    for (int i = 0; i < d.nu; ++i)
      max_p = std::max(
          max_p, (d.marginal_cdf[j + 1] - d.marginal_cdf[j]) * (d.Row(j)[i + 1] - d.Row(j)[i]));
  for (int j = 0; j < d.nv; ++j) {
    for (int i = 0; i < d.nu; ++i) {
      const float p = (d.marginal_cdf[j + 1] - d.marginal_cdf[j]) * (d.Row(j)[i + 1] - d.Row(j)[i]);
      image.Set(i, j, {d.marginal_cdf[j + 1], d.Row(j)[i + 1], max_p > 0 ? p / max_p : 0.0f});
    }
  }
  return image;
}

StatusOr<Image> EnvironmentPdfImage(const std::string& map_path, bool for_png) {
  StatusOr<Image> map = ReadImage(map_path);
  if (!map.ok()) return map.status();
  EnvironmentMapTable table;
  StatusOr<uint32_t> row = AddEnvironmentMap(*map, EnvironmentMapDesc{}, map_path, &table);
  if (!row.ok()) return row.status();
  Image image = EnvironmentPdfDebugImage(table, *row);
  // WritePng applies the sRGB curve; pre-apply its inverse so the bytes are round(255 · value).
  if (for_png)
    for (float& v : image.rgb) v = SrgbToLinear(v);
  return image;
}

}  // namespace ptlab
