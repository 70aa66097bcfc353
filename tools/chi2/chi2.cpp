// Chi-square test driver: sampling histogram, per-cell pdf integration, checks and verdict.
#include "tools/chi2/chi2.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "engine/core/check.h"
#include "engine/core/rng.h"
#include "tools/chi2/coarse_grid.h"

namespace ptlab {
namespace {

// Samples are drawn and mapped in chunks so a batch (SIMD) sampler sees plain arrays.
constexpr int kChunk = 256;

// Cells whose integral came out exactly 0 but that hold samples are integrated again with this
// many forced subdivisions (65 points per axis), so a sliver of support clipping a cell
// corner between the default 9 points per axis is not mistaken for zero mass.
constexpr int kRecheckMinDepth = 6;
// The batch integration keeps every evaluated point (about 50 bytes each with its table): a
// budget on their number bounds its memory (~0.4 GB) whatever the pdf. A smooth pdf needs ~0.4 M
// points at res 51; one that is noise within cells would otherwise grow without bound (found by
// tests/fuzz/fuzz_chi2_api.cpp: 1.9 GB and rising).
constexpr int64_t kMaxBatchPdfPoints = 8'000'000;

std::string FormatPoint(const Chi2Domain& domain, const Chi2Point& p) {
  char buf[96];
  if (domain.spherical()) {
    std::snprintf(buf, sizeof(buf), "(%.7g, %.7g, %.7g)", p.x, p.y, p.z);
  } else {
    std::snprintf(buf, sizeof(buf), "(%.7g, %.7g)", p.x, p.y);
  }
  return buf;
}

std::string Format(const char* fmt, double a, double b = 0, double c = 0) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), fmt, a, b, c);
  return buf;
}

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

// A batch-pdf replay pass (see IntegrateWithBatchPdf): lookups of points not evaluated yet, and
// the cells whose integral an earlier pass completed (skipped: they need no new point).
struct ReplayPass {
  int64_t misses = 0;
  std::vector<uint8_t>* complete = nullptr;  // per cell; null: integrate every cell
  size_t cell = 0;                           // the cell being integrated
};

// Integrates the pdf over every cell (probability per cell, written to r->expected before
// scaling) and records non-finite or negative pdf values.
class CellIntegrator {
 public:
  CellIntegrator(const Chi2Subject& subject, const Chi2PdfFn& pdf, const Chi2Options& options,
                 Chi2Result* r, ReplayPass* replay)
      : subject_(subject), pdf_(pdf), options_(options), r_(r), replay_(replay) {}

  double Integrate(int ix, int iy, const Simpson2DOptions& simpson) {
    const Chi2Domain& d = subject_.domain;
    const double cx0 = d.x0 + (d.x1 - d.x0) * ix / r_->xres;
    const double cx1 = d.x0 + (d.x1 - d.x0) * (ix + 1) / r_->xres;
    const double cy0 = d.y0 + (d.y1 - d.y0) * iy / r_->yres;
    const double cy1 = d.y0 + (d.y1 - d.y0) * (iy + 1) / r_->yres;
    SimpsonBudget budget;
    budget.limit = options_.max_evals_per_cell;
    auto inner = [&](double x) {
      double lo, hi;
      Chi2SupportY(d, x, cy0, cy1, &lo, &hi);
      return AdaptiveSimpson([&](double y) { return Pdf(x, y); }, lo, hi, simpson.inner, &budget);
    };
    const double v = AdaptiveSimpson(inner, cx0, cx1, simpson.outer, &budget);
    if (budget.exhausted) ++exhausted_cells_;
    return v;
  }

  void Report() {
    r_->pdf_evals = evals_;
    if (bad_values_ > 0) {
      r_->failures.push_back(
          Format("the pdf is non-finite or negative at %.0f of %.0f evaluated points",
                 double(bad_values_), double(evals_)) +
          " (first: " + Format("%g", first_bad_value_) + " at " +
          FormatPoint(subject_.domain, first_bad_point_) + ")");
    }
    if (exhausted_cells_ > 0) {
      r_->notes.push_back(
          Format("integration budget (%.0f pdf evaluations) exhausted in %.0f "
                 "cells before convergence",
                 double(options_.max_evals_per_cell), double(exhausted_cells_)));
    }
  }

 private:
  double Pdf(double x, double y) {
    ++evals_;
    const Chi2Point p = Chi2FromParam(subject_.domain, {x, y});
    const int64_t misses = replay_ ? replay_->misses : 0;
    const double v = pdf_(p);
    // Not known yet: NaN stops the refinement that depends on it (see AdaptiveSimpson).
    if (replay_ && replay_->misses != misses) return std::numeric_limits<double>::quiet_NaN();
    if (!std::isfinite(v) || v < 0) {
      if (bad_values_++ == 0) first_bad_point_ = p, first_bad_value_ = v;
      return 0.0;
    }
    return v;
  }

  const Chi2Subject& subject_;
  const Chi2PdfFn& pdf_;
  const Chi2Options& options_;
  Chi2Result* r_;
  ReplayPass* replay_;
  int64_t evals_ = 0, bad_values_ = 0, exhausted_cells_ = 0;
  Chi2Point first_bad_point_;
  double first_bad_value_ = 0;
};

// Integrates `pdf` over every cell into r->expected (samples x probability) and returns the
// integral over the domain. `replay` is null, or a batch replay pass: then cells whose integral
// needs points not evaluated yet come out NaN.
double IntegrateCells(const Chi2Subject& subject, const Chi2PdfFn& pdf, const Chi2Options& options,
                      Chi2Result* r, ReplayPass* replay) {
  CellIntegrator integrator(subject, pdf, options, r, replay);
  Simpson2DOptions recheck = options.simpson;
  recheck.outer.min_depth = std::max(recheck.outer.min_depth, kRecheckMinDepth);
  recheck.inner.min_depth = std::max(recheck.inner.min_depth, kRecheckMinDepth);
  double total = 0;
  for (int iy = 0; iy < r->yres; ++iy) {
    for (int ix = 0; ix < r->xres; ++ix) {
      const size_t c = size_t(iy) * size_t(r->xres) + size_t(ix);
      std::vector<uint8_t>* complete = replay ? replay->complete : nullptr;
      if (complete && (*complete)[c]) continue;
      const int64_t misses = replay ? replay->misses : 0;
      if (replay) replay->cell = c;
      double mass = integrator.Integrate(ix, iy, options.simpson);
      if (mass == 0 && r->observed[c] > 0) mass = integrator.Integrate(ix, iy, recheck);
      if (complete && replay->misses == misses) (*complete)[c] = 1;
      total += mass;
      r->expected[c] = mass * double(options.samples);
    }
  }
  integrator.Report();
  return total;
}

// Pdf values of one cell's points (by bit pattern), open addressing with linear probing: the
// replay looks points up millions of times, so each cell's table stays small and in cache.
class PointTable {
 public:
  enum class State : uint8_t { kEmpty, kQueued, kKnown };

  /// The entry of p, created (queued) if new; *created tells which.
  size_t Find(const Chi2Point& p, bool* created) {
    if (4 * (size_ + 1) > 3 * slots_.size()) Grow();
    const Key k = KeyOf(p);
    for (size_t i = Hash(k) & mask_;; i = (i + 1) & mask_) {
      Slot& s = slots_[i];
      if (s.state == State::kEmpty) {
        s.key = k, s.state = State::kQueued, ++size_;
        *created = true;
        return i;
      }
      if (s.key == k) {
        *created = false;
        return i;
      }
    }
  }
  State state(size_t i) const { return slots_[i].state; }
  double value(size_t i) const { return slots_[i].value; }
  void Set(const Chi2Point& p, double v) {
    bool created;
    Slot& s = slots_[Find(p, &created)];
    s.value = v, s.state = State::kKnown;
  }

 private:
  struct Key {
    uint32_t x, y, z;
    bool operator==(const Key&) const = default;
  };
  struct Slot {
    Key key{};
    State state = State::kEmpty;
    double value = 0;
  };
  static Key KeyOf(const Chi2Point& p) {
    Key k;
    std::memcpy(&k.x, &p.x, 4), std::memcpy(&k.y, &p.y, 4), std::memcpy(&k.z, &p.z, 4);
    return k;
  }
  static size_t Hash(const Key& k) {
    return size_t(MixBits((uint64_t(k.x) << 32 | k.y) ^ (uint64_t(k.z) * 0x9e3779b97f4a7c15ULL)));
  }
  void Grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(std::max<size_t>(64, 2 * old.size()), Slot());
    mask_ = slots_.size() - 1, size_ = 0;
    for (const Slot& s : old) {
      if (s.state == State::kEmpty) continue;
      for (size_t i = Hash(s.key) & mask_;; i = (i + 1) & mask_) {
        if (slots_[i].state == State::kEmpty) {
          slots_[i] = s, ++size_;
          break;
        }
      }
    }
  }

  std::vector<Slot> slots_;
  size_t mask_ = 0, size_ = 0;
};

// The adaptive integration with a batch pdf: each pass runs IntegrateCells on the values known
// so far (an unknown point is collected and reads NaN, which ends the refinement that depends on
// it), then evaluates the collected points in one batch call; cells that needed no new point are
// skipped from then on. Once no cell needs one, a last pass over every cell is exactly the
// one-point-at-a-time run. Batch calls ~ outer x inner refinement depth.
double IntegrateWithBatchPdf(const Chi2Subject& subject, const Chi2Options& options,
                             Chi2Result* r) {
  std::vector<PointTable> tables(r->observed.size());
  std::vector<Chi2Point> missing;
  std::vector<size_t> missing_cell;
  int64_t calls = 0, points = 0;
  std::vector<uint8_t> complete(r->observed.size(), 0);
  ReplayPass replay;
  const Chi2PdfFn lookup = [&](const Chi2Point& p) {
    bool created;
    PointTable& table = tables[replay.cell];
    const size_t i = table.Find(p, &created);
    if (table.state(i) == PointTable::State::kKnown) return table.value(i);
    ++replay.misses;
    if (created) missing.push_back(p), missing_cell.push_back(replay.cell);
    return 0.0;  // read as NaN by CellIntegrator::Pdf
  };
  for (;;) {
    Chi2Result pass = *r;
    replay.misses = 0, replay.complete = &complete, missing.clear(), missing_cell.clear();
    IntegrateCells(subject, lookup, options, &pass, &replay);
    if (missing.empty()) break;
    if (points + int64_t(missing.size()) > kMaxBatchPdfPoints) {
      r->failures.push_back(Format(
          "the pdf needed more than %.0f evaluations to integrate over the cells (a smooth pdf "
          "needs ~0.4 M at res 51): it is not smooth within cells (noise?), or res is too high",
          double(kMaxBatchPdfPoints)));
      return std::numeric_limits<double>::quiet_NaN();
    }
    std::vector<double> values(missing.size());
    ++calls;
    if (!subject.pdf_batch(missing.data(), int64_t(missing.size()), values.data())) {
      r->failures.push_back(Format("the batch pdf could not answer (call %.0f)", double(calls)));
      return std::numeric_limits<double>::quiet_NaN();
    }
    for (size_t i = 0; i < missing.size(); ++i) tables[missing_cell[i]].Set(missing[i], values[i]);
    points += int64_t(missing.size());
  }
  replay.misses = 0, replay.complete = nullptr;
  const double total = IntegrateCells(subject, lookup, options, r, &replay);
  PTLAB_CHECK(replay.misses == 0);
  r->notes.push_back(Format("batch pdf: %.0f points in %.0f calls", double(points), double(calls)));
  return total;
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
