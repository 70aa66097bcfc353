// Splat stage: a wave's finished samples into the tile's film block. The contract (the batch
// it reads) and the scalar oracle; SIMD twin simd::SplatSamples (simd/wavefront/splat8.h).
#pragma once

#include <cstddef>

#include "engine/render/film.h"
#include "engine/render/filter.h"

namespace ptlab {

/// Samples to splat, SoA: continuous image positions and radiance, n rows.
struct FilmSamples {
  const float* sx = nullptr;
  const float* sy = nullptr;
  const float* r = nullptr;
  const float* g = nullptr;
  const float* b = nullptr;
  size_t n = 0;
};

/// Splats the samples in order into `block` (FilmBlock::Splat each): the scalar oracle of
/// simd::SplatSamples (simd/wavefront/splat8.h) and the oracle table's splat kernel (kernels.h).
void SplatSamples(const PixelFilter& filter, const FilmSamples& samples, FilmBlock* block);

}  // namespace ptlab
