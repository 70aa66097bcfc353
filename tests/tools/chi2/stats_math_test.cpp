// Unit tests of the chi-square lab's numerics: incomplete gamma, p-values, Šidák, Simpson, Pearson.
#include "tools/chi2/stats_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace ptlab {
namespace {

constexpr double kPi = 3.14159265358979323846;

// For integer k, Q(k, x) = P[Poisson(x) < k] and P(k, x) = P[Poisson(x) >= k]: sums of Poisson
// terms e^{-x} x^j / j! (each taken in log space), an independent reference for the series /
// continued-fraction code. Each tail is summed directly, so neither suffers 1 - (sum near 1).
double PoissonTerm(int j, double x) {
  return std::exp(-x + j * std::log(x) - std::lgamma(j + 1.0));
}
double GammaQReference(int k, double x) {
  double sum = 0;
  for (int j = 0; j < k; ++j) sum += PoissonTerm(j, x);
  return sum;
}
double GammaPReference(int k, double x) {
  double sum = 0;
  for (int j = k;; ++j) {
    const double t = PoissonTerm(j, x);
    sum += t;
    if (j > x && t < 1e-18 * sum) break;
  }
  return sum;
}

TEST(Chi2MathGamma, OrderOneIsExponential) {
  for (double x : {0.0, 1e-3, 0.1, 1.0, 1.9, 2.1, 5.0, 30.0, 200.0}) {
    EXPECT_NEAR(RegularizedGammaQ(1.0, x), std::exp(-x), 1e-13 * std::exp(-x) + 1e-300) << x;
  }
}

TEST(Chi2MathGamma, OrderOneHalfIsErfc) {
  for (double x : {1e-4, 0.05, 0.5, 1.0, 1.5, 3.0, 10.0, 40.0}) {
    const double ref = std::erfc(std::sqrt(x));
    EXPECT_NEAR(RegularizedGammaQ(0.5, x), ref, 1e-12 * ref) << x;
  }
}

TEST(Chi2MathGamma, IntegerOrderIsPoissonTail) {
  // Covers both branches (x < a + 1: series; else: continued fraction) and the large orders of
  // real runs (dof/2 ≈ 1300 and 2600 for 51x51 and 102x51 grids).
  // Each Poisson term carries a relative error ~1e-16 * x from its exponent: 1e-10 is loose.
  for (int k : {2, 5, 20, 301, 1300, 2601}) {
    for (double f : {0.5, 0.9, 1.0, 1.02, 1.1, 1.5}) {
      const double x = f * k;
      const double q = GammaQReference(k, x), p = GammaPReference(k, x);
      EXPECT_NEAR(RegularizedGammaQ(k, x), q, 1e-10 * q) << "k=" << k << " x=" << x;
      EXPECT_NEAR(RegularizedGammaP(k, x), p, 1e-10 * p) << "k=" << k << " x=" << x;
    }
    const double at_boundary = k + 1.0;  // where the two methods meet
    EXPECT_NEAR(RegularizedGammaQ(k, at_boundary), GammaQReference(k, at_boundary), 1e-12);
  }
}

TEST(Chi2MathGamma, LimitsAndInvalidArguments) {
  EXPECT_EQ(RegularizedGammaQ(3.0, 0.0), 1.0);
  EXPECT_EQ(RegularizedGammaP(3.0, 0.0), 0.0);
  EXPECT_EQ(RegularizedGammaQ(3.0, INFINITY), 0.0);
  EXPECT_TRUE(std::isnan(RegularizedGammaQ(0.0, 1.0)));
  EXPECT_TRUE(std::isnan(RegularizedGammaQ(-1.0, 1.0)));
  EXPECT_TRUE(std::isnan(RegularizedGammaQ(1.0, -1.0)));
  EXPECT_TRUE(std::isnan(RegularizedGammaQ(1.0, NAN)));
}

TEST(Chi2MathPValue, MatchesChiSquareTables) {
  struct Row {
    double chi2;
    int dof;
    double p;
  };
  // Upper critical values of the χ² distribution (NIST/SEMATECH e-Handbook, table 1.3.6.7.4).
  const Row rows[] = {{3.841459, 1, 0.05},  {6.634897, 1, 0.01},   {10.828, 1, 0.001},
                      {5.991465, 2, 0.05},  {18.307038, 10, 0.05}, {23.209251, 10, 0.01},
                      {124.342, 100, 0.05}, {135.807, 100, 0.01},  {0.454936, 1, 0.5}};
  for (const Row& r : rows) {
    EXPECT_NEAR(ChiSquarePValue(r.chi2, r.dof), r.p, 2e-6) << r.chi2 << " " << r.dof;
  }
  // dof 2: Q(1, x/2) = e^{-x/2} exactly.
  EXPECT_NEAR(ChiSquarePValue(7.0, 2), std::exp(-3.5), 1e-15);
  EXPECT_TRUE(std::isnan(ChiSquarePValue(1.0, 0)));
}

TEST(Chi2MathPValue, ExtremeStatisticsGiveExtremePValues) {
  EXPECT_LT(ChiSquarePValue(1e5, 2600), 1e-300);
  EXPECT_GT(ChiSquarePValue(1000.0, 2600), 1.0 - 1e-12);
  const double p = ChiSquarePValue(2600.0, 2600);  // near the median: a little above 1/2
  EXPECT_GT(p, 0.49);
  EXPECT_LT(p, 0.51);
}

TEST(Chi2MathSidak, CorrectsForTheNumberOfTests) {
  EXPECT_NEAR(SidakAlpha(0.01, 1), 0.01, 1e-16);
  for (int n : {2, 13, 100, 10000}) {
    const double a = SidakAlpha(0.01, n);
    EXPECT_NEAR(std::pow(1.0 - a, n), 0.99, 1e-12) << n;
    EXPECT_LT(a, 0.01 / n * 1.01);  // a little above Bonferroni's alpha / n, never far
    EXPECT_GT(a, 0.01 / n);
  }
}

TEST(Chi2MathSimpson, KnownIntegrals) {
  // Simpson is exact for cubics.
  EXPECT_NEAR(AdaptiveSimpson([](double x) { return x * x * x; }, 0.0, 2.0), 4.0, 1e-14);
  // Smooth integrands: relative error within rel_tol (the default 1e-6, then 1e-11).
  auto sin = [](double x) { return std::sin(x); };
  auto exp = [](double x) { return std::exp(x); };
  const double exp_ref = std::exp(2.0) - std::exp(-1.0);
  EXPECT_NEAR(AdaptiveSimpson(sin, 0.0, kPi), 2.0, 2.0 * 1e-6);
  EXPECT_NEAR(AdaptiveSimpson(exp, -1.0, 2.0), exp_ref, exp_ref * 1e-6);
  SimpsonOptions tight;
  tight.rel_tol = 1e-11;
  tight.max_depth = 30;
  EXPECT_NEAR(AdaptiveSimpson(sin, 0.0, kPi, tight), 2.0, 2.0 * 1e-11);
  EXPECT_NEAR(AdaptiveSimpson(exp, -1.0, 2.0, tight), exp_ref, exp_ref * 1e-11);
  // Infinite derivative at 0.
  EXPECT_NEAR(AdaptiveSimpson([](double x) { return std::sqrt(x); }, 0.0, 1.0), 2.0 / 3.0, 1e-6);
  // Step inside the interval: converges only through max_depth (18 -> ~2^-18 of the interval).
  SimpsonOptions deep;
  deep.max_depth = 18;
  EXPECT_NEAR(AdaptiveSimpson([](double x) { return x >= 1.0 / 3.0 ? 1.0 : 0.0; }, 0.0, 1.0, deep),
              2.0 / 3.0, 1e-5);
  EXPECT_EQ(AdaptiveSimpson([](double x) { return x; }, 1.0, 1.0), 0.0);
  EXPECT_EQ(AdaptiveSimpson([](double x) { return x; }, 2.0, 1.0), 0.0);
}

TEST(Chi2MathSimpson, MinDepthAndBudgetBoundTheWork) {
  SimpsonBudget budget;
  EXPECT_EQ(AdaptiveSimpson([](double) { return 0.0; }, 0.0, 1.0, {}, &budget), 0.0);
  EXPECT_EQ(budget.used, 9);  // min_depth 2: 9 points, then the zero function has converged
  EXPECT_FALSE(budget.exhausted);

  // A feature narrower than the 9-point spacing between its points is invisible at min_depth 2
  // and found at min_depth 4 (33 points).
  auto spike = [](double x) { return std::fabs(x - 0.53) < 0.01 ? 1.0 : 0.0; };
  EXPECT_EQ(AdaptiveSimpson(spike, 0.0, 1.0), 0.0);
  SimpsonOptions fine;
  fine.min_depth = 4;
  EXPECT_NEAR(AdaptiveSimpson(spike, 0.0, 1.0, fine), 0.02, 1e-4);

  // An integrand that never converges (a discontinuity everywhere) stops at the budget.
  SimpsonBudget small;
  small.limit = 1000;
  auto noise = [](double x) { return double(uint64_t(x * 1e9) * 0x9e3779b97f4a7c15ULL >> 40); };
  AdaptiveSimpson(noise, 0.0, 1.0, {}, &small);
  EXPECT_TRUE(small.exhausted);
  EXPECT_LE(small.used, small.limit + 2 * 64);  // the recursion unwinds with a few more points
}

TEST(Chi2MathSimpson, KnownIntegrals2D) {
  EXPECT_NEAR(AdaptiveSimpson2D([](double x, double y) { return x * y; }, 0, 1, 0, 1), 0.25, 1e-14);
  const double e3 = std::erf(3.0);
  // Default outer rel_tol 1e-5 (inner 1e-6).
  EXPECT_NEAR(
      AdaptiveSimpson2D([](double x, double y) { return std::exp(-x * x - y * y); }, -3, 3, -3, 3),
      kPi * e3 * e3, kPi * 1e-5);
  // The unit disk's indicator, integrated with its curved discontinuity inside the box.
  auto disk = [](double x, double y) { return x * x + y * y <= 1.0 ? 1.0 : 0.0; };
  EXPECT_NEAR(AdaptiveSimpson2D(disk, -1, 1, -1, 1), kPi, 1e-4);
  // A box the circle cuts through: {x, y >= 1/2} ∩ disk has area π/12 - (√3 - 1)/4.
  EXPECT_NEAR(AdaptiveSimpson2D(disk, 0.5, 1, 0.5, 1), kPi / 12 - (std::sqrt(3.0) - 1) / 4, 1e-5);
}

TEST(Chi2MathPearson, StatisticWithoutPooling) {
  const PearsonResult r = PearsonChiSquare({10, 20, 30}, {12, 18, 30});
  EXPECT_NEAR(r.chi2, 4.0 / 12 + 4.0 / 18, 1e-14);
  EXPECT_EQ(r.dof, 2);
  EXPECT_EQ(r.pooled_cells, 0);
  EXPECT_EQ(r.zero_expected_cells, 0);
}

TEST(Chi2MathPearson, PoolsSmallCellsUntilThePoolIsLargeEnough) {
  // Cells with E < 5 (1, 2, 3 -> pooled E = 6) form one cell.
  PearsonResult r = PearsonChiSquare({11, 0, 19, 3, 2}, {10, 1, 20, 2, 3});
  EXPECT_NEAR(r.chi2, 1.0 / 6 + 1.0 / 10 + 1.0 / 20, 1e-14);
  EXPECT_EQ(r.dof, 2);
  EXPECT_EQ(r.pooled_cells, 3);
  // Small cells add up to E = 2 only: the pool also takes the next cell (E = 8).
  r = PearsonChiSquare({3, 0, 9, 18}, {1, 1, 8, 20});
  EXPECT_NEAR(r.chi2, (12.0 - 10.0) * (12.0 - 10.0) / 10 + 4.0 / 20, 1e-14);
  EXPECT_EQ(r.dof, 1);
  EXPECT_EQ(r.pooled_cells, 3);
}

TEST(Chi2MathPearson, CountsObservationsInCellsOfZeroExpectation) {
  const PearsonResult r = PearsonChiSquare({2, 9, 9, 0}, {0, 10, 10, 0});
  EXPECT_EQ(r.zero_expected_cells, 1);
  EXPECT_EQ(r.zero_expected_observed, 2);
  EXPECT_EQ(r.dof, 1);
  EXPECT_NEAR(r.chi2, 0.2, 1e-14);
}

}  // namespace
}  // namespace ptlab
