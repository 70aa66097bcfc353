// Chi-square tests of the infinite lights' samplers, and a pixel-level test on a real 1k map.
#include "tools/chi2/light_subjects.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/core/rng.h"
#include "engine/image/image_io.h"
#include "engine/light/environment_map.h"
#include "tests/test_data.h"
#include "tools/chi2/chi2.h"
#include "tools/chi2/report.h"
#include "tools/chi2/stats_math.h"

namespace ptlab {
namespace {

std::string VenicePath() { return test_data::Path("envmaps/venice_sunset_1k.exr"); }

const Chi2Registry& Registry() {
  static const Chi2Registry registry = [] {
    Chi2Registry r;
    RegisterLightSubjects(&r, test_data::Path(""));
    return r;
  }();
  return registry;
}

// The light subjects themselves run with every other subject in subjects_test.cpp
// (DefaultChi2Registry registers them); here: the registry and a full-resolution check.

TEST(StatLightChi2Registry, HoldsTheSyntheticAndRealMaps) {
  for (const char* name :
       {"envmap/importance_gradient", "envmap/importance_hot_pixel", "envmap/importance_1x1",
        "envmap/importance_pole_rows", "envmap/uniform_gradient", "distantdisk/full_sphere",
        "envmap/importance_at_poles_gradient", "envmap/importance_at_poles_hot_pixel",
        "envmap/importance_at_poles_pole_rows",
        "distantdisk/cone_10deg_rotated", "distribution/1d", "distribution/2d"})
    EXPECT_NE(Registry().Find(name), nullptr) << name;
  EXPECT_EQ(Registry().Find("envmap/importance_venice_32x16") != nullptr,
            std::filesystem::exists(VenicePath()));
  // Every importance map also drawn by the SIMD batch, and its broken variant.
  for (const char* name :
       {"simd/env_importance_gradient", "simd/env_importance_hot_pixel", "simd/env_importance_1x1",
        "simd/env_importance_pole_rows", "simd/env_importance_rotated_gradient",
        "simd/env_importance_at_poles_gradient", "simd/env_importance_at_poles_hot_pixel",
        "simd/env_importance_at_poles_pole_rows"}) {
    const Chi2Subject* s = Registry().Find(name);
    ASSERT_NE(s, nullptr) << name;
    EXPECT_TRUE(bool(s->sample_batch)) << name;
  }
  EXPECT_EQ(Registry().Find("simd/env_importance_venice_32x16") != nullptr,
            std::filesystem::exists(VenicePath()));
  EXPECT_NE(Registry().Find("broken/simd_env_pdf_half_pixel_shift"), nullptr);
  // Every distant disk also drawn by the SIMD batch.
  for (const char* name : {"simd/distant_disk_cone_10deg_rotated", "simd/distant_disk_cone_90deg",
                           "simd/distant_disk_full_sphere"}) {
    const Chi2Subject* s = Registry().Find(name);
    ASSERT_NE(s, nullptr) << name;
    EXPECT_TRUE(bool(s->sample_batch)) << name;
  }
  for (const Chi2Subject& s : Registry().subjects())
    EXPECT_EQ(s.name.rfind("broken/", 0) == 0, s.expect == Chi2Expect::kFail) << s.name;
}

// The full-resolution 1024x512 map, where cell integration would be too slow for the lab: each
// sample is mapped back to its pixel with an independent lat-long formula, and the counts per
// 32x32-pixel block are compared (Pearson) with probabilities computed here from the pixels
// (bilinear cell-mean luminance × sinθ).
TEST(StatEnvironmentMapPixels, VeniceSunsetMatchesLuminanceTimesSinTheta) {
  PTLAB_REQUIRE_DATA(VenicePath());
  const StatusOr<Image> image = ReadImage(VenicePath());
  ASSERT_TRUE(image.ok()) << image.status().message();
  EnvironmentMapTable table;
  ASSERT_TRUE(AddEnvironmentMap(*image, {}, VenicePath(), &table).ok());
  const int w = image->width, h = image->height;
  constexpr int kBlock = 32;
  const int bw = w / kBlock, bh = h / kBlock;
  ASSERT_EQ(w % kBlock, 0);
  ASSERT_EQ(h % kBlock, 0);

  std::vector<double> lum(size_t(w) * h), expected(size_t(bw) * bh, 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Color3f c = image->At(x, y);
      lum[size_t(y) * w + x] = 0.212671 * c.r + 0.715160 * c.g + 0.072169 * c.b;
    }
  const double k[3] = {0.125, 0.75, 0.125};
  double total = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double mean = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          mean += k[dy + 1] * k[dx + 1] *
                  lum[size_t(std::clamp(y + dy, 0, h - 1)) * w + size_t((x + dx + w) % w)];
      const double p = mean * std::sin(M_PI * (y + 0.5) / h);
      expected[size_t(y / kBlock) * bw + size_t(x / kBlock)] += p;
      total += p;
    }
  constexpr int kSamples = 1000000;
  std::vector<double> observed(expected.size(), 0.0);
  Pcg32 rng(2024, 5);
  int pdf_mismatches = 0;
  for (int i = 0; i < kSamples; ++i) {
    EnvironmentSample s;
    ASSERT_TRUE(SampleEnvironment(table, 0, {rng.NextFloat(), rng.NextFloat()}, &s));
    ASSERT_TRUE(std::isfinite(s.pdf) && s.pdf > 0);
    const double phi = std::atan2(double(s.wi.x), -double(s.wi.z));
    const double u = (phi < 0 ? phi + 2 * M_PI : phi) / (2 * M_PI);
    const double v = std::acos(std::clamp(double(s.wi.y), -1.0, 1.0)) / M_PI;
    const int x = std::min(int(u * w), w - 1), y = std::min(int(v * h), h - 1);
    observed[size_t(y / kBlock) * bw + size_t(x / kBlock)] += 1;
    const float pdf = EnvironmentPdf(table, 0, s.wi);
    if (!(std::fabs(pdf - s.pdf) <= 1e-3f * s.pdf)) ++pdf_mismatches;
  }
  for (double& e : expected) e *= kSamples / total;
  const PearsonResult pearson = PearsonChiSquare(observed, expected, 5.0);
  EXPECT_EQ(pearson.zero_expected_cells, 0);
  ASSERT_GE(pearson.dof, 100);
  const double p = ChiSquarePValue(pearson.chi2, pearson.dof);
  EXPECT_GE(p, 0.01) << "chi2 " << pearson.chi2 << " dof " << pearson.dof;
  // Pdf(wi) recomputes the pixel from wi: only samples within float rounding of a pixel edge may
  // land in the neighbour.
  EXPECT_LE(pdf_mismatches, kSamples / 1000);
}

}  // namespace
}  // namespace ptlab
