// Cache-line aligned storage for SoA component columns.
#pragma once

#include <cstddef>
#include <new>
#include <vector>

namespace ptlab {

inline constexpr std::size_t kColumnAlignment = 64;

/// Allocator that aligns every column to a cache line (and to any SIMD width we use).
template <typename T>
struct AlignedAllocator {
  using value_type = T;
  AlignedAllocator() = default;
  template <typename U>
  AlignedAllocator(const AlignedAllocator<U>&) {}
  T* allocate(std::size_t n) {
    return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(kColumnAlignment)));
  }
  void deallocate(T* p, std::size_t) { ::operator delete(p, std::align_val_t(kColumnAlignment)); }
  template <typename U>
  bool operator==(const AlignedAllocator<U>&) const { return true; }
};

template <typename T>
using AlignedVector = std::vector<T, AlignedAllocator<T>>;

}  // namespace ptlab
