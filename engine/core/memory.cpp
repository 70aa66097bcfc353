// The process's peak resident set size (getrusage).
#include "engine/core/memory.h"

#include <sys/resource.h>

namespace ptlab {

uint64_t PeakResidentBytes() {
  struct rusage usage {};
  if (getrusage(RUSAGE_SELF, &usage) != 0 || usage.ru_maxrss <= 0) return 0;
  return uint64_t(usage.ru_maxrss) * 1024;  // Linux: KiB
}

}  // namespace ptlab
