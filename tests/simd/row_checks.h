// What the SIMD-vs-oracle tests of the wavefront's row stages share: garbage to fill the rows
// a kernel must not write, and the byte-for-byte comparison of whole columns.
#pragma once

#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace ptlab::test {

inline constexpr float kInf = std::numeric_limits<float>::infinity();
inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
inline constexpr float kGarbage = -7.25f;
inline constexpr uint32_t kGarbageU = 0xdeadbeefu;

/// Same length and the same bytes (floats: the same bits, NaN payloads and -0 included).
template <class T>
bool SameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

}  // namespace ptlab::test
