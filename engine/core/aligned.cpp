// Column allocation: cache-line aligned, large columns on transparent huge pages.
#include "engine/core/aligned.h"

#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace ptlab {

void* AllocateColumn(std::size_t bytes) {
  if (bytes < kHugePageBytes) return ::operator new(bytes, std::align_val_t(kColumnAlignment));
  void* p = ::operator new(bytes, std::align_val_t(kHugePageBytes));
#if defined(MADV_HUGEPAGE)
  // Advice only: where the kernel has no huge pages to give (or THP is off), the column simply
  // stays on 4 KiB pages, so a failure here is no error.
  (void)madvise(p, bytes, MADV_HUGEPAGE);
#endif
  return p;
}

void FreeColumn(void* p, std::size_t bytes) {
  ::operator delete(p,
                    std::align_val_t(bytes < kHugePageBytes ? kColumnAlignment : kHugePageBytes));
}

}  // namespace ptlab
