// Numerics of the statistical lab: χ² and Student t p-values, Šidák, adaptive Simpson, Pearson.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace ptlab {

/// Regularised lower incomplete gamma P(a, x) = γ(a, x) / Γ(a); a > 0, x >= 0 (NaN otherwise).
double RegularizedGammaP(double a, double x);

/// Regularised upper incomplete gamma Q(a, x) = Γ(a, x) / Γ(a) = 1 - P(a, x); a > 0, x >= 0.
double RegularizedGammaQ(double a, double x);

/// Probability that a χ² variable with `dof` degrees of freedom is >= `chi2`: Q(dof/2, chi2/2).
double ChiSquarePValue(double chi2, int dof);

/// The χ² value a variable with `dof` degrees of freedom exceeds with probability `alpha`
/// (the test's critical value). dof >= 1, 0 < alpha < 1.
double ChiSquareUpperQuantile(double alpha, int dof);

/// Probability that a noncentral χ² variable (dof, noncentrality lambda >= 0) is > x: the
/// asymptotic power of Pearson's test against an alternative with that noncentrality.
double NoncentralChiSquareSf(double x, int dof, double lambda);

/// Šidák per-test significance: n independent tests at this level reject a true hypothesis
/// somewhere with probability `alpha`: 1 - (1 - alpha)^(1/n). n >= 1.
double SidakAlpha(double alpha, int n);

/// Stopping rules of AdaptiveSimpson. A sub-interval is accepted when its two-panel estimate
/// differs from its one-panel estimate by <= 15 max(rel_tol |estimate|, abs_tol / 2^depth).
struct SimpsonOptions {
  double rel_tol = 1e-6;
  double abs_tol = 0.0;
  int min_depth = 2;  // always split this often (2 -> 9 points per interval), to see small features
  int max_depth = 16;  // never split further (a step discontinuity converges only to here)
};

/// Evaluation counter shared by nested integrations: once `used` reaches `limit`, every interval
/// is accepted as it is (and `exhausted` is set), so the cost of a pathological integrand is
/// bounded.
struct SimpsonBudget {
  int64_t used = 0;
  int64_t limit = std::numeric_limits<int64_t>::max();
  bool exhausted = false;
};

namespace internal {

template <typename F>
double SimpsonRecurse(F& f, double a, double fa, double m, double fm, double b, double fb,
                      double whole, double abs_eps, int depth, const SimpsonOptions& options,
                      SimpsonBudget* budget) {
  const double lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = f(lm), frm = f(rm);
  budget->used += 2;
  // A NaN integrand value makes the integral NaN however far this recursed: stop here. (The
  // chi-square lab's batch replay reads a pdf value it has not evaluated yet as NaN, so this
  // also defers the refinement that depends on it to the next pass.)
  if (std::isnan(fa + fm + fb + flm + frm)) return std::numeric_limits<double>::quiet_NaN();
  const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
  const double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
  const double sum = left + right;
  const double delta = std::fabs(sum - whole);
  const bool converged = delta <= 15.0 * std::max(options.rel_tol * std::fabs(sum), abs_eps);
  if (depth >= options.min_depth && (converged || depth >= options.max_depth)) return sum;
  if (budget->used >= budget->limit) {
    budget->exhausted = budget->exhausted || !converged;
    return sum;
  }
  // No Richardson extrapolation: plain Simpson weights are positive, so the integral of a
  // non-negative pdf stays non-negative even across a discontinuity.
  return SimpsonRecurse(f, a, fa, lm, flm, m, fm, left, 0.5 * abs_eps, depth + 1, options, budget) +
         SimpsonRecurse(f, m, fm, rm, frm, b, fb, right, 0.5 * abs_eps, depth + 1, options, budget);
}

}  // namespace internal

/// ∫_a^b f(x) dx by adaptive Simpson quadrature (Kuncir 1962 / Lyness 1969, without the
/// Richardson step). Returns 0 when b <= a, NaN when f is NaN at a point it evaluates.
/// `budget` may be null (no limit).
template <typename F>
double AdaptiveSimpson(F&& f, double a, double b, const SimpsonOptions& options = {},
                       SimpsonBudget* budget = nullptr) {
  if (!(b > a)) return 0.0;
  SimpsonBudget local;
  if (budget == nullptr) budget = &local;
  const double m = 0.5 * (a + b);
  const double fa = f(a), fm = f(m), fb = f(b);
  budget->used += 3;
  const double whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
  return internal::SimpsonRecurse(f, a, fa, m, fm, b, fb, whole, options.abs_tol, 1, options,
                                  budget);
}

/// Stopping rules of a nested 2-D integration. The outer tolerance must be looser than what the
/// inner integrals achieve: across a step the inner error only shrinks with max_depth, and an
/// outer rule stricter than that noise would refine to its own max_depth everywhere.
struct Simpson2DOptions {
  SimpsonOptions outer{1e-5, 0.0, 2, 16};
  SimpsonOptions inner{1e-6, 0.0, 2, 18};
};

/// ∫_{x0}^{x1} ∫_{y0}^{y1} f(x, y) dy dx by nested 1-D adaptive Simpson (outer x, inner y).
template <typename F>
double AdaptiveSimpson2D(F&& f, double x0, double x1, double y0, double y1,
                         const Simpson2DOptions& options = {}, SimpsonBudget* budget = nullptr) {
  SimpsonBudget local;
  if (budget == nullptr) budget = &local;
  auto inner = [&](double x) {
    return AdaptiveSimpson([&](double y) { return f(x, y); }, y0, y1, options.inner, budget);
  };
  return AdaptiveSimpson(inner, x0, x1, options.outer, budget);
}

/// Outcome of Pearson's χ² statistic over cells with small expected counts pooled.
struct PearsonResult {
  double chi2 = 0;
  int dof = 0;                  // cells after pooling - 1 (may be < 1: then no test is possible)
  int pooled_cells = 0;         // cells merged into the pooled cell (0 = no pooling)
  int zero_expected_cells = 0;  // cells with expected 0 that hold observations
  double zero_expected_observed = 0;
};

/// Pearson's χ² = Σ (O - E)² / E. Cells are taken by increasing expected count; those with
/// E < min_expected are merged into one pooled cell, which keeps taking the next cells until its
/// own E >= min_expected (Nori / Mitsuba style). Cells with E == 0 are left out of the sum and
/// counted in zero_expected_* when they hold observations. observed.size() == expected.size().
PearsonResult PearsonChiSquare(const std::vector<double>& observed,
                               const std::vector<double>& expected, double min_expected = 5.0);

/// Regularised incomplete beta function I_x(a, b) = B(x; a, b) / B(a, b); a, b > 0,
/// 0 <= x <= 1 (NaN otherwise). These special functions and distributions are Boost.Math's.
double RegularizedIncompleteBeta(double a, double b, double x);

/// P[T <= t] for Student's t distribution with `dof` > 0 degrees of freedom (real dof allowed,
/// as Welch's test needs).
double StudentTCdf(double t, double dof);

/// Two-tailed p-value P[|T| >= |t|] = I_{dof/(dof+t²)}(dof/2, 1/2), computed directly (not as
/// 1 - cdf), so tiny p-values keep their digits. NaN t gives NaN.
double StudentTTwoTailedPValue(double t, double dof);

/// Mean and variance of a stream of values, one pass (Welford), mergeable (Chan et al.), so
/// chunks accumulated on several threads and merged in a fixed order give fixed results.
struct RunningMoments {
  int64_t n = 0;
  double mean = 0;
  double m2 = 0;  // Σ (x - mean)²

  void Add(double x) {
    ++n;
    const double delta = x - mean;
    mean += delta / double(n);
    m2 += delta * (x - mean);
  }
  void Merge(const RunningMoments& o) {
    if (o.n == 0) return;
    const int64_t total = n + o.n;
    const double delta = o.mean - mean;
    mean += delta * double(o.n) / double(total);
    m2 += o.m2 + delta * delta * double(n) * double(o.n) / double(total);
    n = total;
  }
  /// Unbiased sample variance (n - 1 in the denominator); 0 for n < 2.
  double Variance() const { return n > 1 ? m2 / double(n - 1) : 0.0; }
};

/// Outcome of a t-test at a Šidák-corrected level.
struct TTestResult {
  double t = 0;  // the t statistic (signed: estimate above the reference is > 0)
  double dof = 0;
  double p_value = std::numeric_limits<double>::quiet_NaN();  // two-tailed
  double alpha = 0;                                           // Šidák-corrected per-test level
  bool pass = false;  // the null hypothesis (equal means) was accepted: p >= alpha
};

/// Nori's floor on the sample variance of a t-test (hypothesis::students_t_test): an estimator
/// that is constant (variance 0, e.g. total internal reflection) and equal to the reference
/// passes instead of dividing 0 by 0.
inline constexpr double kNoriMinTTestVariance = 1e-5;

/// One-sample two-tailed Student t-test of H0: E[X] = reference, from n samples with sample
/// mean `mean` and unbiased sample variance `variance`: t = (mean - reference) /
/// sqrt(max(variance, min_variance) / n), dof = n - 1, rejected when p < SidakAlpha(alpha,
/// test_count) (Nori's test). n >= 2, 0 < alpha < 1, test_count >= 1.
TTestResult OneSampleTTest(double mean, double variance, int64_t n, double reference, double alpha,
                           int test_count, double min_variance = kNoriMinTTestVariance);

/// Welch's two-sample two-tailed t-test of H0: E[X1] = E[X2] (unequal variances; dof by
/// Welch–Satterthwaite), at SidakAlpha(alpha, test_count). n1, n2 >= 2. Two constant samples
/// (both variances 0) give t = 0 (p = 1) when the means are equal, else t = ±inf (p = 0).
TTestResult WelchTTest(double mean1, double variance1, int64_t n1, double mean2, double variance2,
                       int64_t n2, double alpha, int test_count);

}  // namespace ptlab
