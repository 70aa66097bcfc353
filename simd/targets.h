// Highway target policy for ptlab: which targets are compiled. First include of every simd/ file.
#pragma once

// We compile AVX-512 (AVX3), AVX2 and SSE4 (a 128-bit target, so the two-iteration path of
// CappedTag<float, 8> stays tested), plus Highway's baseline fallback. SSSE3 adds nothing we
// use, and AVX3_DL only adds integer/crypto extensions.
#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SSSE3 | HWY_AVX3_DL)
#endif

#include <cstdlib>
#include <cstring>

namespace ptlab::simd {

/// True when PTLAB_FORCE_SCALAR=1 is set: every packet entry point routes through the scalar
/// oracle in engine/ (for A/B runs).
inline bool ForceScalar() {
  const char* v = std::getenv("PTLAB_FORCE_SCALAR");
  return v != nullptr && std::strcmp(v, "0") != 0 && v[0] != '\0';
}

}  // namespace ptlab::simd
