// What both tile loops share (pixel seeds, tile statistics, adaptive-sampling state) and the
// scalar tile loop, one Li per sample; the wavefront is in wavefront.h.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/render/camera.h"
#include "engine/render/film.h"
#include "engine/render/filter.h"
#include "engine/render/bdpt.h"
#include "engine/render/integrator.h"

namespace ptlab {

struct WavefrontKernels;  // engine/wavefront/kernels.h

/// PixelSeed's stride between the render seeds: MixBits hashes seed * stride + pixel.
inline constexpr uint64_t kPixelSeedStride = 0x9e3779b97f4a7c15ULL;

/// Seed of a pixel's random streams; every sample s of the pixel uses Pcg32(PixelSeed, s).
/// RenderTileScalar and the wavefront (wavefront.h) both seed with it.
inline uint64_t PixelSeed(uint64_t seed, uint64_t pixel) {
  return MixBits(seed * kPixelSeedStride + pixel);
}

/// Thread time spent in each stage of the packet path (seconds of one thread, summed).
struct StageSeconds {
  double traversal = 0;  // intersect8 / occluded8 calls of the kernel table
  double shading = 0;    // hit points, emission, MIS weights, environment, accumulation
  double sampling = 0;   // camera rays, emitter samples, Russian roulette, BSDF sampling
  double film = 0;       // splatting into the film block

  StageSeconds& operator+=(const StageSeconds& o) {
    traversal += o.traversal, shading += o.shading, sampling += o.sampling, film += o.film;
    return *this;
  }
  double total() const { return traversal + shading + sampling + film; }
};

/// Luminance moments of one pixel's samples (adaptive sampling): `taken` counts every sample,
/// n, sum and sum2 the finite ones.
struct PixelMoments {
  uint32_t taken = 0, n = 0;
  double sum = 0, sum2 = 0;
};

/// Per-pixel sampling state of a render (image-sized, row-major, `width` pixels a row): which
/// pixels still take samples (null: all) and where their moments go (null: not recorded).
/// A tile reads and writes only its own pixels, so tiles on several threads share it.
struct PixelSampling {
  uint64_t width = 0;
  const uint8_t* active = nullptr;
  PixelMoments* moments = nullptr;
};

/// Records one sample of a pixel (its luminance when finite).
inline void AddPixelSample(const Color3f& L, PixelMoments* m) {
  ++m->taken;
  if (!IsFinite(L)) return;
  const double y = double(Luminance(L));
  ++m->n, m->sum += y, m->sum2 += y * y;
}

/// Rays traced and non-finite samples dropped while rendering one tile; the packet path also
/// counts packets (rays / (8 packets) is the lane occupancy) and times its stages.
struct TileSampleStats {
  uint64_t rays = 0;
  uint64_t packets = 0;
  uint64_t nonfinite = 0;
  int first_x = -1, first_y = -1;  // first dropped sample, in splat order
  StageSeconds seconds;
  /// Whether the wavefront times its stages into `seconds` (else they stay 0 and no clock is
  /// read per stage: task-clock of table's packet render -0.6 %, veach unchanged).
  bool time_stages = true;
  double wall_seconds = 0;  // the tile's wall time on its thread, set by the render driver
};

/// The scalar reference of RenderTilePacket8 (wavefront.h): one Li per sample, in the same
/// splat order. render.cpp uses it when no kernel table is given; tests and benchmarks compare
/// the two. For bdpt and ptracer (IsBidirectional) `bidirectional` must be given: each sample
/// is LiBidirectional's, and its light-tracing contributions are appended to *splats in sample
/// order (the caller merges them into a LightFilm).
void RenderTileScalar(const RenderContext& ctx, const Camera& camera, const PixelFilter& filter,
                      int x0, int y0, int x1, int y1, uint32_t s_begin, uint32_t s_end,
                      uint64_t seed, FilmBlock* block, TileSampleStats* stats,
                      const PixelSampling* pixels = nullptr,
                      const BidirectionalSetup* bidirectional = nullptr,
                      std::vector<LightSplat>* splats = nullptr);

/// bdpt and ptracer (IsBidirectional) as batches of kBidirectionalBatch samples in
/// RenderTileScalar's order (bdpt_batch.h): their rays through `kernels`' intersect8 and
/// occluded8 in packets (null: Intersect1 / Occluded1 one at a time). The same block and
/// splats, bit for bit, as RenderTileScalar's whenever the table's traversal is the oracle's
/// (every table's is).
void RenderTileBidirectional(const RenderContext& ctx, const WavefrontKernels* kernels,
                             const Camera& camera, const PixelFilter& filter, int x0, int y0,
                             int x1, int y1, uint32_t s_begin, uint32_t s_end, uint64_t seed,
                             FilmBlock* block, TileSampleStats* stats,
                             const BidirectionalSetup& bidirectional,
                             std::vector<LightSplat>* splats);

}  // namespace ptlab
