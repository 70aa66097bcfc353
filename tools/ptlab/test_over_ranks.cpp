// `ptlab test FILE.xml` under mpirun: the file's cases shared among ranks, printed by rank 0.
#include "tools/ptlab/test_over_ranks.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

#include "engine/io/nori_test_loader.h"
#include "tools/chi2/nori_tests.h"
#include "tools/common/exit_codes.h"

namespace ptlab {

int RunNoriTestOverRanks(const std::string& path, bool verbose, const mpi::Session& mpi) {
  const auto start = std::chrono::steady_clock::now();
  StatusOr<NoriTestFile> file = LoadNoriTestFile(path);
  const Status loaded = mpi.Agree(file.status());
  if (!loaded.ok() || !file.ok()) {
    // Every rank reads the same file; one that cannot stops all with the same message.
    if (!mpi.root()) return kExitOk;
    if (file.ok() || !IsUnsupportedFeatureMessage(file.status().message())) {
      std::fprintf(stderr, "error: %s\n", loaded.message().c_str());
      return kExitUsage;
    }
    std::printf("SKIP  %s\n      - %s\n", path.c_str(), file.status().message().c_str());
    std::printf("%s: skipped (a feature it needs is not supported yet)\n", path.c_str());
    return kExitSkipped;
  }
  if (mpi.root()) {
    std::printf("%s\n", FormatNoriTestHeader(*file).c_str());
    std::fflush(stdout);
  }
  NoriTestOptions options;
  options.threads = int(std::max(1u, std::thread::hardware_concurrency()));
  size_t cases = 0;
  options.runs_case = [&cases](size_t) { return ++cases, false; };
  RunNoriTestFile(*file, options);  // counts the cases, runs none
  // Each case alone, on its rank: its verdict as the first character, then its lines.
  const std::vector<std::string> texts = mpi.MapInOrder(cases, [&](size_t i) {
    NoriTestOptions one = options;
    one.runs_case = [i](size_t k) { return k == i; };
    const NoriTestReport r = RunNoriTestFile(*file, one);
    if (r.cases.size() != 1) return std::string("F(case " + std::to_string(i) + " did not run)");
    const char verdict = "PFS"[int(r.cases[0].verdict)];
    return verdict + FormatNoriTestCase(r.cases[0], verbose);
  });
  if (!mpi.root()) return kExitOk;
  NoriTestReport report;
  report.path = file->path;
  for (const std::string& t : texts) {
    std::printf("%s\n", t.c_str() + 1);
    NoriTestCase c;
    c.verdict = t[0] == 'P' ? NoriVerdict::kPass
                            : (t[0] == 'S' ? NoriVerdict::kSkip : NoriVerdict::kFail);
    report.cases.push_back(c);
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s\n", FormatNoriTestSummary(report).c_str());
  return NoriTestExitCode(report);
}

}  // namespace ptlab
