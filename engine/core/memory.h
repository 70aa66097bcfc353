// Memory accounting: heap bytes of containers (capacity × element size) and the peak RSS.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ptlab {

/// Heap bytes a vector holds: capacity × element size (what it allocated, used or not).
/// Elements must own no heap memory of their own (see StringsBytes for strings).
template <typename T, typename Allocator>
size_t VectorBytes(const std::vector<T, Allocator>& v) {
  return v.capacity() * sizeof(T);
}

/// The sum of VectorBytes over several vectors.
template <typename... Vectors>
size_t VectorsBytes(const Vectors&... v) {
  return (size_t{0} + ... + VectorBytes(v));
}

/// Heap bytes of a vector of strings: the vector, plus each string's buffer when it is longer
/// than the in-object (short-string) buffer.
inline size_t StringsBytes(const std::vector<std::string>& v) {
  const size_t inline_capacity = std::string().capacity();
  size_t bytes = VectorBytes(v);
  for (const std::string& s : v)
    if (s.capacity() > inline_capacity) bytes += s.capacity() + 1;  // + the terminating NUL
  return bytes;
}

/// The peak resident set size of this process so far, in bytes (getrusage's ru_maxrss, which
/// Linux reports in KiB); 0 when the system does not report it.
uint64_t PeakResidentBytes();

}  // namespace ptlab
