// `chi2 check`: tests a file of samples against a pdf program or a tabulated pdf.
#include "tools/chi2/check/check_command.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/core/parse_number.h"
#include "ptlab/chi2.h"
#include "tools/chi2/check/pdf_command.h"
#include "tools/chi2/check/pdf_grid.h"
#include "tools/chi2/check/sample_file.h"
#include "tools/chi2/report.h"
#include "tools/cli_checks.h"
#include "tools/common/exit_codes.h"
#include "tools/common/json_line.h"
#include "tools/common/output_guard.h"

namespace ptlab {
namespace {


constexpr const char* kFooter =
    R"(Samples: --samples FILE is text (one point per line, "x,y" or "x,y,z", a header line
allowed) or, with --dims K, raw little-endian float32, K per point. Planar domains take 2
coordinates, the sphere and hemisphere 3 (unit vectors).
Pdf program (--pdf-cmd): run with /bin/sh -c a few times per test; each time ptlab writes
points to its stdin, one per line ("x y" or "x y z"), closes it, and reads one density per line
from its stdout (per unit area, per steradian on the sphere); it must exit with status 0.
Pdf grid (--pdf-grid): "NX NY", then NY rows of NX densities at the nodes of the parameter
rectangle (the box; [-1,1]^2 for the disk; (phi, cos theta) on the sphere), interpolated
bilinearly: error <= (hx^2 max|p_xx| + hy^2 max|p_yy|)/8 for node spacings hx, hy.
Exit codes (tools/common/exit_codes.h, as ptlab and imgdiff): 0 pass, 1 fail (the verdict),
2 bad usage or input (files, the pdf program's failures, an --images file that would replace
an input), 3 the --images folder or its files could not be written.)";

int Error(bool json, const std::string& message) {
  std::fprintf(stderr, "chi2 check: %s\n", message.c_str());
  if (json) {
    Json j;
    j["error"] = message;
    std::printf("%s\n", DumpJsonLine(j).c_str());
  }
  return kExitUsage;
}

}  // namespace

int RunCheckCommand(int argc, char** argv) {
  CLI::App app{"chi2 check: chi-square test of samples from a file against a pdf", "chi2 check"};
  app.footer(kFooter);
  std::string domain_text, samples_path, pdf_cmd, pdf_grid, name, images_dir;
  int dims = 0;
  double timeout = 60;
  bool json = false;
  chi2::Options options;
  app.add_option("--domain", domain_text, "square | disk | box:x0,y0,x1,y1 | sphere | hemisphere")
      ->required();
  app.add_option("--samples", samples_path, "sample file (CSV text, or raw float32 with --dims)")
      ->required();
  app.add_option("--dims", dims, "the sample file is raw little-endian float32, K per point")
      ->check(CLI::Range(2, 3));
  auto* cmd = app.add_option("--pdf-cmd", pdf_cmd, "program answering pdf queries (see below)");
  auto* grid = app.add_option("--pdf-grid", pdf_grid, "pdf tabulated on a grid (see below)");
  cmd->excludes(grid);
  app.add_option("--pdf-timeout", timeout, "seconds the pdf program may take per batch")
      ->check(FiniteRange(0.01, 1e6))
      ->capture_default_str();
  app.add_option("--res", options.res, "grid cells along y (cos theta); x gets 2x on the sphere")
      ->check(CLI::Range(2, 4096))
      ->capture_default_str();
  app.add_option("--alpha", options.alpha, "significance level")
      ->check(FiniteRange(1e-12, 0.5))
      ->capture_default_str();
  app.add_option("--name", name, "test name (image file names; default: the sample file's stem)");
  app.add_option("--images", images_dir, "write <DIR>/<name>.png and .csv");
  app.add_flag("--json", json, "print the result as one JSON object");
  app.add_flag("--power", options.power,
               "also print the smallest smooth pdf error the test detects (95 %; text output)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitUsage;
  }
  if (pdf_cmd.empty() == pdf_grid.empty())
    return Error(json, "give the pdf as --pdf-cmd PROGRAM or --pdf-grid FILE (one of them)");
  chi2::Domain domain;
  chi2::Status st = chi2::ParseDomain(domain_text, &domain);
  if (!st.ok()) return Error(json, "--domain: " + st.message());
  if (dims != 0 && dims != domain.dims())
    return Error(json, "--dims " + std::to_string(dims) + " does not fit the " +
                           chi2::DomainName(domain) + " domain: its points have " +
                           std::to_string(domain.dims()) + " coordinates");
  std::vector<chi2::Point> points;
  st = ReadSampleFile(samples_path, dims != 0, domain.dims(), &points);
  if (!st.ok()) return Error(json, st.message());
  chi2::PdfFn pdf;
  if (!pdf_cmd.empty()) {
    pdf = PdfCommand(pdf_cmd, domain, timeout);
  } else {
    st = ReadPdfGrid(pdf_grid, domain, &pdf);
    if (!st.ok()) return Error(json, st.message());
  }
  if (name.empty()) name = std::filesystem::path(samples_path).stem().string();
  if (!images_dir.empty()) {  // before the test: its images may not replace an input
    OutputGuard guard;
    guard.AddInput(samples_path, "--samples");
    guard.AddInput(pdf_grid, "--pdf-grid");
    const std::string stem = (std::filesystem::path(images_dir) / Chi2FileStem(name)).string();
    guard.AddOutput(stem + ".png", "--images");
    guard.AddOutput(stem + ".csv", "--images");
    std::string error;
    int code = PrepareOutputFolder(images_dir, &error);
    if (code == kExitOk) code = guard.Check(&error);
    if (code != kExitOk) {
      Error(json, "--images: " + error);
      return code;
    }
  }
  options.images_dir = images_dir;
  chi2::Result r;
  st = chi2::TestPoints(name, domain, points.data(), int64_t(points.size()), pdf, options, &r);
  if (!st.ok()) {
    // "sample N is (x, y): outside the domain ...": name the file and line of sample N.
    const std::string& m = st.message();
    int64_t index = 0;
    const size_t digits = m.rfind("sample ", 0) == 0 ? m.find(' ', 7) : std::string::npos;
    if (digits != std::string::npos &&
        ParseNumberQuietly<int64_t>(std::string_view(m).substr(7, digits - 7), 0, INT64_MAX,
                                    &index) == NumberError::kOk)
      return Error(json, SampleLocation(samples_path, dims != 0, domain.dims(), index) + ": " + m);
    return Error(json, m);
  }
  if (json) {
    Json j;
    j["name"] = name;
    j["domain"] = chi2::DomainName(domain);
    j["samples"] = r.samples;
    j["res"] = options.res;
    j["passed"] = r.passed;
    j["chi2"] = JsonNumberOrNull(r.chi2);
    j["dof"] = r.dof;
    j["p_value"] = JsonNumberOrNull(r.p_value);
    j["alpha"] = JsonNumberOrNull(options.alpha);
    j["alpha_corrected"] = JsonNumberOrNull(r.alpha);
    j["pdf_integral"] = JsonNumberOrNull(r.pdf_integral);
    j["pdf_evals"] = r.pdf_evals;
    j["failures"] = r.failures;
    j["notes"] = r.notes;
    std::printf("%s\n", DumpJsonLine(j).c_str());
  } else {
    std::printf("%s\n", chi2::FormatResult(name, r).c_str());
    for (const std::string& note : r.notes) std::printf("       . %s\n", note.c_str());
    if (options.power) std::printf("       power: %s\n", r.power_report.c_str());
  }
  return r.passed ? kExitOk : kExitFailed;
}

}  // namespace ptlab
