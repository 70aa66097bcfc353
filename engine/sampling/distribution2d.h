// Piecewise-constant distributions on [0,1) and [0,1)² (marginal rows × conditional columns).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/core/aligned.h"
#include "engine/core/vec.h"
#include "engine/sampling/guide_table.h"

namespace ptlab {

// A 1-D distribution over n equal bins of [0,1) is stored as its CDF alone: n + 1 floats with
// cdf[0] = 0, cdf[n] = 1 and bin i holding probability cdf[i+1] - cdf[i]. The density on bin i
// is n · (cdf[i+1] - cdf[i]). An empty distribution (all weights 0) has an all-zero CDF.
// Sample and Pdf derive every probability from the same float differences, so the pdf a sample
// reports is bit-identical to Pdf at that sample: what MIS and the chi² test need. A bin whose
// float width rounds to 0 is never sampled and has density 0, consistently.

/// The bin of x ∈ [0,1] among n equal bins: ⌊x·n⌋ clamped to [0, n-1] (x = 1 is in the last).
inline int PiecewiseConstantBin(float x, int n) { return std::clamp(int(x * float(n)), 0, n - 1); }

/// Fills cdf[0..n] from n weights (finite, >= 0; summed in double) and returns their sum. When
/// the sum is 0 the CDF is all zero: the distribution is empty.
template <typename T>
double BuildPiecewiseConstantCdf(const T* weights, int n, float* cdf) {
  double total = 0;
  for (int i = 0; i < n; ++i) total += double(weights[i]);
  cdf[0] = 0.0f;
  if (!(total > 0)) {
    std::fill(cdf, cdf + n + 1, 0.0f);
    return 0.0;
  }
  double running = 0;
  for (int i = 0; i < n; ++i) {
    running += double(weights[i]);
    cdf[i + 1] = float(running / total);
  }
  cdf[n] = 1.0f;  // exactly, whatever the rounding
  return total;
}

/// True when the distribution with this CDF has mass (its last entry is 1).
inline bool PiecewiseConstantNonEmpty(const float* cdf, int n) { return cdf[n] > 0.0f; }

/// Density n · (cdf[i+1] - cdf[i]) of bin i (w.r.t. length on [0,1)).
inline float PiecewiseConstantBinPdf(const float* cdf, int n, int bin) {
  return float(n) * (cdf[bin + 1] - cdf[bin]);
}

/// Fills guide[0..n] (n + 1 entries) for the CDF cdf[0..n] of n bins: guide[b] is the bin that
/// u = b / n falls in, so the bin of any u in [b / n, (b + 1) / n) lies between guide[b] and
/// guide[b + 1] (float rounding at the edges aside: readers check or widen by one bucket).
inline void BuildPiecewiseConstantGuide(const float* cdf, int n, uint32_t* guide) {
  // cdf[0] = 0 <= u always, so the last i with cdf[i] <= u is the first index of cdf + 1 whose
  // entry exceeds u: BuildGuideTable over cdf[1..n].
  BuildGuideTable(cdf + 1, uint32_t(n), guide);
}

/// Inverts the CDF at u ∈ [0,1): *x ∈ [0,1) lies in bin *bin (PiecewiseConstantBin(*x) == *bin,
/// guaranteed despite rounding), linearly placed within it; *pdf is the bin's density (> 0).
/// Returns false, touching nothing, when the distribution is empty. The search is over the
/// whole CDF: in renders of the Venice map a guide table made this scalar search slower (the
/// demo's --scalar task-clock 2.08 → 2.16 s), where it makes the 8-wide search of
/// simd/distribution8-inl.h faster.
inline bool SamplePiecewiseConstant1D(const float* cdf, int n, float u, float* x, int* bin,
                                      float* pdf) {
  if (!PiecewiseConstantNonEmpty(cdf, n)) return false;
  u = u >= 0.0f ? std::min(u, kOneMinusEpsilon) : 0.0f;  // also maps NaN to 0
  // The last i with cdf[i] <= u: skips bins of zero width, and is < n because u < 1 = cdf[n].
  const int i = int(std::upper_bound(cdf, cdf + n + 1, u) - cdf) - 1;
  const float lo = cdf[i], width = cdf[i + 1] - lo;
  float t = (u - lo) / width;
  float v = (float(i) + std::min(t, 1.0f)) / float(n);
  // Rounding may push v onto a neighbouring bin; step back inside so Pdf(v) agrees.
  while (v > 0.0f && PiecewiseConstantBin(v, n) > i) v = std::nextafter(v, 0.0f);
  while (PiecewiseConstantBin(v, n) < i) v = std::nextafter(v, 1.0f);
  if (v >= 1.0f) v = kOneMinusEpsilon;
  *x = v;
  *bin = i;
  *pdf = PiecewiseConstantBinPdf(cdf, n, i);
  return true;
}

/// Density at x (w.r.t. length): 0 outside [0,1] and for an empty distribution.
inline float PiecewiseConstant1DPdf(const float* cdf, int n, float x) {
  if (!(x >= 0.0f && x <= 1.0f)) return 0.0f;
  return PiecewiseConstantBinPdf(cdf, n, PiecewiseConstantBin(x, n));
}

/// An owning 1-D distribution (for standalone use and tests; tables store bare CDF columns).
struct Distribution1D {
  int n = 0;
  std::vector<float> cdf;  // n + 1 entries
  double total = 0;        // sum of the weights it was built from

  Distribution1D() = default;
  Distribution1D(const float* weights, int count) : n(count), cdf(size_t(count) + 1) {
    total = BuildPiecewiseConstantCdf(weights, n, cdf.data());
  }
  bool Sample(float u, float* x, float* pdf) const {
    int bin;
    return SamplePiecewiseConstant1D(cdf.data(), n, u, x, &bin, pdf);
  }
  float Pdf(float x) const { return PiecewiseConstant1DPdf(cdf.data(), n, x); }
};

// A 2-D distribution over an nu × nv grid of equal cells of [0,1)² (x = u along columns, y = v
// along rows): the marginal CDF over rows (nv + 1 floats) and one conditional CDF over the
// columns of each row (nv × (nu + 1) floats, row j at j·(nu + 1)). A row of zero weight has an
// all-zero conditional CDF and is never chosen by the marginal. The density on cell (i, j) is
// nv·(M[j+1] - M[j]) · nu·(C_j[i+1] - C_j[i]) w.r.t. area on the unit square.

/// A view of a 2-D distribution's CDF columns (they usually live in a table).
struct Distribution2DView {
  const float* marginal_cdf = nullptr;     // nv + 1
  const float* conditional_cdf = nullptr;  // nv × (nu + 1)
  int nu = 0, nv = 0;
  // Optional guide tables (BuildDistribution2DGuides), laid out as the CDFs; null: none. Read
  // by the 8-wide inversion (simd/distribution8-inl.h) only.
  const uint32_t* marginal_guide = nullptr;
  const uint32_t* conditional_guide = nullptr;

  const float* Row(int j) const { return conditional_cdf + size_t(j) * size_t(nu + 1); }
  bool NonEmpty() const { return PiecewiseConstantNonEmpty(marginal_cdf, nv); }
};

/// Builds the CDFs from weights[j·nu + i] (cell i of row j; finite, >= 0). marginal_cdf needs
/// nv + 1 floats, conditional_cdf nv·(nu + 1). Returns the sum of all weights (0: empty).
template <typename T>
double BuildDistribution2D(const T* weights, int nu, int nv, float* marginal_cdf,
                           float* conditional_cdf) {
  std::vector<double> row_sums(size_t(nv), 0.0);
  for (int j = 0; j < nv; ++j)
    row_sums[size_t(j)] = BuildPiecewiseConstantCdf(weights + size_t(j) * size_t(nu), nu,
                                                    conditional_cdf + size_t(j) * size_t(nu + 1));
  return BuildPiecewiseConstantCdf(row_sums.data(), nv, marginal_cdf);
}

/// Fills the guide tables of d's CDFs: marginal_guide nv + 1 entries, conditional_guide
/// nv × (nu + 1), laid out as the CDFs.
inline void BuildDistribution2DGuides(const Distribution2DView& d, uint32_t* marginal_guide,
                                      uint32_t* conditional_guide) {
  BuildPiecewiseConstantGuide(d.marginal_cdf, d.nv, marginal_guide);
  for (int j = 0; j < d.nv; ++j)
    BuildPiecewiseConstantGuide(d.Row(j), d.nu, conditional_guide + size_t(j) * size_t(d.nu + 1));
}

/// Density of cell (i, j) w.r.t. area on the unit square.
inline float Distribution2DCellPdf(const Distribution2DView& d, int i, int j) {
  return PiecewiseConstantBinPdf(d.marginal_cdf, d.nv, j) *
         PiecewiseConstantBinPdf(d.Row(j), d.nu, i);
}

/// Samples p ∈ [0,1)²: the row from the marginal with u.y, the column from that row's
/// conditional with u.x, each placed linearly within its cell. *pdf = Distribution2DPdf(d, *p)
/// (w.r.t. area); *cell = (column, row) when not null. Returns false for an empty distribution.
inline bool SampleDistribution2D(const Distribution2DView& d, const Vec2f& u, Vec2f* p, float* pdf,
                                 int* column = nullptr, int* row = nullptr) {
  float y, x, pdf_y, pdf_x;
  int j, i;
  if (!SamplePiecewiseConstant1D(d.marginal_cdf, d.nv, u.y, &y, &j, &pdf_y)) return false;
  if (!SamplePiecewiseConstant1D(d.Row(j), d.nu, u.x, &x, &i, &pdf_x)) return false;
  *p = {x, y};
  *pdf = Distribution2DCellPdf(d, i, j);
  if (column) *column = i;
  if (row) *row = j;
  return true;
}

/// Density at p (w.r.t. area on the unit square): 0 outside [0,1]² and when empty.
inline float Distribution2DPdf(const Distribution2DView& d, const Vec2f& p) {
  if (!(p.x >= 0.0f && p.x <= 1.0f && p.y >= 0.0f && p.y <= 1.0f)) return 0.0f;
  return Distribution2DCellPdf(d, PiecewiseConstantBin(p.x, d.nu), PiecewiseConstantBin(p.y, d.nv));
}

/// An owning 2-D distribution (for standalone use and tests; tables store the columns).
struct Distribution2D {
  int nu = 0, nv = 0;
  AlignedVector<float> marginal_cdf, conditional_cdf;
  double total = 0;

  Distribution2D() = default;
  /// weights[j·nu + i], nu, nv >= 1.
  Distribution2D(const float* weights, int columns, int rows)
      : nu(columns),
        nv(rows),
        marginal_cdf(size_t(rows) + 1),
        conditional_cdf(size_t(rows) * (size_t(columns) + 1)) {
    total = BuildDistribution2D(weights, nu, nv, marginal_cdf.data(), conditional_cdf.data());
  }
  Distribution2DView view() const { return {marginal_cdf.data(), conditional_cdf.data(), nu, nv}; }
};

}  // namespace ptlab
