// Error-vs-time records of `ptlab converge`: fits, time to quality, the two-halves estimate.
#include "tools/converge/convergence.h"

#include <cmath>
#include <cstdio>
#include <random>
#include <tuple>

#include <gtest/gtest.h>

#include "tools/imgdiff/imgdiff.h"

namespace ptlab {
namespace {

TEST(Convergence, FitLogLogRecoversAPowerLaw) {
  std::vector<double> x, y;
  for (double n = 16; n <= 1024; n *= 2) x.push_back(n), y.push_back(3.0 * std::pow(n, -1.0));
  const LogLogFit fit = FitLogLog(x, y);
  EXPECT_EQ(fit.points, 7);
  EXPECT_NEAR(fit.slope, -1.0, 1e-12);
  EXPECT_NEAR(std::exp(fit.intercept), 3.0, 1e-9);
  EXPECT_NEAR(fit.slope_stderr, 0.0, 1e-9);
  // Non-positive and non-finite points are left out.
  x.push_back(0), y.push_back(1);
  x.push_back(5), y.push_back(std::nan(""));
  EXPECT_EQ(FitLogLog(x, y).points, 7);
  EXPECT_TRUE(std::isnan(FitLogLog({1}, {1}).slope));
}

TEST(Convergence, TimeToQualityInterpolatesLogLog) {
  std::vector<ConvergencePoint> run(3);
  run[0].seconds = 1, run[0].rel_mse = 1e-1;
  run[1].seconds = 10, run[1].rel_mse = 1e-3;
  run[2].seconds = 20, run[2].rel_mse = 5e-4;
  // Between (1 s, 1e-1) and (10 s, 1e-3): relMSE ~ t^-2, so 1e-2 at sqrt(10) s.
  EXPECT_NEAR(TimeToQuality(run, 1e-2), std::sqrt(10.0), 1e-9);
  EXPECT_NEAR(TimeToQuality(run, 1e-3), 10.0, 1e-9);
  EXPECT_NEAR(TimeToQuality(run, 0.5), 1.0, 1e-12);  // reached at the first pass
  EXPECT_TRUE(std::isnan(TimeToQuality(run, 1e-4)));
}

// Two halves of N samples each of a known noise: the estimate of the mean's relMSE is the
// truth within its sampling error and the bias left by its denominator's second-order Jensen
// correction, the next term of E[1/(1 + x)²] for Gaussian x: 15 r⁴ with r² = var(m) / μ² the
// merged mean's relative variance (r² = 0.02 and 0.08 here: +0.006 and +0.096). On a flat image
// and on stripes two pixels wide that alternate 0.5 and 5 (edges everywhere: a neighbourhood
// mean as the denominator read +7 % at 20 % noise there).
TEST(Convergence, TwoHalvesEstimateTheErrorOfTheirMean) {
  for (const double noise_of_a_half : {0.2, 0.4}) {  // relative to the signal
    for (const bool stripes : {false, true}) {
      const int w = 200, h = 200;
      std::mt19937 rng(7);
      std::normal_distribution<double> noise(0.0, noise_of_a_half);
      Image a(w, h), b(w, h), mean(w, h), truth(w, h);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < 3; ++c) {
            const size_t i = (size_t(y) * w + x) * 3 + c;
            const double mu = stripes && (x / 2) % 2 == 1 ? 5.0 : 0.5;
            a.rgb[i] = float(mu * (1 + noise(rng)));
            b.rgb[i] = float(mu * (1 + noise(rng)));
            mean.rgb[i] = 0.5f * (a.rgb[i] + b.rgb[i]);
            truth.rgb[i] = float(mu);
          }
      const double actual = CompareImages(mean, truth, {}).rel_mse_all;
      const double r2 = noise_of_a_half * noise_of_a_half / 2;
      // 120,000 values: the ratio's sampling error is ~0.5 %; 0.02 leaves 4 of them.
      const double expected_bias = 15 * r2 * r2;
      const double ratio = EstimateRelMseFromHalves(a, b) / actual;
      std::printf("half noise %.0f %%, %s: estimate / truth %.3f (expected %.3f)\n",
                  100 * noise_of_a_half, stripes ? "stripes" : "flat", ratio, 1 + expected_bias);
      if (stripes && noise_of_a_half > 0.3) {
        // Beyond the expansion: at 40 % noise next to 10x contrast the neighbours' r² is
        // itself inflated; measured +42 %. Bounded, not claimed.
        EXPECT_LT(ratio, 1.6);
        EXPECT_GT(ratio, 1.0);
      } else {
        EXPECT_NEAR(ratio, 1.0 + expected_bias, 0.02)
            << "half noise " << noise_of_a_half << (stripes ? " stripes" : " flat");
      }
    }
  }
}

TEST(Convergence, SummaryAveragesSeedsAndFitsTheSlope) {
  std::vector<ConvergencePoint> points;
  for (uint64_t seed : {1, 2})
    for (uint32_t k = 0; k < 4; ++k) {
      ConvergencePoint p;
      // Move-assigned strings: assigning the literals trips GCC 12's -Wrestrict false positive.
      p.scene = std::string("s"), p.variant = std::string("v");
      p.seed = seed, p.pass = k, p.spp = 16 * (k + 1);
      p.mean_spp = p.spp;
      p.seconds = 0.5 * (k + 1);
      p.rel_mse = (seed == 1 ? 0.9 : 1.1) / p.spp;
      p.estimated_rel_mse = k % 2 ? 1.2 / p.spp : std::nan("");
      points.push_back(p);
    }
  const std::vector<VariantSummary> s = Summarize(points);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].seeds, 2);
  EXPECT_NEAR(s[0].final_rel_mse, 1.0 / 64, 1e-12);
  EXPECT_NEAR(s[0].slope_spp.slope, -1.0, 1e-12);
  EXPECT_NEAR(s[0].efficiency, 64.0 / 2.0, 1e-9);
  EXPECT_NEAR(s[0].estimate_ratio, 1.2, 1e-12);
  EXPECT_NEAR(s[0].final_rel_mse_sd, std::sqrt(2.0) * 0.1 / 64, 1e-12);
}

// Two variants with relMSE = c / seconds: efficiency 1/(relMSE·s) = 1/c at every time, so the
// ratio at matched time is c_first / c_other wherever the curves overlap.
TEST(Convergence, MatchedRatioComparesAtTheTimeBothRunsReached) {
  std::vector<ConvergencePoint> points;
  for (const auto& [variant, c, dt] : {std::tuple<const char*, double, double>{"a", 1.0, 1.0},
                                       {"b", 4.0, 0.3}}) {
    for (uint32_t k = 0; k < 5; ++k) {
      ConvergencePoint p;
      p.scene = std::string("s"), p.variant = std::string(variant);
      p.pass = k, p.spp = p.mean_spp = 16 * (k + 1);
      p.seconds = dt * (k + 1);
      p.rel_mse = c / p.seconds;
      points.push_back(p);
    }
  }
  const std::vector<VariantSummary> s = Summarize(points);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_DOUBLE_EQ(s[0].matched_ratio, 1.0);
  EXPECT_NEAR(s[1].matched_seconds, 1.5, 1e-12);  // b's last pass; a reached 5 s
  EXPECT_NEAR(s[1].matched_ratio, 0.25, 1e-9);
  EXPECT_NEAR(RelMseAtSeconds(s[0], 1.5), 1.0 / 1.5, 1e-9);  // between a's passes 1 and 2
  EXPECT_TRUE(std::isnan(RelMseAtSeconds(s[0], 0.5)));       // before a's first pass
}

}  // namespace
}  // namespace ptlab
