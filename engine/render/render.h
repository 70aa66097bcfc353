// The render driver: passes of samples over tiles on worker threads, deterministic film merge.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>
#include <string>

#include "engine/bvh/bvh.h"
#include "engine/image/image.h"
#include "engine/render/film.h"
#include "engine/render/packet_render.h"
#include "engine/scene/scene.h"

namespace ptlab {

struct WavefrontKernels;  // engine/wavefront/wavefront.h

struct RenderProgress {
  uint64_t samples_done = 0, samples_total = 0;  // pixel samples
  uint64_t rays = 0;
  double seconds = 0;
};

/// Shares the tiles of every pass among several processes (MPI ranks, tools/mpi/). The driver
/// stays the same: each process renders the tiles this hands it, and after the pass the blocks of
/// all tiles are brought to the process that keeps the film, which merges them in tile order as
/// one process would, so the image does not depend on how the work was shared.
struct RenderDistribution {
  /// The next tile of pass `pass` this process renders (called by worker threads); a value
  /// >= tile_count means the pass has no tiles left.
  std::function<size_t(uint32_t pass, size_t tile_count)> next_tile;
  /// Called by the coordinating thread after this process's workers stopped. `complete` says
  /// whether every tile this process took was rendered (false when cancelled); `rendered[i]` is
  /// set for the tiles it rendered into blocks[i] / stats[i]. Returns whether the pass completed
  /// in every process; when it did, blocks and stats hold every tile on the film's process.
  std::function<bool(uint32_t pass, bool complete, const std::vector<uint8_t>& rendered,
                     std::vector<FilmBlock>* blocks, std::vector<TileSampleStats>* stats)>
      finish_pass;
  /// Whether this process merges and keeps the film (one process does).
  bool keeps_film = true;
};

/// CS184's adaptive sampling (pathtracer -a batch tolerance): every `batch` samples, a pixel
/// whose luminance has a 95 % confidence interval within tolerance of its mean stops taking
/// samples (PixelConverged). batch = 0: off, every pixel takes spp samples.
struct AdaptiveSampling {
  uint32_t batch = 0;
  float tolerance = 0.05f;
};

/// Fewest finite samples after which a pixel may stop (adaptive sampling).
inline constexpr uint32_t kAdaptiveMinSamples = 32;

/// The stopping rule: n >= kAdaptiveMinSamples finite samples with mean μ > 0 and sample
/// variance σ² of their luminance, and 1.96 σ / sqrt(n) <= tolerance · μ (CS184's
/// I <= maxTolerance · μ). CS184's rule alone stops a pixel whose first batch is all black
/// (0 <= 0): one that missed a small light keeps it black. Here a pixel that has seen no light
/// never stops early (it takes every sample, as without adaptive sampling), and the minimum
/// count bounds the chance of stopping on a lucky batch: a light hit by a fraction q of a pixel's
/// samples is missed by all of 32 with probability (1 − q)^32 (< 4 % for q = 0.1); the stopping
/// decision still depends on the samples, a bias the block t-test against a non-adaptive render
/// measures (docs/chi2-power.md).
bool PixelConverged(const PixelMoments& m, float tolerance);

/// One completed pass, handed to RenderOptions::on_pass on the process that keeps the film.
struct RenderPass {
  uint32_t index = 0;     // 0, 1, ...
  uint32_t spp_done = 0;  // samples per pixel in the film, this pass included
  /// Render time since the start, without the time spent in on_pass itself (so that a caller
  /// measuring error after each pass does not slow the clock it reports).
  double seconds = 0;
  /// CPU time of the process (all threads) since the start, on_pass left out likewise: the
  /// render's cost without the noise of other work on the machine (this process only when the
  /// render is distributed).
  double cpu_seconds = 0;
  const FilmBlock* film = nullptr;                 // every completed pass, merged
  const std::vector<FilmBlock>* blocks = nullptr;  // this pass's tile blocks, in merge order
  /// Adaptive sampling: every pixel's moments after this pass (row-major); else null.
  const std::vector<PixelMoments>* pixels = nullptr;
};

struct RenderOptions {
  uint32_t spp = 1;
  int threads = 1;
  uint64_t seed = 0;
  /// Set (e.g. by a SIGINT handler) to stop; the image keeps every completed pass.
  const std::atomic<bool>* cancel = nullptr;
  /// When set, tiles run through the wavefront (RenderTilePacket8, wavefront.h) with this kernel
  /// table: the oracle's (bit-identical to the scalar loop) or simd/'s (within the render
  /// contract of RenderTilePacket8); it must outlive the render. Null: the scalar loop, one Li per sample (RenderTileScalar).
  const WavefrontKernels* kernels = nullptr;
  /// > 0: no pass starts once this many seconds of rendering have passed (the image keeps
  /// the passes done; spp is then an upper bound). Not with a distribution.
  double time_budget = 0;
  /// Adaptive sampling (passes are then `batch` samples). Not with a distribution.
  AdaptiveSampling adaptive;
  /// Samples per pixel of each pass (the last one may be shorter); 0: SamplesPerPass(spp).
  /// The image does not depend on it (every sample has its own stream); what a pass is does:
  /// on_pass, the time budget, the tile times. Ignored with adaptive sampling.
  uint32_t pass_spp = 0;
  /// When set, the tiles of each pass are shared with other processes through it.
  const RenderDistribution* distribution = nullptr;
  /// Called from the coordinating thread after each tile completes.
  std::function<void(const RenderProgress&)> on_progress;
  /// Called from the coordinating thread after each completed pass (e.g. to measure the error
  /// of the image so far, or to accumulate passes into several films).
  std::function<void(const RenderPass&)> on_pass;
  /// Time the wavefront's stages (RenderResult::stage_seconds, ptlab's --stats); off, they
  /// stay 0 (TileSampleStats::time_stages).
  bool time_stages = false;
};

/// Heap bytes a render held at its end (capacity × element size of the containers).
struct RenderMemory {
  /// The wavefronts' path state, queues and columns: each worker thread's high-water mark,
  /// summed over the threads (0 on the scalar path, which has none).
  uint64_t wavefront = 0;
  /// The film and the tile blocks (one per tile, filter border included).
  uint64_t film = 0;
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
  /// Wall time of every tile of every completed pass on the thread that rendered it (pass-major,
  /// tiles in row order): the unit costs that load balancing has to even out.
  std::vector<float> tile_seconds;
  int tile_count = 0;
  /// Adaptive sampling: the samples each pixel took (row-major), summing to samples_taken.
  std::vector<uint32_t> pixel_samples;
  uint64_t samples_taken = 0;  // every pixel sample of the completed passes
  RenderMemory memory;
};

/// Renders scene.camera's image with the scene's integrator. The image is a function of
/// (scene, spp, seed) only: every pixel sample has its own random stream, and tile blocks are
/// merged in tile order, so any thread count gives the same bits. bdpt and ptracer also splat
/// into other tiles' pixels: each tile's splats are merged into the pass's light film in tile
/// order as tiles complete (a tile waits for the tiles before it), never with atomics, and the
/// light film joins the camera's film after each complete pass (LightFilm::ComposeInto). With a
/// kernel table they run as batches of samples through its packet traversal
/// (RenderTileBidirectional), without one one sample at a time (RenderTileScalar), the same
/// bits either way; they refuse adaptive sampling and a distribution (RenderResult::error).
RenderResult Render(const Scene& scene, const Bvh& bvh, const RenderOptions& options);

/// Samples per pass for a render of spp samples (passes are the unit kept on interruption).
uint32_t SamplesPerPass(uint32_t spp);

/// The samples per pass of a render with these options (adaptive batch, pass_spp or
/// SamplesPerPass), at least 1.
uint32_t PassSamples(const RenderOptions& options);

}  // namespace ptlab
