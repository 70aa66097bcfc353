// Vectorized film splatting through the pixel filter's table (plain API).
#pragma once

#include "engine/render/filter.h"
#include "engine/wavefront/splat.h"

namespace ptlab::simd {

/// Splats the samples in order into `block`. Filters are separable: eight samples at a time,
/// their footprints and 4 x and 4 y taps (PixelFilter::Eval's table, read by gathers) are
/// vectors over the samples; then each footprint row is whole vectors of (r, g, b, w)
/// accumulators (4 pixels per AVX3 vector, 2 per AVX2 one), wx·wy·(r, g, b, 1) with
/// FilmBlock::Splat's operations lane by lane. Samples with more than 4 taps on an axis, the
/// samples after the last whole group of eight, groups with a position of magnitude 2^24 or more
/// and 128-bit targets take a per-pixel path (one pixel's r, g, b, w per 4-lane vector). Measured
/// (benchmarks/splat_bench.cpp, Gaussian radius 2, Xeon): 62-65 M samples/s on AVX3 against
/// 46 with the taps evaluated per sample (a latency chain per sample), 23 for the per-pixel
/// path and 16 for the oracle. Oracle: ptlab::SplatSamples (FilmBlock::Splat per sample).
/// Contract: the block's sums are bit-identical to the oracle's on every target (the same float
/// operations in the same order per accumulator; FMA contraction is off).
/// tests/simd/wavefront/splat8_test.cpp.
void SplatSamples(const PixelFilter& filter, const FilmSamples& samples, FilmBlock* block);

}  // namespace ptlab::simd
