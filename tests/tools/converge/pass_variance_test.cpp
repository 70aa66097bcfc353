// Tests of PassVariance: the batch-means estimator by hand, and against a known variance.
#include "tools/converge/pass_variance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/core/rng.h"
#include "tools/imgdiff/ztest.h"

namespace ptlab {
namespace {

// Adds `rgb` with weight w to pixel (x, y) of the block.
void Put(FilmBlock* b, int x, int y, Color3f rgb, float w) {
  float* s = b->PixelSums(x, y);
  s[0] += w * rgb.r, s[1] += w * rgb.g, s[2] += w * rgb.b, s[3] += w;
}

Color3f XyzToRgbColor(double x, double y, double z) {
  return Color3f{float(kXyzToRgb[0][0] * x + kXyzToRgb[0][1] * y + kXyzToRgb[0][2] * z),
                 float(kXyzToRgb[1][0] * x + kXyzToRgb[1][1] * y + kXyzToRgb[1][2] * z),
                 float(kXyzToRgb[2][0] * x + kXyzToRgb[2][1] * y + kXyzToRgb[2][2] * z)};
}

TEST(PassVariance, MatchesTheFormulaByHand) {
  // One pixel, three passes with weights 16, 16 and 4 (a short last pass), XYZ values
  // X = 1, 2, 4 (Y = 2 X, Z = 0.5): m = (16 + 32 + 16) / 36 = 16/9,
  // s² = (16 (1 - 16/9)² + 16 (2 - 16/9)² + 4 (4 - 16/9)²) / 2, per-sample = spp s² / 36.
  PassVariance pv(1, 1);
  const double xs[3] = {1, 2, 4};
  const float ws[3] = {16, 16, 4};
  for (int k = 0; k < 3; ++k) {
    std::vector<FilmBlock> blocks(1, FilmBlock(0, 0, 1, 1));
    Put(&blocks[0], 0, 0, XyzToRgbColor(xs[k], 2 * xs[k], 0.5), ws[k]);
    pv.AddPass(blocks);
  }
  EXPECT_EQ(pv.passes(), 3u);
  const double m = 16.0 / 9.0;
  const double s2 = (16 * (1 - m) * (1 - m) + 16 * (2 - m) * (2 - m) + 4 * (4 - m) * (4 - m)) / 2;
  const Image var = RgbToXyz(pv.PerSampleVariance(36));
  EXPECT_NEAR(var.rgb[0], s2, 1e-4 * s2);
  EXPECT_NEAR(var.rgb[1], 4 * s2, 4e-4 * s2);
  EXPECT_NEAR(var.rgb[2], 0.0, 1e-4 * s2);
  // spp scales it: the variance of the pixel, s² / 36, times spp.
  EXPECT_NEAR(RgbToXyz(pv.PerSampleVariance(72)).rgb[0], 2 * s2, 2e-4 * s2);
}

// Passes of 16 samples, or fewer so that there are at least 32 (31 degrees of freedom) where
// the render has 32 samples or more; a single pass only at 1 spp.
TEST(PassVariance, PassSamplesMakeAtLeast32Passes) {
  EXPECT_EQ(PassVariance::PassSamples(868), 16u);  // Mitsuba's budget for 48 x 48: 55 passes
  EXPECT_EQ(PassVariance::PassSamples(512), 16u);
  EXPECT_EQ(PassVariance::PassSamples(511), 15u);
  EXPECT_EQ(PassVariance::PassSamples(61), 1u);
  EXPECT_EQ(PassVariance::PassSamples(64), 2u);
  EXPECT_EQ(PassVariance::PassSamples(8), 1u);
  EXPECT_EQ(PassVariance::PassSamples(1), 1u);
  EXPECT_EQ(PassVariance::PassSamples(0), 1u);
  for (uint32_t spp = 32; spp < 2000; ++spp)
    EXPECT_GE((spp + PassVariance::PassSamples(spp) - 1) / PassVariance::PassSamples(spp), 32u)
        << spp;
}

TEST(PassVariance, FewerThanTwoPassesGiveNaN) {
  PassVariance pv(2, 1);
  std::vector<FilmBlock> blocks(1, FilmBlock(0, 0, 2, 1));
  Put(&blocks[0], 0, 0, {1, 1, 1}, 16);
  pv.AddPass(blocks);
  pv.AddPass(blocks);  // pixel 1 never has weight
  const Image var = pv.PerSampleVariance(32);
  EXPECT_FALSE(std::isnan(var.rgb[0]));
  EXPECT_EQ(var.rgb[0], 0.0f);  // identical passes
  EXPECT_TRUE(std::isnan(var.rgb[3]));
  PassVariance one(1, 1);
  std::vector<FilmBlock> b1(1, FilmBlock(0, 0, 1, 1));
  Put(&b1[0], 0, 0, {1, 1, 1}, 16);
  one.AddPass(b1);
  EXPECT_TRUE(std::isnan(one.PerSampleVariance(16).rgb[0]));
}

// Known variance: 40 passes of 16 independent samples per pixel, each XYZ channel normal with
// standard deviations 0.3, 0.5, 0.2, spread over four tile blocks. Each pixel's estimate s² has
// 39 degrees of freedom (relative sd sqrt(2/39) = 0.23); their mean over 1024 pixels has relative
// sd 0.0071: it must be within 4 of those (2.8 %) of the truth, with a fixed seed.
TEST(PassVariance, RecoversAKnownPerSampleVariance) {
  const int w = 32, h = 32, passes = 40, spp_per_pass = 16;
  const double sigma[3] = {0.3, 0.5, 0.2}, mu[3] = {1.0, 1.2, 0.8};
  PassVariance pv(w, h);
  Pcg32 rng(11, 5);
  const auto normal = [&] {
    const double u1 = (double(rng.NextUint()) + 0.5) * 0x1p-32;
    const double u2 = double(rng.NextUint()) * 0x1p-32;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  };
  Image sum(w, h);  // the image: the mean of all samples, in RGB
  for (int k = 0; k < passes; ++k) {
    std::vector<FilmBlock> blocks = {FilmBlock(0, 0, 16, 16), FilmBlock(16, 0, 16, 16),
                                     FilmBlock(0, 16, 16, 16), FilmBlock(16, 16, 16, 16)};
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        FilmBlock& b = blocks[size_t((y / 16) * 2 + x / 16)];
        for (int s = 0; s < spp_per_pass; ++s) {
          const Color3f c = XyzToRgbColor(mu[0] + sigma[0] * normal(), mu[1] + sigma[1] * normal(),
                                          mu[2] + sigma[2] * normal());
          Put(&b, x, y, c, 1.0f);
          sum.Set(x, y, sum.At(x, y) + c * (1.0f / float(passes * spp_per_pass)));
        }
      }
    }
    pv.AddPass(blocks);
  }
  const uint32_t spp = passes * spp_per_pass;
  const Image var_rgb = pv.PerSampleVariance(spp);
  const Image var = RgbToXyz(var_rgb);
  for (int c = 0; c < 3; ++c) {
    double mean = 0;
    for (size_t p = 0; p < size_t(w * h); ++p) mean += var.rgb[p * 3 + size_t(c)];
    mean /= double(w * h);
    EXPECT_NEAR(mean / (sigma[c] * sigma[c]), 1.0, 0.028) << "channel " << c;
  }
  // The Z test of the image against the truth with its own variance passes.
  Image truth(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) truth.Set(x, y, XyzToRgbColor(mu[0], mu[1], mu[2]));
  ZTestOptions o;
  o.spp = spp;
  const ZTestResult r = ZTest(sum, truth, var_rgb, o);
  EXPECT_TRUE(r.pass) << FormatZTestTable(r);
  // ... and fails for an image 10 % too bright: z shifts by 0.1 · 1.2 / (0.5 / sqrt(640)) = 6
  // in Y.
  Image bright = sum;
  for (float& v : bright.rgb) v *= 1.1f;
  EXPECT_FALSE(ZTest(bright, truth, var_rgb, o).pass);
}

}  // namespace
}  // namespace ptlab
