// The output columns of a direction-sampling batch (EnvironmentBatchOutputs: environment maps,
// distant disks) and their comparison against the oracle's, for the SIMD-vs-oracle tests.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/wavefront/environment.h"

namespace ptlab::test {

/// n rows of wi x, y, z, radiance r, g, b and pdf, as owned vectors.
struct SampleColumns {
  explicit SampleColumns(size_t n) : col(7, std::vector<float>(n)) {}
  std::vector<std::vector<float>> col;  // wi x, y, z, r, g, b, pdf
  EnvironmentBatchOutputs Out() {
    return {col[0].data(), col[1].data(), col[2].data(), col[3].data(),
            col[4].data(), col[5].data(), col[6].data()};
  }
};

/// What CompareSampleColumns found: rows out of contract per kind, the first such row (m if
/// none), and the largest |Δwi| and relative pdf error seen.
struct SampleColumnsDiff {
  size_t radiance_differ = 0, wi_off = 0, pdf_off = 0, nonfinite = 0, first = 0;
  float seen_wi = 0, seen_pdf = 0;
};

/// Expects rows [0, m) of `got` to match `want`: radiance bit for bit, wi within wi_tolerance
/// per component, pdf within pdf_tolerance relative (0: equal) and positive exactly where
/// want's is, and no non-finite value in `got`. Returns the counts, for the caller's report.
inline SampleColumnsDiff ExpectSampleColumnsMatch(const SampleColumns& got,
                                                  const SampleColumns& want, size_t m,
                                                  float wi_tolerance, float pdf_tolerance) {
  SampleColumnsDiff diff;
  diff.first = m;
  for (size_t i = 0; i < m; ++i) {
    bool off = false;
    for (size_t c = 0; c < 7; ++c) diff.nonfinite += !std::isfinite(got.col[c][i]);
    for (size_t c = 3; c < 6; ++c)
      if (std::bit_cast<uint32_t>(got.col[c][i]) != std::bit_cast<uint32_t>(want.col[c][i]))
        ++diff.radiance_differ, off = true;
    for (size_t c = 0; c < 3; ++c) {
      const float e = std::fabs(got.col[c][i] - want.col[c][i]);
      diff.seen_wi = std::max(diff.seen_wi, e);
      if (!(e <= wi_tolerance)) ++diff.wi_off, off = true;
    }
    const float p = got.col[6][i], q = want.col[6][i];
    if (q > 0) diff.seen_pdf = std::max(diff.seen_pdf, std::fabs(p - q) / q);
    if (!(std::fabs(p - q) <= pdf_tolerance * q) || ((p > 0) != (q > 0)))
      ++diff.pdf_off, off = true;
    if (off) diff.first = std::min(diff.first, i);
  }
  EXPECT_EQ(diff.radiance_differ, 0u) << "first differing row " << diff.first << " of " << m;
  EXPECT_EQ(diff.wi_off, 0u) << "first differing row " << diff.first << " of " << m;
  EXPECT_EQ(diff.pdf_off, 0u) << "first differing row " << diff.first << " of " << m;
  EXPECT_EQ(diff.nonfinite, 0u);
  return diff;
}

}  // namespace ptlab::test
