// Highway target policy for ptlab: which targets are compiled. First include of every simd/ file.
#pragma once

// We compile AVX-512 (AVX3), AVX2 and SSE4 (a 128-bit target, so the two-iteration path of
// CappedTag<float, 8> stays tested), plus Highway's baseline fallback. SSSE3 adds nothing we
// use, and AVX3_DL only adds integer/crypto extensions.
#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SSSE3 | HWY_AVX3_DL)
#endif
