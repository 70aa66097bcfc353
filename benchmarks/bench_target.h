// Included by every benchmark that runs SIMD kernels: PTLAB_TARGET=AVX2 (say) pins them to that
// Highway target before the first benchmark runs (simd/target_select.h), so one machine
// measures each compiled target's ratios; a bad name stops the binary with exit 2.
#pragma once

#include <cstdio>
#include <cstdlib>

#include "simd/target_select.h"

namespace ptlab::bench {

inline const bool kTargetSelected = [] {
  const Status st = simd::SelectTargetFromEnvironment();
  if (!st.ok()) {
    std::fprintf(stderr, "error: %s\n", st.message().c_str());
    std::exit(2);
  }
  return true;
}();

}  // namespace ptlab::bench
