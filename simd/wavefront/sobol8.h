// Vectorized sampler: Owen-scrambled Sobol' points of 8 path samples at once (plain API).
#pragma once

#include <cstddef>
#include <cstdint>

namespace ptlab::simd {

// 8-wide Highway kernels (hn::CappedTag<uint32_t, 8>) of the batch oracles in
// engine/wavefront/sobol.h, chosen at run time among the compiled targets. The sampler is
// integer arithmetic (hashes, bit reversal, the Laine-Karras
// permutation, dimension 1 from byte tables) and one exact conversion to float, so the
// results are bit-identical to the oracle's on every target (tests/simd/wavefront/sobol8_test.cpp).
// Arrays hold n rows (any n); outputs may not alias inputs.

/// Oracle: ptlab::ScrambledSobol2DBatch.
void ScrambledSobol2DBatch(const uint32_t* pixel_seed, const uint32_t* index, uint32_t dim,
                           size_t n, float* x, float* y);

/// Oracle: ptlab::ScrambledSobol1DBatch.
void ScrambledSobol1DBatch(const uint32_t* pixel_seed, const uint32_t* index, uint32_t dim,
                           size_t n, float* x);

}  // namespace ptlab::simd
