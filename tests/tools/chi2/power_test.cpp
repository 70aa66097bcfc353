// The chi-square lab's power estimate: coarse grid, perturbations, and analytic vs simulated power.
#include "tools/chi2/power.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/sampling/warp.h"
#include "tools/chi2/coarse_grid.h"
#include "tools/chi2/subjects.h"

namespace ptlab {
namespace {

// P(X <= k) for X ~ Binomial(n, p), summed directly (n is small).
double BinomialCdf(int k, int n, double p) {
  double sum = 0;
  for (int i = 0; i <= k; ++i)
    sum += std::exp(std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0) +
                    i * std::log(p) + (n - i) * std::log1p(-p));
  return sum;
}

TEST(Chi2CoarseGrid, BlocksHoldEqualMarginalMass) {
  // A pdf living in columns 10..13 of 40 and rows 0..19 of 20: the 4 block columns take one
  // fine column each; rows split 5 per block.
  const int xres = 40, yres = 20;
  std::vector<double> expected(size_t(xres * yres), 0.0);
  for (int iy = 0; iy < yres; ++iy)
    for (int ix = 10; ix < 14; ++ix) expected[size_t(iy * xres + ix)] = 1.0;
  const Chi2CoarseGrid g = MakeChi2CoarseGrid(expected, xres, yres, 4);
  const std::vector<double> blocks = AggregateChi2Cells(g, expected);
  ASSERT_EQ(blocks.size(), 16u);
  for (double b : blocks) EXPECT_DOUBLE_EQ(b, 5.0);
  const std::vector<double> cdf = Chi2MarginalCdf(expected, xres, yres, 0);
  EXPECT_EQ(cdf.front(), 0.0);
  EXPECT_EQ(cdf.back(), 1.0);
  EXPECT_DOUBLE_EQ(cdf[12], 0.5);
}

TEST(Chi2Power, PerturbationsOfAUniformPdfAreTheClassicShapes) {
  Chi2Result base;
  base.domain = Chi2Domain::Hemisphere();
  base.xres = 8, base.yres = 4;
  base.expected.assign(32, 1.0);
  const std::vector<Chi2Perturbation> perts = Chi2SmoothPerturbations(base);
  ASSERT_EQ(perts.size(), 3u);
  // Column ix spans phi in [ix, ix + 1] * 2 pi / 8: the cell mean of cos phi.
  const double h = 2 * 3.14159265358979 / 8;
  for (int ix = 0; ix < 8; ++ix) {
    EXPECT_NEAR(perts[0].g[size_t(ix)], (std::sin((ix + 1) * h) - std::sin(ix * h)) / h, 1e-12);
  }
  // Polar: the ramp 2 cos(theta) - 1 averaged over rows of 1/4.
  for (int iy = 0; iy < 4; ++iy) EXPECT_NEAR(perts[2].g[size_t(iy * 8)], (2 * iy + 1) / 4.0 - 1, 1e-12);
}

// The analytic estimate against the test itself: the subject's sampler with the error applied
// by rejection, over 30 seeds, at the estimated 95 % error and at half of it; each count must
// lie in the central 99 % of Binomial(30, analytic power). 2·10^5 samples keep it quick.
TEST(StatChi2Power, AnalyticPowerMatchesSimulatedRejections) {
  const Chi2Subject subject = DirectionWarpSubject("warp/cosine_hemisphere",
                                                   Chi2Domain::Hemisphere(),
                                                   SampleCosineHemisphere, CosineHemispherePdf);
  Chi2Options options;
  options.samples = 200000;
  options.test_count = 120;
  const Chi2Result base = RunChi2Test(subject, options);
  ASSERT_TRUE(base.pass) << FormatChi2Result(subject, base);
  const Chi2Power power = EstimateChi2Power(base, false, options);
  const std::vector<Chi2Perturbation> perts = Chi2SmoothPerturbations(base);
  constexpr int kSeeds = 30;
  for (size_t k : {size_t(0), size_t(2)}) {  // azimuth-cos, polar
    for (double scale : {1.0, 0.5}) {
      const double e = power.shapes[k].epsilon * scale;
      const double predicted = Chi2AnalyticPower(base, false, options, perts[k], e);
      std::vector<double> keep(perts[k].g.size());
      for (size_t i = 0; i < keep.size(); ++i) keep[i] = (1 + e * perts[k].g[i]) / (1 + e);
      int detected = 0;
      for (int s = 0; s < kSeeds; ++s) {
        Chi2Options o = options;
        o.seed = 1000 + uint64_t(s);
        detected += !RerunChi2Thinned(subject, o, base, keep, 1 / (1 + e)).pass;
      }
      EXPECT_GT(BinomialCdf(detected, kSeeds, predicted), 0.005)
          << perts[k].shape << " eps " << e << ": " << detected << "/" << kSeeds
          << " rejected, predicted " << predicted;
      EXPECT_GT(1 - BinomialCdf(detected - 1, kSeeds, predicted), 0.005)
          << perts[k].shape << " eps " << e << ": " << detected << "/" << kSeeds
          << " rejected, predicted " << predicted;
    }
  }
}

// Without the coarse grid the fine one misses a 2 % smooth error at 10^6 samples (the blindness
// the coarse grid exists for); with it the error is caught.
TEST(Chi2Power, CoarseGridCatchesWhatTheFineGridMisses) {
  const Chi2Subject subject = DirectionWarpSubject("warp/cosine_hemisphere",
                                                   Chi2Domain::Hemisphere(),
                                                   SampleCosineHemisphere, CosineHemispherePdf);
  Chi2Options options;
  options.test_count = 120;
  Chi2Result base = RunChi2Test(subject, options);
  const std::vector<Chi2Perturbation> perts = Chi2SmoothPerturbations(base);
  for (const Chi2Perturbation& p : perts)
    EXPECT_GT(Chi2AnalyticPower(base, false, options, p, 0.02), 0.95) << p.shape;
  options.coarse_blocks = 0;
  base = RunChi2Test(subject, options);
  for (const Chi2Perturbation& p : Chi2SmoothPerturbations(base))
    EXPECT_LT(Chi2AnalyticPower(base, false, options, p, 0.02), 0.2) << p.shape;
}

}  // namespace
}  // namespace ptlab
