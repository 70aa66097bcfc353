// Power of the chi-square lab: smooth perturbations, noncentral χ² power, bisection, simulation.
#include "tools/chi2/power.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/core/check.h"
#include "tools/chi2/coarse_grid.h"
#include "tools/chi2/stats_math.h"

namespace ptlab {
namespace {

constexpr double kTwoPi = 6.283185307179586;

// Mean over a cell of f(F) for F running linearly from a to b.
double RampMean(double a, double b) { return a + b - 1.0; }
double CosMean(double a, double b) {
  if (b - a < 1e-9) return std::cos(kTwoPi * 0.5 * (a + b));
  return (std::sin(kTwoPi * b) - std::sin(kTwoPi * a)) / (kTwoPi * (b - a));
}
double SinMean(double a, double b) {
  if (b - a < 1e-9) return std::sin(kTwoPi * 0.5 * (a + b));
  return (std::cos(kTwoPi * a) - std::cos(kTwoPi * b)) / (kTwoPi * (b - a));
}

Chi2Perturbation Along(const Chi2Result& base, const char* shape, int axis,
                       double (*mean)(double, double)) {
  const std::vector<double> cdf = Chi2MarginalCdf(base.expected, base.xres, base.yres, axis);
  Chi2Perturbation p;
  p.shape = shape;
  p.g.resize(base.expected.size());
  for (int iy = 0; iy < base.yres; ++iy) {
    for (int ix = 0; ix < base.xres; ++ix) {
      const size_t i = size_t(axis == 0 ? ix : iy);
      p.g[size_t(iy) * size_t(base.xres) + size_t(ix)] = mean(cdf[i], cdf[i + 1]);
    }
  }
  return p;
}

// Pearson's statistic of counts N q against N p is the noncentrality; its dof and critical value
// are the null test's (pooling depends on the expected counts only).
double GridPower(const std::vector<double>& q, const std::vector<double>& p, double samples,
                 double min_expected, double alpha) {
  std::vector<double> oq(q.size()), ep(p.size());
  for (size_t i = 0; i < q.size(); ++i) oq[i] = samples * q[i], ep[i] = samples * p[i];
  const PearsonResult r = PearsonChiSquare(oq, ep, min_expected);
  if (r.dof < 1) return 0.0;
  return NoncentralChiSquareSf(ChiSquareUpperQuantile(alpha, r.dof), r.dof, r.chi2);
}

// Smallest x in (lo, hi] with f(x) >= target for f increasing (hi if even f(hi) falls short):
// bisection in log space.
template <typename F>
double SmallestReaching(F f, double lo, double hi, double target) {
  if (f(hi) < target) return hi;
  for (int it = 0; it < 40; ++it) {
    const double mid = std::sqrt(lo * hi);
    (f(mid) >= target ? hi : lo) = mid;
    if (hi / lo < 1.001) break;
  }
  return hi;
}

}  // namespace

std::vector<Chi2Perturbation> Chi2SmoothPerturbations(const Chi2Result& base) {
  if (base.domain.spherical()) {
    return {Along(base, "azimuth-cos", 0, CosMean), Along(base, "azimuth-sin", 0, SinMean),
            Along(base, "polar", 1, RampMean)};
  }
  return {Along(base, "x", 0, RampMean), Along(base, "y", 1, RampMean)};
}

double Chi2AnalyticPower(const Chi2Result& base, bool defective, const Chi2Options& options,
                         const Chi2Perturbation& perturbation, double epsilon, double samples) {
  PTLAB_CHECK(perturbation.g.size() == base.expected.size() && base.samples >= 1);
  if (samples <= 0) samples = double(base.samples);
  const size_t n = base.expected.size();
  std::vector<double> p(n), q(n);
  double shift = 0;
  for (size_t i = 0; i < n; ++i) {
    p[i] = base.expected[i] / double(base.samples);
    q[i] = p[i] * (1.0 + epsilon * perturbation.g[i]);
    shift += p[i] * epsilon * perturbation.g[i];
  }
  const double z = 1.0 + shift;
  for (double& v : q) v /= z;
  const double alpha = base.alpha_each;
  auto with_absorbed = [&](std::vector<double> cells, double absorbed) {
    if (defective) cells.push_back(absorbed);
    return cells;
  };
  const double p_abs = std::max(1.0 - base.pdf_integral, 1e-300 / samples);
  double power = GridPower(with_absorbed(q, p_abs / z), with_absorbed(p, p_abs), samples,
                           options.min_expected, alpha);
  if (base.coarse_blocks > 0) {
    const Chi2CoarseGrid grid =
        MakeChi2CoarseGrid(base.expected, base.xres, base.yres, base.coarse_blocks);
    power = std::max(power, GridPower(with_absorbed(AggregateChi2Cells(grid, q), p_abs / z),
                                      with_absorbed(AggregateChi2Cells(grid, p), p_abs), samples,
                                      options.min_expected, alpha));
  }
  return power;
}

Chi2Power EstimateChi2Power(const Chi2Result& base, bool defective, const Chi2Options& options,
                            double target) {
  Chi2Power power;
  power.target = target;
  power.epsilon = 0;
  for (const Chi2Perturbation& pert : Chi2SmoothPerturbations(base)) {
    Chi2ShapePower s;
    s.shape = pert.shape;
    s.epsilon = SmallestReaching(
        [&](double e) { return Chi2AnalyticPower(base, defective, options, pert, e); }, 1e-5, 1.0,
        target);
    s.power_at_2 = Chi2AnalyticPower(base, defective, options, pert, 0.02);
    const double n = double(base.samples);
    s.samples_for_2 = n * SmallestReaching(
                              [&](double scale) {
                                return Chi2AnalyticPower(base, defective, options, pert, 0.02,
                                                         n * scale);
                              },
                              1e-3, 1e3, target);
    power.epsilon = std::max(power.epsilon, s.epsilon);
    power.power_at_2 = std::min(power.power_at_2, s.power_at_2);
    power.samples_for_2 = std::max(power.samples_for_2, s.samples_for_2);
    power.shapes.push_back(s);
  }
  return power;
}

void CheckChi2PowerBySeeds(const Chi2Subject& subject, const Chi2Options& options,
                           const Chi2Result& base, int seeds, Chi2Power* power) {
  const std::vector<Chi2Perturbation> perts = Chi2SmoothPerturbations(base);
  PTLAB_CHECK(perts.size() == power->shapes.size());
  for (size_t k = 0; k < perts.size(); ++k) {
    Chi2ShapePower& s = power->shapes[k];
    const double e = s.epsilon;
    // Keep a sample with probability (1 + ε g) / (1 + ε): the kept ones follow p (1 + ε g) / Z.
    std::vector<double> keep(perts[k].g.size());
    for (size_t i = 0; i < keep.size(); ++i) keep[i] = (1.0 + e * perts[k].g[i]) / (1.0 + e);
    s.seeds = seeds;
    s.detected = 0;
    for (int i = 0; i < seeds; ++i) {
      Chi2Options o = options;
      o.seed = options.seed + 0x9e3779b9ULL * uint64_t(i + 1);
      s.detected += !RerunChi2Thinned(subject, o, base, keep, 1.0 / (1.0 + e)).pass;
    }
  }
}

std::string FormatChi2Power(const Chi2Power& power) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), "detects a %.2g %% error with %.0f %% probability (worst of:",
                100 * power.epsilon, 100 * power.target);
  std::string s = buf;
  for (const Chi2ShapePower& shape : power.shapes) {
    std::snprintf(buf, sizeof(buf), " %s %.2g %%", shape.shape.c_str(), 100 * shape.epsilon);
    s += buf;
    if (shape.seeds > 0) {
      std::snprintf(buf, sizeof(buf), " [simulated: %d/%d]", shape.detected, shape.seeds);
      s += buf;
    }
  }
  std::snprintf(buf, sizeof(buf), "); a 2 %% error with probability %.4f; %.3g samples for 95 %%",
                power.power_at_2, power.samples_for_2);
  return s + buf;
}

}  // namespace ptlab
