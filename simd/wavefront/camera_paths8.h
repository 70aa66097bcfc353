// Vectorized camera paths: each new path's PathSampler and first draws (plain API).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/wavefront/camera_paths.h"

namespace ptlab::simd {

/// ptlab::StartCameraPaths, a vector of rows per step (hn::CappedTag<uint64_t, 8>: eight rows
/// on AVX-512, four on AVX2, two on SSE4): the pixel seed (MixBits), the PCG32 stream's
/// seeding and, for the independent sampler, its four draws from one state each (Pcg32Advance:
/// two multiplies that do not wait on each other, where the oracle steps four times), stored
/// with interleaving stores (PathSampler rows, lens points); the last rows take the oracle.
/// Oracle: ptlab::StartCameraPaths. Contract: every output bit-identical to the oracle's on
/// every target (integer operations mod 2^64 and exact conversions; PathSampler's padding
/// bytes are written as zero). tests/simd/wavefront/camera_paths8_test.cpp.
void StartCameraPaths(SamplerType type, uint64_t seed, uint64_t width, size_t n,
                      const CameraPathInputs& in, const CameraPathOutputs& out);

}  // namespace ptlab::simd
