// Power of the chi-square lab: the smallest smooth error of a pdf that a test detects.
#pragma once

#include <string>
#include <vector>

#include "tools/chi2/chi2.h"

namespace ptlab {

/// A low-order perturbation of a subject's distribution: its probability in fine cell c becomes
/// p_c (1 + ε g[c]) / Z (Z renormalises; absorbed mass keeps its weight), with |g| <= 1.
/// g is a function of the pdf's own marginal CDFs F_x, F_y (see Chi2MarginalCdf), averaged over
/// the cell with F linear across it, so an ε error tilts the distribution where its mass is,
/// however narrow: on planar domains the ramps 2F_x − 1 ("x") and 2F_y − 1 ("y"); on the
/// (hemi)sphere cos 2πF_φ ("azimuth-cos"), sin 2πF_φ ("azimuth-sin") and 2F_cosθ − 1 ("polar").
/// For a uniform pdf these are the ramps along x, y, cos φ, sin φ and the linear law in cos θ.
struct Chi2Perturbation {
  std::string shape;
  std::vector<double> g;  // per fine cell
};

/// The perturbation family of a test result's domain, built from its expected counts.
std::vector<Chi2Perturbation> Chi2SmoothPerturbations(const Chi2Result& base);

/// Probability that the test (fine and coarse grids, each at base.alpha_each) rejects samples
/// drawn with error ε in the given shape, from the noncentral χ² law of Pearson's statistic
/// (noncentrality N Σ (q − p)² / p over the pooled cells of each grid). The two grids' rejections
/// are positively dependent; the larger of the two is returned (a lower bound on the run's).
/// `samples` (default base.samples) asks what another sample count would give.
double Chi2AnalyticPower(const Chi2Result& base, bool defective, const Chi2Options& options,
                         const Chi2Perturbation& perturbation, double epsilon,
                         double samples = 0);

/// One shape's figures.
struct Chi2ShapePower {
  std::string shape;
  double epsilon = 0;       // smallest ε detected with the target probability (1 if none <= 1)
  double power_at_2 = 0;    // detection probability of a 2 % error
  double samples_for_2 = 0;  // samples at which a 2 % error is detected with the target probability
  int seeds = 0, detected = 0;  // the check by simulation at epsilon (seeds = 0: not run)
};

/// A subject's power: per shape, and the worst shape.
struct Chi2Power {
  double target = 0.95;
  std::vector<Chi2ShapePower> shapes;
  double epsilon = 0;        // the worst shape's ε (largest)
  double power_at_2 = 1;     // the worst shape's (smallest)
  double samples_for_2 = 0;  // the most any shape needs
};

/// The analytic power of a test result (no sampling, no pdf evaluation): bisection on ε.
/// defective: the subject's absorbed samples are an outcome of the test (Chi2Subject::defective).
Chi2Power EstimateChi2Power(const Chi2Result& base, bool defective, const Chi2Options& options,
                            double target = 0.95);

/// Checks the estimate by simulation: for every shape, `seeds` runs on fresh seeds of the
/// subject's own sampler with the error applied by rejection (RerunChi2Thinned) at the shape's
/// ε; fills seeds and detected (how many runs rejected).
void CheckChi2PowerBySeeds(const Chi2Subject& subject, const Chi2Options& options,
                           const Chi2Result& base, int seeds, Chi2Power* power);

/// "detects a 1.3 % error with 95 % probability (worst of: x 1.1 %, y 1.3 %); a 2 % error with
/// probability 0.999" and, when checked, the simulated detection counts.
std::string FormatChi2Power(const Chi2Power& power);

}  // namespace ptlab
