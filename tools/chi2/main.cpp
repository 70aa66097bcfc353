// chi2 CLI: lists and runs the chi-square lab's subjects; exit code = verdict of the run.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "tools/chi2/check/check_command.h"
#include "tools/chi2/chi2.h"
#include "tools/chi2/power.h"
#include "tools/chi2/report.h"
#include "tools/chi2/subjects.h"
#include "tools/cli_checks.h"
#include "tools/common/exit_codes.h"
#include "tools/common/output_guard.h"
#include "tools/mpi/mpi_session.h"

namespace {

using ptlab::kExitFailed;
using ptlab::kExitOk;
using ptlab::kExitRunFailed;
using ptlab::kExitUsage;

constexpr const char* kFooter =
    R"(Each test histograms the subject's samples on a grid (res x res cells; 2res x res in
(phi, cos theta) on the sphere), integrates its pdf over every cell (adaptive Simpson), pools
cells expecting < 5 samples and applies Pearson's chi-square test. It also fails on samples that
are non-finite, outside the domain or in cells of zero expected mass, on non-finite or negative
pdf values, and on a pdf integral off 1 (or the subject's albedo) by more than 1e-3.
Significance: alpha for the whole run, Sidak-corrected per test: alpha' = 1 - (1 - alpha)^(1/n).
Verdicts: PASS / FAIL for real subjects; XFAIL (rejected as expected) / XPASS for "broken/..."
subjects, which exist to prove the test can fail.
Each subject is tested twice on the same samples: on the fine grid (local errors) and on a
coarse grid of 6x6 blocks of equal marginal mass (smooth errors), each at alpha'' = 1 - (1 - alpha')^(1/2).
--power: the smallest smooth error (pdf x (1 + eps g), g a low-order ramp or harmonic of the pdf's
own marginal CDFs) the test detects with 95 % probability, from the noncentral chi-square law;
--power-seeds S also checks it by S runs of the sampler with the error applied by rejection.
Exit codes (tools/common/exit_codes.h, shared with ptlab and imgdiff): 0 every subject as
  expected (real ones pass, broken ones fail), 1 otherwise, 2 bad usage or unknown subject,
  3 the image directory or an image could not be written.
`chi2 check --help`: test samples from a file against a pdf program or grid (any language).)";

// What --power and --power-seeds ask for (power_seeds: simulated runs per shape, 0 = none).
struct PowerRequest {
  bool power = false;
  int seeds = 0;
};

// The power line of a subject's result ("" unless asked for; broken subjects have none).
std::string PowerText(const ptlab::Chi2Subject& s, const ptlab::Chi2Options& options,
                      const ptlab::Chi2Result& result, const PowerRequest& request) {
  if (!request.power || s.expect != ptlab::Chi2Expect::kPass) return "";
  ptlab::Chi2Power power = ptlab::EstimateChi2Power(result, s.defective(), options);
  if (request.seeds > 0) ptlab::CheckChi2PowerBySeeds(s, options, result, request.seeds, &power);
  return "       power: " + ptlab::FormatChi2Power(power) + "\n";
}

// One subject's verdict line (and notes): what a rank sends to rank 0.
std::string RunOne(const ptlab::Chi2Subject& s, const ptlab::Chi2Options& options,
                   const std::string& images_dir, bool verbose, const PowerRequest& power,
                   bool* as_expected) {
  const ptlab::Chi2Result result = ptlab::RunChi2Test(s, options);
  std::string text = ptlab::FormatChi2Result(s, result) + "\n" +
                     PowerText(s, options, result, power);
  if (verbose) {
    for (const std::string& note : result.notes) text += "       . " + note + "\n";
    text += "       . " + std::to_string(result.pdf_evals) + " pdf evaluations\n";
  }
  *as_expected = ptlab::Chi2AsExpected(s, result);
  if (!images_dir.empty()) {
    const ptlab::Status status = ptlab::WriteChi2Report(images_dir, result);
    if (!status.ok()) text += "error: " + status.message() + "\n";
  }
  return text;
}

// The subjects of the run shared among MPI ranks (i % ranks == rank); rank 0 prints every line
// in subject order, so the output equals a one-process run's.
int RunOverRanks(const ptlab::mpi::Session& mpi,
                 const std::vector<const ptlab::Chi2Subject*>& selected,
                 const ptlab::Chi2Options& options, const std::string& images_dir, bool verbose,
                 const PowerRequest& power) {
  if (mpi.root())
    std::printf(
        "chi2: %d tests, %lld samples, res %d, seed %llu, alpha %g (alpha' = %.3g per test), "
        "%d ranks\n",
        options.test_count, static_cast<long long>(options.samples), options.res,
        static_cast<unsigned long long>(options.seed), options.alpha,
        ptlab::SidakAlpha(options.alpha, options.test_count), mpi.size());
  // The verdict travels as the text's first character.
  const std::vector<std::string> texts = mpi.MapInOrder(selected.size(), [&](size_t i) {
    bool ok = false;
    const std::string text = RunOne(*selected[i], options, images_dir, verbose, power, &ok);
    return (ok ? "+" : "-") + text;
  });
  if (!mpi.root()) return kExitOk;  // rank 0 gives the run's exit status
  int as_expected = 0, unexpected = 0, image_errors = 0;
  for (const std::string& t : texts) {
    std::fputs(t.c_str() + 1, stdout);
    (t[0] == '+' ? as_expected : unexpected)++;
    image_errors += t.find("\nerror: ") != std::string::npos;
  }
  std::printf("chi2: %d as expected, %d not: %s\n", as_expected, unexpected,
              unexpected == 0 ? "PASS" : "FAIL");
  if (image_errors > 0) return kExitRunFailed;
  return unexpected == 0 ? kExitOk : kExitFailed;
}

}  // namespace

int main(int argc, char** argv) {
  // `chi2 check ...` tests samples from a file (any language's sampler); see check_command.h.
  if (argc >= 2 && std::string(argv[1]) == "check")
    return ptlab::RunCheckCommand(argc - 1, argv + 1);
  // Under mpirun the subjects are shared among the ranks; rank 0 prints them in order.
  const ptlab::mpi::Session mpi(&argc, &argv);
  CLI::App app{"chi2: chi-square goodness-of-fit tests of sampling routines against their pdfs"};
  app.footer(kFooter);
  std::vector<std::string> names;
  bool list = false, all = false, verbose = false;
  std::string images_dir;
  ptlab::Chi2Options options;
  app.add_option("NAME", names, "subjects to run (see --list)");
  app.add_flag("--list", list, "list the subjects and exit");
  app.add_flag("--all", all, "run every subject");
  app.add_flag("-v,--verbose", verbose, "also print notes (pooling, integration cost)");
  app.add_option("--samples", options.samples, "samples per test")
      ->check(CLI::Range(int64_t{1}, int64_t{1} << 40))
      ->capture_default_str();
  app.add_option("--res", options.res, "grid cells along y (cos theta); x gets 2x on the sphere")
      ->check(CLI::Range(2, 4096))
      ->capture_default_str();
  app.add_option("--seed", options.seed, "PCG32 seed (the stream comes from the subject name)")
      ->check(ptlab::UnsignedDecimal())
      ->capture_default_str();
  app.add_option("--alpha", options.alpha, "significance level of the whole run")
      ->check(ptlab::FiniteRange(1e-12, 0.5))
      ->capture_default_str();
  PowerRequest power;
  app.add_flag("--power", power.power,
               "also print the smallest smooth pdf error each subject detects (95 %)");
  app.add_option("--power-seeds", power.seeds,
                 "check --power by this many simulated runs per error shape")
      ->check(CLI::Range(0, 10000));
  app.add_option("--coarse", options.coarse_blocks,
                 "coarse grid blocks per axis (0: fine grid only)")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  app.add_option("--images", images_dir,
                 "write <DIR>/<name>.png (observed | expected | difference) and .csv per test");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }

  const ptlab::Chi2Registry registry = ptlab::DefaultChi2Registry();
  if (list) {
    for (const ptlab::Chi2Subject& s : registry.subjects()) {
      std::printf("%-40s %-22s %s%s%s\n", s.name.c_str(), ptlab::Chi2DomainName(s.domain).c_str(),
                  s.expect == ptlab::Chi2Expect::kPass ? "must pass" : "must fail",
                  s.params.empty() ? "" : "  ", s.params.c_str());
    }
    return kExitOk;
  }
  if (all == !names.empty()) {
    std::fprintf(stderr, "chi2: give either --all or subject names (--list shows them)\n%s",
                 app.help().c_str());
    return kExitUsage;
  }
  std::vector<const ptlab::Chi2Subject*> selected;
  if (all) {
    for (const ptlab::Chi2Subject& s : registry.subjects()) selected.push_back(&s);
  } else {
    for (const std::string& name : names) {
      const ptlab::Chi2Subject* s = registry.Find(name);
      if (s == nullptr) {
        std::fprintf(stderr, "chi2: unknown subject \"%s\" (--list shows them)\n", name.c_str());
        return kExitUsage;
      }
      selected.push_back(s);
    }
  }

  if (!images_dir.empty()) {  // created and probed before any test runs
    std::string error;
    if (const int code = ptlab::PrepareOutputFolder(images_dir, &error); code != kExitOk) {
      std::fprintf(stderr, "chi2: --images: %s\n", error.c_str());
      return code;
    }
  }
  options.test_count = int(selected.size());
  if (power.seeds > 0) power.power = true;
  if (mpi.active()) return RunOverRanks(mpi, selected, options, images_dir, verbose, power);
  std::printf(
      "chi2: %d tests, %lld samples, res %d, seed %llu, alpha %g (alpha' = %.3g per test)\n",
      options.test_count, static_cast<long long>(options.samples), options.res,
      static_cast<unsigned long long>(options.seed), options.alpha,
      ptlab::SidakAlpha(options.alpha, options.test_count));
  int as_expected = 0, unexpected = 0;
  for (const ptlab::Chi2Subject* s : selected) {
    const ptlab::Chi2Result result = ptlab::RunChi2Test(*s, options);
    std::printf("%s\n%s", ptlab::FormatChi2Result(*s, result).c_str(),
                PowerText(*s, options, result, power).c_str());
    if (verbose) {
      for (const std::string& note : result.notes) std::printf("       . %s\n", note.c_str());
      std::printf("       . %lld pdf evaluations\n", static_cast<long long>(result.pdf_evals));
    }
    std::fflush(stdout);
    (ptlab::Chi2AsExpected(*s, result) ? as_expected : unexpected)++;
    if (!images_dir.empty()) {
      const ptlab::Status status = ptlab::WriteChi2Report(images_dir, result);
      if (!status.ok()) {
        std::fprintf(stderr, "chi2: %s\n", status.message().c_str());
        return kExitRunFailed;
      }
    }
  }
  std::printf("chi2: %d as expected, %d not: %s\n", as_expected, unexpected,
              unexpected == 0 ? "PASS" : "FAIL");
  return unexpected == 0 ? kExitOk : kExitFailed;
}
