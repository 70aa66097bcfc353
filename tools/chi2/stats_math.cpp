// χ² and t p-values (Boost.Math), Šidák, the Pearson statistic, t-tests.
#include "tools/chi2/stats_math.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/non_central_chi_squared.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/gamma.hpp>

namespace ptlab {
namespace {

// Boost.Math with errors as NaN results instead of exceptions (callers check their domains
// first; a failure to converge must not throw out of a statistics routine).
using NanPolicy = boost::math::policies::policy<
    boost::math::policies::domain_error<boost::math::policies::ignore_error>,
    boost::math::policies::pole_error<boost::math::policies::ignore_error>,
    boost::math::policies::overflow_error<boost::math::policies::ignore_error>,
    boost::math::policies::evaluation_error<boost::math::policies::ignore_error>>;

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
  if (std::isinf(x)) return 1.0;
  return boost::math::gamma_p(a, x, NanPolicy());
}

double RegularizedGammaQ(double a, double x) {
  if (!(a > 0) || !(x >= 0)) return std::numeric_limits<double>::quiet_NaN();
  if (std::isinf(x)) return 0.0;
  return boost::math::gamma_q(a, x, NanPolicy());
}

double ChiSquarePValue(double chi2, int dof) {
  if (dof < 1 || !(chi2 >= 0)) return std::numeric_limits<double>::quiet_NaN();
  if (std::isinf(chi2)) return 0.0;
  const boost::math::chi_squared_distribution<double, NanPolicy> dist(dof);
  return boost::math::cdf(boost::math::complement(dist, chi2));
}

double ChiSquareUpperQuantile(double alpha, int dof) {
  if (dof < 1 || !(alpha > 0 && alpha < 1)) return std::numeric_limits<double>::quiet_NaN();
  const boost::math::chi_squared_distribution<double, NanPolicy> dist(dof);
  return boost::math::quantile(boost::math::complement(dist, alpha));
}

double NoncentralChiSquareSf(double x, int dof, double lambda) {
  if (dof < 1 || !(lambda >= 0) || std::isnan(x)) return std::numeric_limits<double>::quiet_NaN();
  if (x <= 0) return 1.0;
  if (std::isinf(x)) return 0.0;
  if (lambda == 0) return ChiSquarePValue(x, dof);
  const boost::math::non_central_chi_squared_distribution<double, NanPolicy> dist(dof, lambda);
  return boost::math::cdf(boost::math::complement(dist, x));
}

double SidakAlpha(double alpha, int n) {
  // 1 - (1 - alpha)^(1/n), written with log1p/expm1 to keep digits for small alpha.
  return -std::expm1(std::log1p(-alpha) / std::max(n, 1));
}

double RegularizedIncompleteBeta(double a, double b, double x) {
  if (!(a > 0) || !(b > 0) || !(x >= 0 && x <= 1)) return std::numeric_limits<double>::quiet_NaN();
  return boost::math::ibeta(a, b, x, NanPolicy());
}

double StudentTTwoTailedPValue(double t, double dof) {
  if (std::isnan(t) || !(dof > 0)) return std::numeric_limits<double>::quiet_NaN();
  if (std::isinf(t)) return 0.0;
  // The upper tail itself (not 1 - cdf), so tiny p-values keep their digits.
  const boost::math::students_t_distribution<double, NanPolicy> dist(dof);
  return 2.0 * boost::math::cdf(boost::math::complement(dist, std::fabs(t)));
}

double StudentTCdf(double t, double dof) {
  if (std::isnan(t) || !(dof > 0)) return std::numeric_limits<double>::quiet_NaN();
  if (std::isinf(t)) return t > 0 ? 1.0 : 0.0;
  const boost::math::students_t_distribution<double, NanPolicy> dist(dof);
  return boost::math::cdf(dist, t);
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
