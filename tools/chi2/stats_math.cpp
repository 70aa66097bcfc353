// Incomplete gamma function, χ² p-values, Šidák correction and pooled Pearson statistic.
#include "tools/chi2/stats_math.h"

#include <algorithm>
#include <numeric>

namespace ptlab {
namespace {

constexpr int kMaxIterations = 1000000;  // series/fraction need ~sqrt(a) terms near x = a
constexpr double kEps = 1e-15;
constexpr double kTiny = 1e-300;

// log of the common prefactor e^{-x} x^a / Γ(a).
double LogPrefactor(double a, double x) { return -x + a * std::log(x) - std::lgamma(a); }

// P(a, x) by its power series, good for x < a + 1:
// P = e^{-x} x^a / Γ(a+1) · Σ_n x^n / ((a+1)(a+2)...(a+n)).
double GammaPSeries(double a, double x) {
  double term = 1.0 / a, sum = term, denom = a;
  for (int n = 0; n < kMaxIterations; ++n) {
    denom += 1.0;
    term *= x / denom;
    sum += term;
    if (std::fabs(term) < std::fabs(sum) * kEps) break;
  }
  return sum * std::exp(LogPrefactor(a, x));
}

// Q(a, x) by the continued fraction Γ(a,x) = e^{-x} x^a (1/(x+1-a-) 1·(1-a)/(x+3-a-) ...),
// evaluated with the modified Lentz method; good for x >= a + 1.
double GammaQContinuedFraction(double a, double x) {
  double b = x + 1.0 - a;
  double c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < kMaxIterations; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::fabs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double step = d * c;
    h *= step;
    if (std::fabs(step - 1.0) < kEps) break;
  }
  return std::exp(LogPrefactor(a, x)) * h;
}

}  // namespace

double RegularizedGammaP(double a, double x) {
  if (!(a > 0) || !(x >= 0)) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0) return 0.0;
  if (std::isinf(x)) return 1.0;
  return x < a + 1.0 ? GammaPSeries(a, x) : 1.0 - GammaQContinuedFraction(a, x);
}

double RegularizedGammaQ(double a, double x) {
  if (!(a > 0) || !(x >= 0)) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0) return 1.0;
  if (std::isinf(x)) return 0.0;
  return x < a + 1.0 ? 1.0 - GammaPSeries(a, x) : GammaQContinuedFraction(a, x);
}

double ChiSquarePValue(double chi2, int dof) {
  if (dof < 1) return std::numeric_limits<double>::quiet_NaN();
  return RegularizedGammaQ(0.5 * dof, 0.5 * chi2);
}

double SidakAlpha(double alpha, int n) {
  // 1 - (1 - alpha)^(1/n), written with log1p/expm1 to keep digits for small alpha.
  return -std::expm1(std::log1p(-alpha) / std::max(n, 1));
}

PearsonResult PearsonChiSquare(const std::vector<double>& observed,
                               const std::vector<double>& expected, double min_expected) {
  PearsonResult r;
  std::vector<size_t> order(expected.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t i, size_t j) { return expected[i] < expected[j]; });
  double pooled_obs = 0, pooled_exp = 0;
  int cells = 0;
  for (size_t i : order) {
    const double o = observed[i], e = expected[i];
    if (e <= 0) {
      if (o > 0) {
        ++r.zero_expected_cells;
        r.zero_expected_observed += o;
      }
    } else if (e < min_expected || (r.pooled_cells > 0 && pooled_exp < min_expected)) {
      pooled_obs += o;
      pooled_exp += e;
      ++r.pooled_cells;
    } else {
      r.chi2 += (o - e) * (o - e) / e;
      ++cells;
    }
  }
  if (r.pooled_cells > 0) {
    r.chi2 += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
    ++cells;
  }
  r.dof = cells - 1;
  return r;
}

}  // namespace ptlab
