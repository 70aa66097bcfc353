// Runs Nori's statistical test files (ttest, chi2test) as written: one verdict per test.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "engine/core/status.h"
#include "engine/io/nori_test_loader.h"

namespace ptlab {

enum class NoriVerdict : uint8_t { kPass, kFail, kSkip };

/// "PASS", "FAIL" or "SKIP".
const char* NoriVerdictName(NoriVerdict verdict);

/// One test of a file: a (BSDF, angle) or scene t-test, or a (BSDF, incident direction) χ² test.
struct NoriTestCase {
  std::string name;  // "bsdf 1 microfacet (line 7) at 45 deg", "scene 3 path_mis (line 57)", ...
  NoriVerdict verdict = NoriVerdict::kSkip;
  int64_t samples = 0;
  // t-tests: the estimate (mean luminance), the reference and the sample variance.
  double estimate = std::numeric_limits<double>::quiet_NaN();
  double reference = std::numeric_limits<double>::quiet_NaN();
  double variance = std::numeric_limits<double>::quiet_NaN();
  // t (t-tests) or χ² (chi2tests), its degrees of freedom, two-tailed / upper p-value and the
  // Šidák-corrected level the p-value was compared with.
  double statistic = std::numeric_limits<double>::quiet_NaN();
  double dof = 0;
  double p_value = std::numeric_limits<double>::quiet_NaN();
  double alpha = 0;
  std::vector<std::string> details;  // why it failed or was skipped; χ² notes
};

/// Everything one file's run found.
struct NoriTestReport {
  std::string path;
  NoriTestType type = NoriTestType::kTTest;
  NoriTestProperties properties;  // as loaded (sample_count resolved)
  int test_count = 0;             // tests in the file: the n of the Šidák correction
  /// Non-empty when the whole file was skipped: it uses a feature the loader or renderer does
  /// not support yet (then `cases` is empty).
  std::string skip_reason;
  std::vector<NoriTestCase> cases;
  double seconds = 0;  // wall time of the run, for the CLI (never checked by tests)

  int Count(NoriVerdict v) const;
  /// kFail if any case failed, else kSkip if the file or any case was skipped, else kPass.
  NoriVerdict Verdict() const;
};

struct NoriTestOptions {
  uint64_t seed = 1;  // every test has its own PCG32 streams derived from (seed, test index)
  /// Worker threads of scene t-tests. Results do not depend on it: samples are drawn from
  /// per-sample streams and accumulated in fixed chunks merged in a fixed order.
  int threads = 1;
  /// > 0: replaces the file's sampleCount (for quick experiments; the stat tests use the file's).
  int64_t sample_count_override = 0;
  /// Dielectric BSDF t-tests weight refraction by (η_o/η_i)² (DielectricFlags
  /// kDielectricScaleRadiance): Nori's (ETH) dielectric sample() does, and its ttest-dielectric
  /// references (2.18 > 1 leaving the denser medium) show it. False = the scene default
  /// (unscaled, weight 1 on both lobes).
  bool dielectric_scale_radiance = true;
  /// Non-empty: a failing χ² test writes its heat maps and table here (WriteChi2Report).
  std::string chi2_report_dir;
  /// When set, only the cases (counted in file order from 0) for which it returns true are run
  /// and reported, e.g. one MPI rank's share; every case keeps its own random streams, so a
  /// case's result does not depend on which others run.
  std::function<bool(size_t case_index)> runs_case;
  /// Called after each case completes (e.g. to print it at once).
  std::function<void(const NoriTestCase&)> on_case;
};

/// Runs every test of a loaded file with Nori's semantics (src/ttest.cpp, src/chi2test.cpp):
/// - ttest of BSDFs: for each BSDF (file order) and each angle θ, sampleCount BSDF samples for
///   wo = (sin θ, 0, cos θ) in the local frame; each sample contributes the luminance of its
///   weight f·|cos θi|/pdf (0 when no direction is sampled); the mean is the directional albedo,
///   compared with references[b · angles + i].
/// - ttest of scenes: sampleCount primary rays through uniformly jittered image positions
///   (lens sample for thin lenses) of each scene's camera; each contributes the luminance of the
///   scene integrator's Li (no pixel filter; a 1×1 image gives the pixel's value).
/// - each t-test: OneSampleTTest (variance floored at 1e-5 as Nori does) at SidakAlpha(
///   significanceLevel, number of references).
/// - chi2test: for each BSDF, testCount incident directions wo with cos θ and φ/2π uniform
///   (upper hemisphere), each a RunChi2Test of BsdfSampleDirection against BsdfPdf on
///   Chi2Domain::Sphere() with resolution × 2·resolution cells, sampleCount samples,
///   minExpFrequency pooling and Šidák over testCount × BSDFs tests. The subject is defective
///   (samples without a direction are absorbed; the pdf's mass is only bounded by 1).
/// BSDFs the renderer cannot shade and scenes UnsupportedFeature() rejects are skipped cases;
/// delta BSDFs in a chi2test are skipped (they have no density to test).
NoriTestReport RunNoriTestFile(const NoriTestFile& file, const NoriTestOptions& options);

/// Loads `path` with LoadNoriTestFile and runs it. A load error that says a feature is "not
/// supported yet" gives a skipped report; any other load error is returned.
StatusOr<NoriTestReport> RunNoriTest(const std::string& path, const NoriTestOptions& options);

/// One line: verdict, name, estimate vs reference (t-tests), statistic, dof, p, α'; then one
/// indented line per detail when `details` is set or the case did not pass.
std::string FormatNoriTestCase(const NoriTestCase& c, bool details = false);

/// Whether a load error says the file needs a feature that is "not supported yet" (a skip).
bool IsUnsupportedFeatureMessage(const std::string& message);
/// The first line `ptlab test` prints for a loaded file: type, tests, samples, significance.
std::string FormatNoriTestHeader(const NoriTestFile& file);
/// The last line `ptlab test` prints: the file's verdict and counts.
std::string FormatNoriTestSummary(const NoriTestReport& report);
/// Exit status of `ptlab test` for a report: 0 pass, 1 fail, 2 skipped.
int NoriTestExitCode(const NoriTestReport& report);

/// `ptlab test FILE.xml`: runs the file on all cores, prints one verdict line per test as it
/// completes and a summary. Returns the exit status: 0 every test passed, 1 a test failed,
/// 2 a test (or the file) was skipped because a feature is not supported yet, 3 the file
/// cannot be read or is invalid. `verbose` adds variance / χ² notes to every line.
int RunNoriTestCommand(const std::string& path, bool verbose);

}  // namespace ptlab
