// Incomplete gamma and beta functions, χ² and t p-values, Šidák, Pearson statistic, t-tests.
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

// The continued fraction of I_x(a, b) (Numerical Recipes eq. 6.4.5): I_x(a, b) = x^a y^b /
// (a B(a, b)) · 1/(1+ d1/(1+ d2/(1+ ...))) with d_{2m+1} = -(a+m)(a+b+m) x / ((a+2m)(a+2m+1)),
// d_{2m} = m(b-m) x / ((a+2m-1)(a+2m)), by the modified Lentz method. y = 1 - x is passed
// separately so callers that know it exactly (the t distribution) lose no digits near x = 1.
// Converges in O(sqrt(max(a, b))) steps for x < (a+1)/(a+b+2).
double BetaContinuedFraction(double a, double b, double x, double y) {
  const double qab = a + b, qap = a + 1.0, qam = a - 1.0;
  double c = 1.0, d = 1.0 - qab * x / qap;
  if (std::fabs(d) < kTiny) d = kTiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m < kMaxIterations; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((qam + m2) * (a + m2));
    d = 1.0 + aa * d;
    if (std::fabs(d) < kTiny) d = kTiny;
    c = 1.0 + aa / c;
    if (std::fabs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    h *= d * c;
    aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
    d = 1.0 + aa * d;
    if (std::fabs(d) < kTiny) d = kTiny;
    c = 1.0 + aa / c;
    if (std::fabs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double step = d * c;
    h *= step;
    if (std::fabs(step - 1.0) < kEps) break;
  }
  const double log_front =
      std::lgamma(qab) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log(y);
  return std::exp(log_front) * h / a;
}

// I_x(a, b) with y = 1 - x given exactly; a, b > 0, 0 < x < 1.
double IncompleteBeta(double a, double b, double x, double y) {
  if (x < (a + 1.0) / (a + b + 2.0)) return BetaContinuedFraction(a, b, x, y);
  return 1.0 - BetaContinuedFraction(b, a, y, x);
}

TTestResult Decide(double t, double dof, double alpha, int test_count) {
  TTestResult r;
  r.t = t;
  r.dof = dof;
  r.p_value = StudentTTwoTailedPValue(t, dof);
  r.alpha = SidakAlpha(alpha, test_count);
  r.pass = r.p_value >= r.alpha;  // false for NaN
  return r;
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

double RegularizedIncompleteBeta(double a, double b, double x) {
  if (!(a > 0) || !(b > 0) || !(x >= 0 && x <= 1)) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0) return 0.0;
  if (x == 1) return 1.0;
  return IncompleteBeta(a, b, x, 1.0 - x);
}

double StudentTTwoTailedPValue(double t, double dof) {
  if (std::isnan(t) || !(dof > 0)) return std::numeric_limits<double>::quiet_NaN();
  if (std::isinf(t)) return 0.0;
  if (t == 0) return 1.0;
  // P[|T| >= t] = I_{ν/(ν+t²)}(ν/2, 1/2) (Abramowitz & Stegun 26.7.1 with 26.5.27).
  const double t2 = t * t;
  return IncompleteBeta(0.5 * dof, 0.5, dof / (dof + t2), t2 / (dof + t2));
}

double StudentTCdf(double t, double dof) {
  if (std::isnan(t) || !(dof > 0)) return std::numeric_limits<double>::quiet_NaN();
  const double tail = 0.5 * StudentTTwoTailedPValue(t, dof);  // P[T >= |t|]
  return t > 0 ? 1.0 - tail : tail;
}

TTestResult OneSampleTTest(double mean, double variance, int64_t n, double reference, double alpha,
                           int test_count, double min_variance) {
  const double v = std::max(variance, min_variance);
  const double t = (mean - reference) / std::sqrt(v / double(n));
  return Decide(t, double(n - 1), alpha, test_count);
}

TTestResult WelchTTest(double mean1, double variance1, int64_t n1, double mean2, double variance2,
                       int64_t n2, double alpha, int test_count) {
  const double s1 = variance1 / double(n1), s2 = variance2 / double(n2);
  const double se2 = s1 + s2;
  const double diff = mean1 - mean2;
  if (!(se2 > 0)) {
    const double t = diff == 0 ? 0.0 : std::copysign(INFINITY, diff);
    return Decide(t, double(n1 + n2 - 2), alpha, test_count);
  }
  // Welch–Satterthwaite: ν = (s1 + s2)² / (s1² / (n1 - 1) + s2² / (n2 - 1)).
  const double dof = se2 * se2 / (s1 * s1 / double(n1 - 1) + s2 * s2 / double(n2 - 1));
  return Decide(diff / std::sqrt(se2), dof, alpha, test_count);
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
