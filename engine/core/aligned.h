// Cache-line aligned storage for SoA component columns.
#pragma once

#include <cstddef>
#include <vector>

namespace ptlab {

inline constexpr std::size_t kColumnAlignment = 64;

/// Columns of at least this many bytes are aligned to a 2 MiB huge page and offered to the
/// kernel's transparent huge pages (madvise), as Embree does for its BVH: traversal of a large
/// scene visits nodes and leaves all over megabytes of memory, and with 4 KiB pages those
/// visits also wait on page walks (measured: the 1 M-triangle terrain's bounce rays traverse
/// 5-7 % faster on huge pages, see docs/traversal.md).
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

/// Aligned allocation of `bytes` for a column (kColumnAlignment, or kHugePageBytes with the
/// huge-page advice from kHugePageBytes on); FreeColumn takes the same `bytes` back.
void* AllocateColumn(std::size_t bytes);
void FreeColumn(void* p, std::size_t bytes);

/// Allocator that aligns every column to a cache line (and to any SIMD width we use).
template <typename T>
struct AlignedAllocator {
  using value_type = T;
  AlignedAllocator() = default;
  template <typename U>
  AlignedAllocator(const AlignedAllocator<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(AllocateColumn(n * sizeof(T))); }
  void deallocate(T* p, std::size_t n) { FreeColumn(p, n * sizeof(T)); }
  template <typename U>
  bool operator==(const AlignedAllocator<U>&) const { return true; }
};

template <typename T>
using AlignedVector = std::vector<T, AlignedAllocator<T>>;

}  // namespace ptlab
