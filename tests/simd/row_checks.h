// What the SIMD-vs-oracle tests of the wavefront's row stages share: garbage to fill the rows
// a kernel must not write, and the byte-for-byte comparison of whole columns.
#pragma once

#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include "engine/core/rng.h"

namespace ptlab::test {

inline constexpr float kInf = std::numeric_limits<float>::infinity();
inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
inline constexpr float kGarbage = -7.25f;
inline constexpr uint32_t kGarbageU = 0xdeadbeefu;

/// Same length and the same bytes (floats: the same bits, NaN payloads and -0 included).
/// Empty vectors may hold null data(), which memcmp must not be given (UBSan: nonnull).
template <class T>
bool SameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

/// A random permutation of 0, 1, ..., n - 1 (Fisher-Yates from the back): distinct path ids
/// for a batch's rows.
inline std::vector<uint32_t> Shuffled(Pcg32& rng, size_t n) {
  std::vector<uint32_t> v(n);
  std::iota(v.begin(), v.end(), 0u);
  for (size_t i = n; i > 1;) {
    --i;
    std::swap(v[i], v[rng.NextUint() % (i + 1)]);
  }
  return v;
}

/// n distinct values of [0, m) in random order (a partial Fisher-Yates from the front): a
/// batch's queue entries.
inline std::vector<uint32_t> DistinctRows(Pcg32& rng, size_t m, size_t n) {
  std::vector<uint32_t> v(m);
  std::iota(v.begin(), v.end(), 0u);
  for (size_t i = 0; i < n; ++i) std::swap(v[i], v[i + rng.NextUint() % (m - i)]);
  v.resize(n);
  return v;
}

}  // namespace ptlab::test
