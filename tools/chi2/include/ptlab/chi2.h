// ptlab's statistical lab for samplers written outside ptlab: chi-square and t-tests (public API).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

// Only these declarations are exported from libptlab_chi2; everything else stays inside it.
#if defined(PTLAB_CHI2_BUILDING)
#define PTLAB_CHI2_API __attribute__((visibility("default")))
#else
#define PTLAB_CHI2_API
#endif

namespace ptlab::chi2 {

/// Ok, or an error message saying what was wrong and what was expected.
class Status {
 public:
  static Status Ok() { return Status(); }
  static Status Error(std::string message) {
    Status s;
    s.ok_ = false;
    s.message_ = std::move(message);
    return s;
  }
  bool ok() const { return ok_; }
  const std::string& message() const { return message_; }

 private:
  bool ok_ = true;
  std::string message_;
};

enum class DomainKind {
  kBox,         // (x, y) in [x0, x1] × [y0, y1]; densities per unit area
  kDisk,        // unit disk x² + y² <= 1; densities per unit area
  kSphere,      // unit directions (x, y, z); densities per steradian
  kHemisphere,  // unit directions with z >= 0; densities per steradian
};

/// Where samples live. Planar domains have 2-D points (x, y), spherical ones 3-D unit vectors.
struct Domain {
  DomainKind kind = DomainKind::kBox;
  double x0 = 0, y0 = 0, x1 = 1, y1 = 1;  // the box's corners (box only)

  static Domain Square() { return {}; }
  static Domain Box(double x0, double y0, double x1, double y1) {
    return {DomainKind::kBox, x0, y0, x1, y1};
  }
  static Domain Disk() { return {DomainKind::kDisk, -1, -1, 1, 1}; }
  static Domain Sphere() { return {DomainKind::kSphere}; }
  static Domain Hemisphere() { return {DomainKind::kHemisphere}; }
  /// Coordinates per point: 2 on the square, box and disk, 3 on the sphere and hemisphere.
  int dims() const {
    return kind == DomainKind::kSphere || kind == DomainKind::kHemisphere ? 3 : 2;
  }
};

/// Parses "square", "disk", "sphere", "hemisphere" or "box:x0,y0,x1,y1" (x0 < x1, y0 < y1).
PTLAB_CHI2_API Status ParseDomain(const std::string& text, Domain* domain);

/// "square", "disk", "sphere", "hemisphere" or "box:x0,y0,x1,y1".
PTLAB_CHI2_API std::string DomainName(const Domain& domain);

/// A sample point: (x, y, 0) on planar domains, a unit direction on spherical ones.
struct Point {
  float x = 0, y = 0, z = 0;
};

/// Maps n rows of uniforms in [0, 1) (row i is u[i * uniform_dims ...]) to n points. Called with
/// all the test's samples at once (in chunks of at most 2²² rows). A non-ok status stops the test
/// and is returned by Test.
using SampleFn = std::function<Status(const float* u, int64_t n, int uniform_dims, Point* points)>;

/// Writes the density at each of n points (per unit area, or per steradian on the sphere).
/// Called a few times per test with every point the adaptive integration needs next. A non-ok
/// status stops the test and is returned by Test.
using PdfFn = std::function<Status(const Point* points, int64_t n, double* densities)>;

/// What is tested: a sampler and the pdf it claims, on a domain.
struct Subject {
  std::string name = "sampler";  // names the images; with the seed, selects the random stream
  Domain domain;
  int uniform_dims = 2;  // uniforms per sample: 1 to 8
  SampleFn sample;
  PdfFn pdf;
};

inline constexpr uint64_t kDefaultSeed = 0x9e3779b97f4a7c15ULL;

/// How a test is run: samples, res × res cells (2·res × res in (φ, cos θ) on the sphere),
/// significance alpha for a run of test_count tests (Šidák-corrected per test).
struct Options {
  int64_t samples = 1000000;
  int res = 51;
  uint64_t seed = kDefaultSeed;
  double alpha = 0.01;
  int test_count = 1;
  double integral_tol = 1e-3;  // |∫pdf − 1| allowed
  std::string images_dir;      // non-empty: write <dir>/<name>.png and .csv (see WriteImages)
  // The second test on the same samples: coarse_blocks² blocks of equal marginal mass, for
  // smooth errors; each test at 1 − (1 − α′)^(1/2). 0: the fine test only, at α′.
  int coarse_blocks = 6;
  // Also estimate the test's power: the smallest smooth error of the pdf (pdf·(1 + ε g), g a
  // ramp or harmonic of the pdf's marginal CDFs) detected with 95 % probability (Result::power_*).
  bool power = false;
};

/// What a test found. Cell (ix, iy) is index iy * xres + ix; iy grows with y (cos θ).
struct Result {
  Domain domain;
  bool passed = false;  // Pearson's test accepted the pdf and every check held
  double chi2 = 0;
  int dof = 0;
  double p_value = std::numeric_limits<double>::quiet_NaN();
  double alpha = 0;         // Šidák-corrected per-test significance
  double pdf_integral = 0;  // ∫ pdf over the domain
  int64_t samples = 0;
  int64_t pdf_evals = 0;
  int xres = 0, yres = 0;
  std::vector<double> observed, expected;
  std::vector<std::string> failures;  // why it was rejected
  std::vector<std::string> notes;     // information (pooled cells, pdf calls)
  // The coarse test (coarse_blocks = 0: not run) and the level each of the two tests is held to.
  int coarse_blocks = 0;
  double coarse_chi2 = 0;
  int coarse_dof = 0;
  double coarse_p_value = std::numeric_limits<double>::quiet_NaN();
  double alpha_each = 0;
  // With Options::power: the smallest error ε detected with 95 % probability (worst shape), the
  // probability of detecting a 2 % error, the samples that would detect it with 95 %, and the
  // report line ("detects a 1.3 % error with 95 % probability (worst of: ...)"). NaN/empty without.
  double power_epsilon = std::numeric_limits<double>::quiet_NaN();
  double power_at_2 = std::numeric_limits<double>::quiet_NaN();
  double power_samples_for_2 = std::numeric_limits<double>::quiet_NaN();
  std::string power_report;
};

/// Draws options.samples rows of uniforms (PCG32, seeded by options.seed and the subject's name,
/// the same stream ptlab's own `chi2` tool uses for a subject of that name), maps them with
/// subject.sample, and tests the points against subject.pdf: histogram vs the pdf integrated
/// over every cell (adaptive Simpson), Pearson's χ² with cells expecting < 5 samples pooled.
/// Errors (status not ok, *result untouched): bad options or subject, a sample that is not
/// finite or not in the domain, or a callable that returned an error.
PTLAB_CHI2_API Status Test(const Subject& subject, const Options& options, Result* result);

/// The same test on points drawn elsewhere (n points; the file-based route of `chi2 check`).
PTLAB_CHI2_API Status TestPoints(const std::string& name, const Domain& domain, const Point* points,
                                 int64_t n, const PdfFn& pdf, const Options& options,
                                 Result* result);

/// Writes <dir>/<name>.png (observed | expected | residual (o−e)/√e heat maps) and <dir>/<name>.csv
/// (the cells), creating dir; name has characters outside [A-Za-z0-9._-] replaced by '_'.
PTLAB_CHI2_API Status WriteImages(const std::string& dir, const std::string& name,
                                  const Result& result);

/// One line: PASS/FAIL, name, χ², dof, p, α′ and ∫pdf; then one indented line per failure.
PTLAB_CHI2_API std::string FormatResult(const std::string& name, const Result& result);

/// Outcome of a two-tailed t-test at a Šidák-corrected level.
struct TTestResult {
  bool passed = false;  // equal means accepted: p >= alpha
  double t = 0, dof = 0;
  double p_value = std::numeric_limits<double>::quiet_NaN();
  double alpha = 0;  // Šidák-corrected per-test level
  double mean = 0, variance = 0;
  int64_t n = 0;
};

/// One-sample Student t-test of H0: E[X] = reference on n >= 2 finite values (Nori's test: the
/// variance floored at 1e-5), at SidakAlpha(alpha, test_count).
PTLAB_CHI2_API Status OneSampleTTest(const double* values, int64_t n, double reference,
                                     double alpha, int test_count, TTestResult* result);

/// Welch's two-sample t-test of H0: E[X1] = E[X2] on n1, n2 >= 2 finite values.
PTLAB_CHI2_API Status WelchTTest(const double* values1, int64_t n1, const double* values2,
                                 int64_t n2, double alpha, int test_count, TTestResult* result);

}  // namespace ptlab::chi2
