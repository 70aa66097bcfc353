// The wavefront's camera paths: each new path's random stream (PathSampler) and, with the
// independent sampler, its first draws: the film position inside its pixel and the lens point.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/vec.h"
#include "engine/render/packet_render.h"
#include "engine/sampling/sampler.h"

namespace ptlab {

/// One row per new path: its pixel (px, py) and sample index.
struct CameraPathInputs {
  const int32_t* px = nullptr;
  const int32_t* py = nullptr;
  const uint32_t* sample = nullptr;
};

/// Row k's path: its sampler after the camera's draws, its film position (px + jitter.x,
/// py + jitter.y) and lens point. sx, sy and lens are written by the independent sampler only.
struct CameraPathOutputs {
  PathSampler* sampler = nullptr;
  float* sx = nullptr;
  float* sy = nullptr;
  Vec2f* lens = nullptr;
};

/// The wavefront's camera-path slot, for rows [0, n): sampler[k] = PathSampler(type,
/// PixelSeed(seed, py·width + px), sample) and, when type is independent, the film jitter then
/// the lens point drawn from it (Get2D(kDimensionPixel), Get2D(kDimensionLens): the scalar
/// path's order), the sampler left after them. With `sobol` the wavefront draws those two
/// dimensions itself, in batches. Pixels: 0 <= px, py and py·width + px < 2^63.
/// SIMD twin: simd::StartCameraPaths (simd/wavefront/camera_paths8.h).
void StartCameraPaths(SamplerType type, uint64_t seed, uint64_t width, size_t n,
                      const CameraPathInputs& in, const CameraPathOutputs& out);

}  // namespace ptlab
