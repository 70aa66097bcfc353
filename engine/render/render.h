// The render driver: passes of samples over tiles on worker threads, deterministic film merge.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "engine/bvh/bvh.h"
#include "engine/image/image.h"
#include "engine/render/packet_render.h"
#include "engine/scene/scene.h"

namespace ptlab {

struct RenderProgress {
  uint64_t samples_done = 0, samples_total = 0;  // pixel samples
  uint64_t rays = 0;
  double seconds = 0;
};

struct RenderOptions {
  uint32_t spp = 1;
  int threads = 1;
  uint64_t seed = 0;
  /// Set (e.g. by a SIGINT handler) to stop; the image keeps every completed pass.
  const std::atomic<bool>* cancel = nullptr;
  /// When set, tiles run through the 8-wide packet path on this traversal backend (bit-identical
  /// to the scalar path); it must outlive the render. Null: one ray at a time, the oracle.
  const TraversalBackend8* packets = nullptr;
  /// Called from the coordinating thread after each tile completes.
  std::function<void(const RenderProgress&)> on_progress;
};

struct RenderResult {
  Image image;
  uint32_t spp_done = 0;       // samples per pixel in the image (< spp when interrupted)
  bool interrupted = false;
  std::string error;  // non-empty: the render could not run (e.g. its threads did not start)
  double seconds = 0;
  uint64_t rays = 0;
  uint64_t nonfinite_samples = 0;  // dropped, never splatted
  int first_nonfinite_x = -1, first_nonfinite_y = -1;
  /// Packet path only: packets traced and the thread time of each stage (all threads summed).
  uint64_t packets = 0;
  StageSeconds stage_seconds;
};

/// Renders scene.camera's image with the scene's integrator. The image is a function of
/// (scene, spp, seed) only: every pixel sample has its own random stream, and tile blocks are
/// merged in tile order, so any thread count gives the same bits.
RenderResult Render(const Scene& scene, const Bvh& bvh, const RenderOptions& options);

/// Samples per pass for a render of spp samples (passes are the unit kept on interruption).
uint32_t SamplesPerPass(uint32_t spp);

}  // namespace ptlab
