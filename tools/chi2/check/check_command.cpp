// `chi2 check`: tests a file of samples against a pdf program or a tabulated pdf.
#include "tools/chi2/check/check_command.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "ptlab/chi2.h"
#include "tools/chi2/check/pdf_command.h"
#include "tools/chi2/check/pdf_grid.h"
#include "tools/chi2/check/sample_file.h"

namespace ptlab {
namespace {

constexpr int kExitPass = 0;
constexpr int kExitFail = 1;
constexpr int kExitBadInput = 2;

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
Exit codes: 0 pass, 1 fail (the verdict), 2 bad input.)";

std::string JsonString(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\', out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof(buf), "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string JsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

std::string JsonList(const std::vector<std::string>& items) {
  std::string out = "[";
  for (size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + JsonString(items[i]);
  return out + "]";
}

int Error(bool json, const std::string& message) {
  std::fprintf(stderr, "chi2 check: %s\n", message.c_str());
  if (json) std::printf("{\"error\": %s}\n", JsonString(message).c_str());
  return kExitBadInput;
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
      ->check(CLI::Range(0.01, 1e6))
      ->capture_default_str();
  app.add_option("--res", options.res, "grid cells along y (cos theta); x gets 2x on the sphere")
      ->check(CLI::Range(2, 4096))
      ->capture_default_str();
  app.add_option("--alpha", options.alpha, "significance level")
      ->check(CLI::Range(1e-12, 0.5))
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
    return kExitBadInput;
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
  options.images_dir = images_dir;
  chi2::Result r;
  st = chi2::TestPoints(name, domain, points.data(), int64_t(points.size()), pdf, options, &r);
  if (!st.ok()) return Error(json, st.message());
  if (json) {
    std::printf(
        "{\"name\": %s, \"domain\": %s, \"samples\": %lld, \"res\": %d, \"passed\": %s, "
        "\"chi2\": %s, \"dof\": %d, \"p_value\": %s, \"alpha\": %s, \"alpha_corrected\": %s, "
        "\"pdf_integral\": %s, \"pdf_evals\": %lld, \"failures\": %s, \"notes\": %s}\n",
        JsonString(name).c_str(), JsonString(chi2::DomainName(domain)).c_str(),
        static_cast<long long>(r.samples), options.res, r.passed ? "true" : "false",
        JsonNumber(r.chi2).c_str(), r.dof, JsonNumber(r.p_value).c_str(),
        JsonNumber(options.alpha).c_str(), JsonNumber(r.alpha).c_str(),
        JsonNumber(r.pdf_integral).c_str(), static_cast<long long>(r.pdf_evals),
        JsonList(r.failures).c_str(), JsonList(r.notes).c_str());
  } else {
    std::printf("%s\n", chi2::FormatResult(name, r).c_str());
    for (const std::string& note : r.notes) std::printf("       . %s\n", note.c_str());
    if (options.power) std::printf("       power: %s\n", r.power_report.c_str());
  }
  return r.passed ? kExitPass : kExitFail;
}

}  // namespace ptlab
