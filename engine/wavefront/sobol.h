// Sampling stage, Sobol' numbers: the batch draws of a decision's numbers for all the wave's
// paths (slots sobol2d and sobol1d) and their scalar oracle, the sampler of
// engine/sampling/sobol.h row by row; SIMD twin simd/wavefront/sobol8.h, bit-identical.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/sampling/sobol.h"

namespace ptlab {

/// Batch form, the scalar oracle of simd::ScrambledSobol2DBatch: row i is point index[i] of
/// dimension `dim` of the pixel with 32-bit seed pixel_seed[i] (DimensionSeeds).
inline void ScrambledSobol2DBatch(const uint32_t* pixel_seed, const uint32_t* index, uint32_t dim,
                                  size_t n, float* x, float* y) {
  for (size_t i = 0; i < n; ++i) {
    const Vec2f p = ScrambledSobol2D(index[i], DimensionSeeds(pixel_seed[i], dim));
    x[i] = p.x, y[i] = p.y;
  }
}

/// Batch form of ScrambledSobol1D (oracle of simd::ScrambledSobol1DBatch).
inline void ScrambledSobol1DBatch(const uint32_t* pixel_seed, const uint32_t* index, uint32_t dim,
                                  size_t n, float* x) {
  for (size_t i = 0; i < n; ++i) x[i] = ScrambledSobol1D(index[i], DimensionSeeds(pixel_seed[i], dim));
}

}  // namespace ptlab
