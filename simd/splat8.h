// Vectorized film splatting through the pixel filter's table (plain API).
#pragma once

#include "engine/render/film.h"
#include "engine/render/filter.h"

namespace ptlab::simd {

/// Splats the samples in order into `block`: each sample's filter taps from the table
/// (PixelFilter::Eval), then every touched pixel's r, g, b, w accumulators as one 4-lane vector
/// (hn::CappedTag<float, 4>). Gathering the taps 8-wide was measured slower (AVX3 on AMD EPYC:
/// 9.2 % of a veach render against 5.3 %). Oracle: ptlab::SplatSamples (FilmBlock::Splat per
/// sample). Contract: the block's sums are bit-identical to the oracle's on every target (the
/// same float operations in the same order per accumulator; FMA contraction is off).
/// tests/simd/splat8_test.cpp.
void SplatSamples(const PixelFilter& filter, const FilmSamples& samples, FilmBlock* block);

/// Name of the Highway target SplatSamples dispatches to now; for logs and tests.
const char* SplatTargetName();

}  // namespace ptlab::simd
