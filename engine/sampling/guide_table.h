// Guide tables (Chen & Asau's index tables) that turn CDF inversion into an O(1) expected
// lookup with the same result as a binary search over the whole CDF.
#pragma once

#include <algorithm>
#include <cstdint>

#include "engine/core/vec.h"

namespace ptlab {

/// Fills guide[0..n] for the non-decreasing cdf[0..n): guide[b] = the first index whose cdf
/// exceeds b / n (n when none does).
inline void BuildGuideTable(const float* cdf, uint32_t n, uint32_t* guide) {
  for (uint32_t b = 0; b <= n; ++b) {
    const float edge = n > 0 ? float(b) / float(n) : 1.0f;
    guide[b] = uint32_t(std::upper_bound(cdf, cdf + n, edge) - cdf);
  }
}

/// A CDF of at most this many entries is searched by GuidedUpperBound with a full branchless
/// scan instead of its guide.
inline constexpr uint32_t kScanUpperBoundMax = 16;

/// std::upper_bound(cdf, cdf + n, u) - cdf for u in [0, 1), searching only the guide's bucket of
/// u. The answer is verified against its neighbours and falls back to the full binary search
/// when the guide does not bracket it (a guide built for other CDF values, or float rounding at
/// a bucket edge), so the result never depends on the guide's contents.
inline uint32_t GuidedUpperBound(const float* cdf, uint32_t n, const uint32_t* guide, float u) {
  if (n == 0) return 0;
  if (n <= kScanUpperBoundMax) {
    // upper_bound's own predicate counted over the whole sorted CDF: the same index, without
    // the search's branches on u (random, so mispredicted about once a pick: the emitter pick
    // of a scene with a few lights); the loop runs n times, which the branch predictor learns.
    uint32_t k = 0;
    for (uint32_t i = 0; i < n; ++i) k += !(u < cdf[i]) ? 1u : 0u;
    return k;
  }
  const uint32_t b = std::min(n - 1, uint32_t(std::max(0.0f, u) * float(n)));
  const uint32_t lo = std::min(guide[b], n), hi = std::min(n, guide[b + 1] + 1);
  uint32_t k = lo < hi ? uint32_t(std::upper_bound(cdf + lo, cdf + hi, u) - cdf) : lo;
  const bool exact = (k == 0 || !(cdf[k - 1] > u)) && (k == n || cdf[k] > u);
  if (!exact) k = uint32_t(std::upper_bound(cdf, cdf + n, u) - cdf);
  return k;
}

/// A bin picked by u from a CDF of n > 0 entries, and u stretched back to [0, 1) over the bin's
/// interval: a number independent of the pick, so a stratified u stays stratified within each
/// bin when it goes on to the next decision (0.5 for a bin of zero width, which u never picks).
struct CdfPick {
  uint32_t bin = 0;
  float u_remapped = 0.5f;
};

inline CdfPick PickCdfBin(const float* cdf, uint32_t n, const uint32_t* guide, float u) {
  const uint32_t k = std::min<uint32_t>(GuidedUpperBound(cdf, n, guide, u), n - 1);
  const float lo = k > 0 ? cdf[k - 1] : 0.0f, width = cdf[k] - lo;
  const float v = width > 0 ? std::min((u - lo) / width, kOneMinusEpsilon) : 0.5f;
  return {k, std::max(v, 0.0f)};
}

}  // namespace ptlab
