// Chi-square test driver: sampling histogram, per-cell pdf integration, checks and verdict.
#include "tools/chi2/chi2.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "engine/core/check.h"
#include "engine/core/rng.h"
#include "tools/chi2/chi2_format.h"
#include "tools/chi2/chi2_integration.h"
#include "tools/chi2/coarse_grid.h"

namespace ptlab {
namespace {

// Samples are drawn and mapped in chunks so a batch (SIMD) sampler sees plain arrays.
constexpr int kChunk = 256;

using chi2_internal::Format;
using chi2_internal::FormatPoint;
using chi2_internal::IntegrateCells;
using chi2_internal::IntegrateWithBatchPdf;

// Thinning of the samples by rejection (RerunChi2Thinned): keep probability per fine cell.
struct Thinning {
  const std::vector<double>* keep = nullptr;
  double keep_absorbed = 1.0;
};

// Draws `samples` samples and bins them (thinned, when `thin` is given, with a second stream).
// Fills observed, samples, absorbed and the failure reasons of samples that are not finite or
// not in the domain.
void TabulateSamples(const Chi2Subject& subject, const Chi2Options& options, int64_t samples,
                     const Thinning* thin, Chi2Result* r) {
  Pcg32 rng(options.seed, Chi2StreamFromName(subject.name));
  Pcg32 thin_rng(options.seed ^ 0x5bd1e995ULL, Chi2StreamFromName(subject.name) + 1);
  int64_t kept = 0;
  const Chi2Domain& d = subject.domain;
  const double sx = r->xres / (d.x1 - d.x0), sy = r->yres / (d.y1 - d.y0);
  float u1[kChunk];
  Vec2f u2[kChunk];
  Chi2Point p[kChunk];
  uint8_t ok[kChunk];
  int64_t non_finite = 0, outside = 0;
  Chi2Point first_non_finite, first_outside;
  for (int64_t done = 0; done < samples; done += kChunk) {
    const int n = int(std::min<int64_t>(kChunk, samples - done));
    for (int i = 0; i < n; ++i) {
      u1[i] = subject.uniform_dims >= 3 ? rng.NextFloat() : 0.0f;
      u2[i].x = rng.NextFloat();
      u2[i].y = rng.NextFloat();
    }
    if (subject.sample_batch) {
      subject.sample_batch(u1, u2, n, p, ok);
    } else {
      for (int i = 0; i < n; ++i) ok[i] = subject.sample(u1[i], u2[i], &p[i]) ? 1 : 0;
    }
    for (int i = 0; i < n; ++i) {
      if (!ok[i]) {
        if (thin && !(double(thin_rng.NextFloat()) < thin->keep_absorbed)) continue;
        ++r->absorbed, ++kept;
        continue;
      }
      if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y) || !std::isfinite(p[i].z)) {
        if (non_finite++ == 0) first_non_finite = p[i];
        continue;
      }
      if (!Chi2Contains(d, p[i])) {
        if (outside++ == 0) first_outside = p[i];
        continue;
      }
      const Chi2Param q = Chi2ToParam(d, p[i]);
      const int ix = std::clamp(int((q.x - d.x0) * sx), 0, r->xres - 1);
      const int iy = std::clamp(int((q.y - d.y0) * sy), 0, r->yres - 1);
      const size_t c = size_t(iy) * size_t(r->xres) + size_t(ix);
      if (thin && !(double(thin_rng.NextFloat()) < (*thin->keep)[c])) continue;
      r->observed[c] += 1.0;
      ++kept;
    }
  }
  // Non-finite and outside samples count as kept (they fail the test anyway).
  r->samples = thin ? kept + non_finite + outside : samples;
  if (non_finite > 0) {
    r->failures.push_back(Format("%.0f non-finite samples", double(non_finite)) + " (first " +
                          FormatPoint(d, first_non_finite) + ")");
  }
  if (outside > 0) {
    r->failures.push_back(Format("%.0f samples outside the domain", double(outside)) + " (first " +
                          FormatPoint(d, first_outside) + ", domain " + Chi2DomainName(d) + ")");
  }
  if (r->absorbed > 0 && !subject.defective()) {
    r->failures.push_back(
        Format("the sampler absorbed %.0f samples but the subject is not "
               "defective (albedo 1)",
               double(r->absorbed)));
  }
}

}  // namespace

uint64_t Chi2StreamFromName(std::string_view name) {
  uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a, 64 bit
  for (char c : name) h = (h ^ uint8_t(c)) * 0x100000001b3ULL;
  return MixBits(h);
}

namespace {

// Pearson's test of one grid at level alpha: appends the failure and returns the result.
PearsonResult PearsonOnGrid(const std::vector<double>& observed,
                            const std::vector<double>& expected, double min_expected,
                            double alpha, const char* grid, Chi2Result* r, double* p_value) {
  const PearsonResult pearson = PearsonChiSquare(observed, expected, min_expected);
  *p_value = std::numeric_limits<double>::quiet_NaN();
  if (pearson.dof < 1) {
    r->failures.push_back(Format("too few cells with expected mass for a test (dof %.0f)",
                                 double(pearson.dof)) + " on the " + grid + " grid");
    return pearson;
  }
  *p_value = ChiSquarePValue(pearson.chi2, pearson.dof);
  if (!(*p_value >= alpha)) {
    r->failures.push_back(Format("chi-square rejects the pdf: p = %.4g < alpha' = %.4g",
                                 *p_value, alpha) + " on the " + grid + " grid");
  }
  return pearson;
}

// The χ² part of the verdict from r's observed and expected counts (expected = samples × cell
// probability), r->absorbed and r->pdf_integral: the fine test, then the coarse one.
void JudgeCounts(const Chi2Subject& subject, const Chi2Options& options, Chi2Result* r) {
  // Pearson over the cells, plus the absorbed samples as one more outcome of a defective
  // distribution (their expected count is the mass the pdf leaves out).
  std::vector<double> observed = r->observed, expected = r->expected;
  if (subject.defective()) {
    observed.push_back(double(r->absorbed));
    // 1 − ∫pdf is only known to the integration's accuracy (~1e-6): a subject that almost
    // never absorbs may come out <= 0. Treat that as a tiny cell (it gets pooled), not an
    // impossible one; a sampler that really drops samples still fails in the pooled cell.
    expected.push_back(std::max((1.0 - r->pdf_integral) * double(r->samples), 1e-300));
  }
  r->coarse_blocks = options.coarse_blocks;
  r->alpha_each = options.coarse_blocks > 0 ? SidakAlpha(r->alpha, 2) : r->alpha;
  const PearsonResult pearson = PearsonOnGrid(observed, expected, options.min_expected,
                                              r->alpha_each, "fine", r, &r->p_value);
  r->chi2 = pearson.chi2;
  r->dof = pearson.dof;
  r->pooled_cells = pearson.pooled_cells;
  if (pearson.pooled_cells > 0) {
    r->notes.push_back(Format("pooled %.0f cells with expected count < %g into one",
                              double(pearson.pooled_cells), options.min_expected));
  }
  if (pearson.zero_expected_cells > 0) {
    r->failures.push_back(Format("%.0f samples fell in %.0f cells of zero expected mass",
                                 pearson.zero_expected_observed,
                                 double(pearson.zero_expected_cells)));
  }
  if (options.coarse_blocks > 0) {
    const Chi2CoarseGrid grid =
        MakeChi2CoarseGrid(r->expected, r->xres, r->yres, options.coarse_blocks);
    std::vector<double> coarse_obs = AggregateChi2Cells(grid, r->observed);
    std::vector<double> coarse_exp = AggregateChi2Cells(grid, r->expected);
    if (subject.defective()) {
      coarse_obs.push_back(observed.back());
      coarse_exp.push_back(expected.back());
    }
    const PearsonResult coarse = PearsonOnGrid(coarse_obs, coarse_exp, options.min_expected,
                                               r->alpha_each, "coarse", r, &r->coarse_p_value);
    r->coarse_chi2 = coarse.chi2;
    r->coarse_dof = coarse.dof;
  }
  r->pass = r->failures.empty();
}

int64_t SubjectSamples(const Chi2Subject& subject, const Chi2Options& options) {
  return std::max<int64_t>(1, std::llround(double(options.samples) * subject.sample_scale));
}

}  // namespace

Chi2Result RunChi2Test(const Chi2Subject& subject, const Chi2Options& options) {
  PTLAB_CHECK(options.samples >= 1 && options.res >= 1 && options.test_count >= 1);
  PTLAB_CHECK(options.alpha > 0 && options.alpha < 1 && options.coarse_blocks >= 0);
  PTLAB_CHECK((subject.pdf || subject.pdf_batch) && (subject.sample || subject.sample_batch));
  PTLAB_CHECK(subject.sample_scale > 0);
  Chi2Result r;
  r.name = subject.name;
  r.domain = subject.domain;
  r.xres = Chi2GridWidth(subject.domain, options.res);
  r.yres = options.res;
  const size_t cells = size_t(r.xres) * size_t(r.yres);
  r.observed.assign(cells, 0.0);
  r.expected.assign(cells, 0.0);
  r.alpha = SidakAlpha(options.alpha, options.test_count);

  const int64_t samples = SubjectSamples(subject, options);
  TabulateSamples(subject, options, samples, nullptr, &r);

  Chi2Options scaled = options;
  scaled.samples = samples;
  const double total = subject.pdf_batch
                           ? IntegrateWithBatchPdf(subject, scaled, &r)
                           : IntegrateCells(subject, subject.pdf, scaled, &r, nullptr);
  r.pdf_integral = total;

  if (std::isnan(subject.albedo)) {
    if (!(total <= 1.0 + options.integral_tol)) {
      r.failures.push_back(
          Format("the pdf integrates to %.6f over the domain, more than 1 "
                 "(tolerance %g)",
                 total, options.integral_tol));
    }
  } else if (!(std::fabs(total - subject.albedo) <= options.integral_tol)) {
    r.failures.push_back(
        Format("the pdf integrates to %.6f over the domain, expected %g "
               "(tolerance %g)",
               total, subject.albedo, options.integral_tol));
  }
  JudgeCounts(subject, options, &r);
  return r;
}

Chi2Result RerunChi2Thinned(const Chi2Subject& subject, const Chi2Options& options,
                            const Chi2Result& base, const std::vector<double>& keep,
                            double keep_absorbed) {
  PTLAB_CHECK(keep.size() == base.observed.size() && base.samples >= 1);
  Chi2Result r;
  r.name = base.name;
  r.domain = base.domain;
  r.xres = base.xres;
  r.yres = base.yres;
  r.observed.assign(base.observed.size(), 0.0);
  r.alpha = SidakAlpha(options.alpha, options.test_count);
  r.pdf_integral = base.pdf_integral;
  const Thinning thin{&keep, keep_absorbed};
  TabulateSamples(subject, options, SubjectSamples(subject, options), &thin, &r);
  r.expected = base.expected;
  for (double& e : r.expected) e *= double(r.samples) / double(base.samples);
  JudgeCounts(subject, options, &r);
  return r;
}

std::string FormatChi2Result(const Chi2Subject& subject, const Chi2Result& result) {
  const bool broken = subject.expect == Chi2Expect::kFail;
  const char* verdict =
      broken ? (result.pass ? "XPASS" : "XFAIL") : (result.pass ? "PASS" : "FAIL");
  char buf[512];
  std::snprintf(buf, sizeof(buf),
                "%-5s  %-40s chi2=%-10.1f dof=%-5d p=%-10.4g alpha'=%-9.3g mass=%.6f", verdict,
                result.name.c_str(), result.chi2, result.dof, result.p_value, result.alpha,
                result.pdf_integral);
  std::string s = buf;
  if (result.coarse_blocks > 0) {
    std::snprintf(buf, sizeof(buf), "  coarse %dx%d: chi2=%.1f dof=%d p=%.4g (each grid at %.3g)",
                  result.coarse_blocks, result.coarse_blocks, result.coarse_chi2,
                  result.coarse_dof, result.coarse_p_value, result.alpha_each);
    s += buf;
  }
  if (!subject.params.empty()) s += "  [" + subject.params + "]";
  for (const std::string& f : result.failures) s += "\n       - " + f;
  return s;
}

}  // namespace ptlab