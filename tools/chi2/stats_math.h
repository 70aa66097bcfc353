// Numerics of the chi-square lab: incomplete gamma / p-values, Šidák, adaptive Simpson, Pearson.
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
/// Series for x < a + 1, Lentz continued fraction otherwise (Numerical Recipes §6.2).
double RegularizedGammaQ(double a, double x);

/// Probability that a χ² variable with `dof` degrees of freedom is >= `chi2`: Q(dof/2, chi2/2).
double ChiSquarePValue(double chi2, int dof);

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
/// Richardson step). Returns 0 when b <= a. `budget` may be null (no limit).
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

}  // namespace ptlab
