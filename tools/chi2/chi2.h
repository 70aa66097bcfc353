// Chi-square goodness-of-fit test of a (sample, pdf) pair: histogram vs integrated pdf, Pearson.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/vec.h"
#include "tools/chi2/domain.h"
#include "tools/chi2/stats_math.h"

namespace ptlab {

/// Maps uniforms to a point of the subject's domain. u1 is 0 unless the subject asks for 3
/// uniforms (e.g. a BSDF's lobe choice). Returns false when the sample is absorbed (no
/// direction, as a BSDF sampler may): allowed only for defective subjects (albedo < 1).
using Chi2SampleFn = std::function<bool(float u1, const Vec2f& u2, Chi2Point* p)>;

/// The same for n samples at once (plain arrays, as a SIMD kernel takes them): ok[i] = 0 marks
/// sample i absorbed. If a subject sets it, it is used instead of Chi2SampleFn.
using Chi2BatchSampleFn =
    std::function<void(const float* u1, const Vec2f* u2, int n, Chi2Point* p, uint8_t* ok)>;

/// Density at p w.r.t. the domain's measure (area, or solid angle on the sphere). Must be
/// finite and >= 0 wherever it is evaluated (the test fails otherwise).
using Chi2PdfFn = std::function<double(const Chi2Point& p)>;

/// The same for n points at once: writes density[i] for p[i]. For pdfs that are expensive to
/// call once per point (another process, a Python function over NumPy arrays). If a subject sets
/// it, it is used instead of Chi2PdfFn, and the result equals what Chi2PdfFn returning the same
/// values would give (the adaptive integration is replayed until it needs no new point).
/// Returns false when it cannot answer (a pdf program died): the test then stops and fails.
using Chi2BatchPdfFn = std::function<bool(const Chi2Point* p, int64_t n, double* density)>;

/// What a run of the subject must show: real subjects pass, deliberately broken ones fail.
enum class Chi2Expect { kPass, kFail };

/// Albedo of a defective subject whose total mass is not known in closed form: the pdf's
/// integral is then only required to be <= 1 (+ tolerance).
inline constexpr double kChi2UnknownAlbedo = std::numeric_limits<double>::quiet_NaN();

/// A test subject: a sampler and the pdf it claims, on a domain, with a name and parameters.
struct Chi2Subject {
  std::string name;    // "group/what", e.g. "warp/cosine_hemisphere", "broken/disk_linear_r"
  std::string params;  // free text shown with results, e.g. "alpha=0.1 wo=(0.6,0,0.8)"
  Chi2Domain domain;
  Chi2SampleFn sample;
  Chi2BatchSampleFn sample_batch;  // optional
  Chi2PdfFn pdf;
  Chi2BatchPdfFn pdf_batch;  // optional
  int uniform_dims = 2;      // 2, or 3 to also draw u1
  double albedo = 1.0;       // total mass of the distribution; < 1 (or unknown) = defective
  Chi2Expect expect = Chi2Expect::kPass;
  // Samples drawn = options.samples × sample_scale: > 1 for subjects whose power at the default
  // count falls short of the lab's target (a 2 % smooth error caught with 95 % probability).
  double sample_scale = 1.0;

  bool defective() const { return !(albedo == 1.0); }
};

inline constexpr uint64_t kChi2DefaultSeed = 0x9e3779b97f4a7c15ULL;

/// The PCG32 stream of a subject's samples: a hash of its name (FNV-1a, mixed).
uint64_t Chi2StreamFromName(std::string_view name);

/// How a test is run. res is the number of cells along y; x gets Chi2GridWidth(domain, res).
struct Chi2Options {
  int64_t samples = 1000000;
  int res = 51;
  uint64_t seed = kChi2DefaultSeed;  // the PCG32 stream is derived from the subject's name
  double alpha = 0.01;               // family-wise significance of the run
  int test_count = 1;          // tests in the run: Šidák gives each alpha' = SidakAlpha(...)
  double min_expected = 5.0;   // cells expecting fewer samples are pooled
  // The second, coarse test: coarse_blocks × coarse_blocks blocks of equal marginal mass (see
  // Chi2CoarseGrid), for smooth errors the fine grid dilutes over its many cells; each of the
  // two tests gets SidakAlpha(alpha', 2). 0: the fine test only, at alpha'.
  int coarse_blocks = 6;
  double integral_tol = 1e-3;  // |∫pdf - albedo| allowed
  Simpson2DOptions simpson;    // the nested cell integration (outer x, inner y)
  int64_t max_evals_per_cell = 200000;
};

/// Everything a test found. Cell (ix, iy) is index iy * xres + ix; iy grows with y (cosθ).
struct Chi2Result {
  std::string name;
  Chi2Domain domain;
  int xres = 0, yres = 0;
  std::vector<double> observed;  // sample counts per cell
  std::vector<double> expected;  // samples × ∫ pdf over the cell
  int64_t samples = 0;
  int64_t absorbed = 0;     // sampler returned no point
  double pdf_integral = 0;  // ∫ pdf over the whole domain
  double chi2 = 0;
  int dof = 0;
  double p_value = std::numeric_limits<double>::quiet_NaN();
  double alpha = 0;  // Šidák-corrected per-test significance (the subject's, both grids)
  // The coarse test (blocks of equal mass; coarse_blocks = 0: not run) and the level each of the
  // two tests is held to: alpha_each = SidakAlpha(alpha, 2) (alpha when there is one test).
  int coarse_blocks = 0;
  double coarse_chi2 = 0;
  int coarse_dof = 0;
  double coarse_p_value = std::numeric_limits<double>::quiet_NaN();
  double alpha_each = 0;
  int pooled_cells = 0;
  int64_t pdf_evals = 0;
  bool pass = false;                  // the null hypothesis was accepted and every check held
  std::vector<std::string> failures;  // why it was rejected (checks first, then χ²)
  std::vector<std::string> notes;     // information (pooling, exhausted integration budget)
};

/// Runs the test: histograms options.samples samples on the grid, integrates the pdf over every
/// cell (nested adaptive Simpson), pools small cells and applies Pearson's χ² at the Šidák
/// level. Also fails on non-finite or out-of-domain samples, absorbed samples of a
/// non-defective subject, samples in cells of zero expected mass, non-finite or negative pdf
/// values, and a pdf integral off the albedo by more than options.integral_tol.
/// A defective subject's absorbed samples are one more Pearson cell (expected N (1 - ∫pdf)).
/// Preconditions: samples >= 1, res >= 1, test_count >= 1, 0 < alpha < 1.
Chi2Result RunChi2Test(const Chi2Subject& subject, const Chi2Options& options);

/// The test again on fresh samples (options.seed), thinned by rejection: a sample in fine cell c
/// is kept with probability keep[c], an absorbed one with keep_absorbed; judged against `base`'s
/// expected counts scaled to the samples kept (no pdf evaluation). The power estimate uses it
/// to give a sampler a known error. keep.size() == base.observed.size(), values in [0, 1].
Chi2Result RerunChi2Thinned(const Chi2Subject& subject, const Chi2Options& options,
                            const Chi2Result& base, const std::vector<double>& keep,
                            double keep_absorbed);

/// True when the result is what the subject expects (real: passed; broken: rejected).
inline bool Chi2AsExpected(const Chi2Subject& subject, const Chi2Result& result) {
  return result.pass == (subject.expect == Chi2Expect::kPass);
}

/// One line: verdict (PASS / FAIL for real subjects, XFAIL = rejected as expected / XPASS for
/// broken ones), name, χ², dof, p, alpha' and the pdf's integral ("mass"); then one indented
/// line per failure reason.
std::string FormatChi2Result(const Chi2Subject& subject, const Chi2Result& result);

}  // namespace ptlab
