// The public chi-square API (ptlab/chi2.h) over the lab's own test: conversion and input checks.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "engine/core/parse_number.h"
#include "engine/core/rng.h"
#include "ptlab/chi2.h"
#include "tools/chi2/chi2.h"
#include "tools/chi2/power.h"
#include "tools/chi2/report.h"

// PTLAB_RETURN_IF_ERROR for ptlab::chi2::Status.
#define PTLAB_CHI2_RETURN_IF_ERROR(expr)         \
  do {                                           \
    ::ptlab::chi2::Status chi2_status_ = (expr); \
    if (!chi2_status_.ok()) return chi2_status_; \
  } while (0)

namespace ptlab::chi2 {
namespace {

// Rows of uniforms handed to SampleFn at once: whole arrays for NumPy, bounded memory.
constexpr int64_t kSampleChunk = int64_t(1) << 22;
// Largest magnitude of a box corner: the box's area and its cells' stay finite in double
// (a box of ±1e308 had an infinite area and reported -1 degrees of freedom).
constexpr double kMaxBoxCorner = 1e150;

Chi2Domain ToInternal(const Domain& d) {
  switch (d.kind) {
    case DomainKind::kBox:
      return Chi2Domain::Box(d.x0, d.y0, d.x1, d.y1);
    case DomainKind::kDisk:
      return Chi2Domain::Disk();
    case DomainKind::kSphere:
      return Chi2Domain::Sphere();
    case DomainKind::kHemisphere:
      return Chi2Domain::Hemisphere();
  }
  return {};
}

std::string Describe(const Domain& d) {
  switch (d.kind) {
    case DomainKind::kBox:
      return DomainName(d) + " (points (x, y) with x0 <= x <= x1, y0 <= y <= y1)";
    case DomainKind::kDisk:
      return "disk (points (x, y) with x² + y² <= 1)";
    case DomainKind::kSphere:
      return "sphere (unit vectors (x, y, z))";
    case DomainKind::kHemisphere:
      return "hemisphere (unit vectors (x, y, z) with z >= 0)";
  }
  return "?";
}

std::string FormatPoint(const Domain& d, const Point& p) {
  char buf[128];
  if (d.dims() == 3) {
    std::snprintf(buf, sizeof(buf), "(%.9g, %.9g, %.9g)", p.x, p.y, p.z);
  } else {
    std::snprintf(buf, sizeof(buf), "(%.9g, %.9g)", p.x, p.y);
  }
  return buf;
}

Status CheckOptions(const Options& o) {
  if (o.samples < 1) return Status::Error("samples must be >= 1, got " + std::to_string(o.samples));
  if (o.res < 2 || o.res > 4096)
    return Status::Error("res must be in [2, 4096], got " + std::to_string(o.res));
  if (!(o.alpha > 0 && o.alpha < 1))
    return Status::Error("alpha must be in (0, 1), got " + std::to_string(o.alpha));
  if (o.coarse_blocks < 0 || o.coarse_blocks > 64)
    return Status::Error("coarse_blocks must be in [0, 64], got " +
                         std::to_string(o.coarse_blocks));
  if (o.test_count < 1)
    return Status::Error("test_count must be >= 1, got " + std::to_string(o.test_count));
  if (!(o.integral_tol > 0))
    return Status::Error("integral_tol must be > 0, got " + std::to_string(o.integral_tol));
  return Status::Ok();
}

Status CheckDomain(const Domain& d) {
  if (d.kind == DomainKind::kBox &&
      !(std::isfinite(d.x0) && std::isfinite(d.x1) && std::isfinite(d.y0) && std::isfinite(d.y1) &&
        d.x0 < d.x1 && d.y0 < d.y1))
    return Status::Error("a box domain needs finite corners with x0 < x1 and y0 < y1, got " +
                         DomainName(d));
  if (d.kind == DomainKind::kBox &&
      !(std::fabs(d.x0) <= kMaxBoxCorner && std::fabs(d.x1) <= kMaxBoxCorner &&
        std::fabs(d.y0) <= kMaxBoxCorner && std::fabs(d.y1) <= kMaxBoxCorner))
    return Status::Error("a box domain's corners must lie in [-1e150, 1e150] (its area must "
                         "stay finite), got " + DomainName(d));
  return Status::Ok();
}

// Every point finite and in the domain (the lab's own tolerance), else an error naming the first.
Status CheckPoints(const Domain& d, const Point* points, int64_t n) {
  const Chi2Domain internal = ToInternal(d);
  for (int64_t i = 0; i < n; ++i) {
    const Point& p = points[i];
    const bool finite =
        std::isfinite(p.x) && std::isfinite(p.y) && (d.dims() == 2 || std::isfinite(p.z));
    if (!finite)
      return Status::Error("sample " + std::to_string(i) + " is " + FormatPoint(d, p) +
                           ": not finite");
    if (!Chi2Contains(internal, {p.x, p.y, d.dims() == 3 ? p.z : 0.0f}))
      return Status::Error("sample " + std::to_string(i) + " is " + FormatPoint(d, p) +
                           ": outside the domain " + Describe(d));
  }
  return Status::Ok();
}

Result ToPublic(const Domain& domain, const Chi2Result& r) {
  Result out;
  out.domain = domain;
  out.passed = r.pass;
  out.chi2 = r.chi2;
  out.dof = r.dof;
  out.p_value = r.p_value;
  out.alpha = r.alpha;
  out.pdf_integral = r.pdf_integral;
  out.samples = r.samples;
  out.pdf_evals = r.pdf_evals;
  out.xres = r.xres;
  out.yres = r.yres;
  out.observed = r.observed;
  out.expected = r.expected;
  out.failures = r.failures;
  out.notes = r.notes;
  out.coarse_blocks = r.coarse_blocks;
  out.coarse_chi2 = r.coarse_chi2;
  out.coarse_dof = r.coarse_dof;
  out.coarse_p_value = r.coarse_p_value;
  out.alpha_each = r.alpha_each;
  return out;
}

Chi2Result ToInternal(const std::string& name, const Result& r) {
  Chi2Result out;
  out.name = name;
  out.domain = ToInternal(r.domain);
  out.xres = r.xres;
  out.yres = r.yres;
  out.observed = r.observed;
  out.expected = r.expected;
  return out;
}

}  // namespace

Status ParseDomain(const std::string& text, Domain* domain) {
  if (text == "square") return *domain = Domain::Square(), Status::Ok();
  if (text == "disk") return *domain = Domain::Disk(), Status::Ok();
  if (text == "sphere") return *domain = Domain::Sphere(), Status::Ok();
  if (text == "hemisphere") return *domain = Domain::Hemisphere(), Status::Ok();
  const std::string expected =
      "expected square, disk, sphere, hemisphere or box:x0,y0,x1,y1 (e.g. box:0,0,2,1)";
  if (text.rfind("box:", 0) != 0)
    return Status::Error("unknown domain \"" + text + "\": " + expected);
  double v[4];
  std::string_view rest = std::string_view(text).substr(4);
  for (int i = 0; i < 4; ++i) {
    const size_t comma = i < 3 ? rest.find(',') : rest.size();
    if (comma == std::string_view::npos)
      return Status::Error("bad box domain \"" + text + "\": " + expected);
    // Corners within ±1e150: the box's area (a product of two sides) and the cell areas
    // then stay finite, so the test's degrees of freedom do too.
    const std::string error =
        ptlab::ParseNumber<double>(rest.substr(0, comma), -kMaxBoxCorner, kMaxBoxCorner, &v[i]);
    if (!error.empty())
      return Status::Error("bad box domain \"" + text + "\": corner " + std::to_string(i + 1) +
                           " " + error + "; " + expected);
    rest.remove_prefix(i < 3 ? comma + 1 : comma);
  }
  const Domain box = Domain::Box(v[0], v[1], v[2], v[3]);
  PTLAB_CHI2_RETURN_IF_ERROR(CheckDomain(box));
  *domain = box;
  return Status::Ok();
}

std::string DomainName(const Domain& d) {
  switch (d.kind) {
    case DomainKind::kBox: {
      if (d.x0 == 0 && d.y0 == 0 && d.x1 == 1 && d.y1 == 1) return "square";
      char buf[160];
      std::snprintf(buf, sizeof(buf), "box:%.9g,%.9g,%.9g,%.9g", d.x0, d.y0, d.x1, d.y1);
      return buf;
    }
    case DomainKind::kDisk:
      return "disk";
    case DomainKind::kSphere:
      return "sphere";
    case DomainKind::kHemisphere:
      return "hemisphere";
  }
  return "?";
}

Status TestPoints(const std::string& name, const Domain& domain, const Point* points, int64_t n,
                  const PdfFn& pdf, const Options& options, Result* result) {
  PTLAB_CHI2_RETURN_IF_ERROR(CheckOptions(options));
  PTLAB_CHI2_RETURN_IF_ERROR(CheckDomain(domain));
  if (!pdf) return Status::Error("no pdf given");
  if (n < 1) return Status::Error("no samples given (at least 1 needed)");
  PTLAB_CHI2_RETURN_IF_ERROR(CheckPoints(domain, points, n));

  Chi2Subject s;
  s.name = name;
  s.domain = ToInternal(domain);
  const bool planar = domain.dims() == 2;
  auto next = std::make_shared<int64_t>(0);
  s.sample_batch = [points, planar, next](const float*, const Vec2f*, int m, Chi2Point* p,
                                          uint8_t* ok) {
    for (int i = 0; i < m; ++i, ++*next) {
      const Point& q = points[*next];
      p[i] = {q.x, q.y, planar ? 0.0f : q.z};
      ok[i] = 1;
    }
  };
  // The first error of the pdf stops the test.
  Status pdf_status;
  s.pdf_batch = [&](const Chi2Point* p, int64_t m, double* density) {
    std::vector<Point> q(static_cast<size_t>(m));
    for (int64_t i = 0; i < m; ++i) q[size_t(i)] = {p[i].x, p[i].y, planar ? 0.0f : p[i].z};
    pdf_status = pdf(q.data(), m, density);
    return pdf_status.ok();
  };
  Chi2Options o;
  o.samples = n;
  o.res = options.res;
  o.seed = options.seed;
  o.alpha = options.alpha;
  o.test_count = options.test_count;
  o.integral_tol = options.integral_tol;
  o.coarse_blocks = options.coarse_blocks;
  const Chi2Result r = RunChi2Test(s, o);
  if (!pdf_status.ok()) return Status::Error("the pdf failed: " + pdf_status.message());
  Result out = ToPublic(domain, r);
  if (options.power) {
    const Chi2Power power = EstimateChi2Power(r, /*defective=*/false, o);
    out.power_epsilon = power.epsilon;
    out.power_at_2 = power.power_at_2;
    out.power_samples_for_2 = power.samples_for_2;
    out.power_report = FormatChi2Power(power);
  }
  if (!options.images_dir.empty())
    PTLAB_CHI2_RETURN_IF_ERROR(WriteImages(options.images_dir, name, out));
  *result = std::move(out);
  return Status::Ok();
}

Status Test(const Subject& subject, const Options& options, Result* result) {
  PTLAB_CHI2_RETURN_IF_ERROR(CheckOptions(options));
  PTLAB_CHI2_RETURN_IF_ERROR(CheckDomain(subject.domain));
  if (!subject.sample) return Status::Error("the subject has no sample function");
  if (subject.uniform_dims < 1 || subject.uniform_dims > 8)
    return Status::Error("uniform_dims must be in [1, 8], got " +
                         std::to_string(subject.uniform_dims));
  // Row i holds the uniforms in the order they are drawn: for 2 (or 3) dimensions exactly the
  // (u.x, u.y) (or (u1, u.x, u.y)) that ptlab's own chi2 draws for a subject of the same name.
  Pcg32 rng(options.seed, Chi2StreamFromName(subject.name));
  const int k = subject.uniform_dims;
  std::vector<Point> points(size_t(options.samples));
  std::vector<float> u;
  for (int64_t done = 0; done < options.samples; done += kSampleChunk) {
    const int64_t m = std::min(kSampleChunk, options.samples - done);
    u.resize(size_t(m) * size_t(k));
    for (float& x : u) x = rng.NextFloat();
    const Status st = subject.sample(u.data(), m, k, points.data() + done);
    if (!st.ok()) return Status::Error("the sampler failed: " + st.message());
  }
  return TestPoints(subject.name, subject.domain, points.data(), options.samples, subject.pdf,
                    options, result);
}

Status WriteImages(const std::string& dir, const std::string& name, const Result& result) {
  if (result.observed.size() != size_t(result.xres) * size_t(result.yres) ||
      result.expected.size() != result.observed.size() || result.xres < 1)
    return Status::Error("the result has no cells (xres x yres observed and expected counts)");
  const ptlab::Status st = WriteChi2Report(dir, ToInternal(name, result));
  return st.ok() ? Status::Ok() : Status::Error(st.message());
}

std::string FormatResult(const std::string& name, const Result& result) {
  Chi2Subject s;
  s.name = name;
  Chi2Result r;
  r.name = name;
  r.pass = result.passed;
  r.chi2 = result.chi2;
  r.dof = result.dof;
  r.p_value = result.p_value;
  r.alpha = result.alpha;
  r.pdf_integral = result.pdf_integral;
  r.coarse_blocks = result.coarse_blocks;
  r.coarse_chi2 = result.coarse_chi2;
  r.coarse_dof = result.coarse_dof;
  r.coarse_p_value = result.coarse_p_value;
  r.alpha_each = result.alpha_each;
  r.failures = result.failures;
  return FormatChi2Result(s, r);
}

}  // namespace ptlab::chi2
