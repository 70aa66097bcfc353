// Integration of a chi-square subject's pdf over every cell of its grid (one point at a time
// or with a batch pdf), and the checks of the pdf values it meets.
#include "tools/chi2/chi2_integration.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "engine/core/check.h"
#include "engine/core/rng.h"
#include "tools/chi2/chi2_format.h"

namespace ptlab::chi2_internal {
namespace {

// Cells whose integral came out exactly 0 but that hold samples are integrated again with this
// many forced subdivisions (65 points per axis), so a sliver of support clipping a cell
// corner between the default 9 points per axis is not mistaken for zero mass.
constexpr int kRecheckMinDepth = 6;
// The batch integration keeps every evaluated point (about 50 bytes each with its table): a
// budget on their number bounds its memory (~0.4 GB) whatever the pdf. A smooth pdf needs ~0.4 M
// points at res 51; one that is noise within cells would otherwise grow without bound (found by
// tests/fuzz/fuzz_chi2_api.cpp: 1.9 GB and rising).
constexpr int64_t kMaxBatchPdfPoints = 8'000'000;

}  // namespace

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

}  // namespace ptlab::chi2_internal
