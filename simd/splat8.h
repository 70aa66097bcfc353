// Vectorized film splatting through the pixel filter's table (plain API).
#pragma once

#include "engine/render/film.h"
#include "engine/render/filter.h"

namespace ptlab::simd {

/// Splats the samples in order into `block`. Filters are separable, so per sample one 8-lane
/// PixelFilter::Eval (two table gathers) gives its x taps (lanes 0-3) and y taps (lanes 4-7);
/// each footprint row is then one vector of (r, g, b, w) accumulators per 4 pixels (AVX3) or
/// per 2 (AVX2), wx·wy·(r, g, b, 1) added with FilmBlock::Splat's operations lane by lane.
/// Samples with more than 4 taps on an axis, and 128-bit targets, take a per-pixel path (one
/// pixel's r, g, b, w per 4-lane vector). Measured (benchmarks/splat_bench.cpp, Gaussian radius
/// 2, AVX3, Xeon): 44 M samples/s against the per-pixel path's 23 and the oracle's 17.
/// Oracle: ptlab::SplatSamples (FilmBlock::Splat per sample). Contract: the block's sums are
/// bit-identical to the oracle's on every target (the same float operations in the same order
/// per accumulator; FMA contraction is off). tests/simd/splat8_test.cpp.
void SplatSamples(const PixelFilter& filter, const FilmSamples& samples, FilmBlock* block);

/// Name of the Highway target SplatSamples dispatches to now; for logs and tests.
const char* SplatTargetName();

}  // namespace ptlab::simd
