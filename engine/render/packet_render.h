// 8-wide render path: a wavefront of camera, bounce and shadow rays in compacted packet queues,
// traced through a registered packet backend; shading reproduces the scalar integrators' bits.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/bvh/bvh.h"
#include "engine/core/packet8.h"
#include "engine/render/camera.h"
#include "engine/render/film.h"
#include "engine/render/filter.h"
#include "engine/render/integrator.h"
#include "engine/sampling/sobol.h"

namespace ptlab {

/// Packet traversal entry points, registered by the binary that links simd/ (engine/ never
/// includes simd/ or hwy/). `accel` is handed back to the functions unchanged. Contract of
/// both functions: Intersect8 / Occluded8 of simd/traverse8.h (only lanes in `active` are
/// read; a lane that misses or is inactive is not written).
struct TraversalBackend8 {
  const void* accel = nullptr;
  Mask8 (*intersect8)(const void* accel, const RayPacket8& rays, Mask8 active,
                      HitPacket8* hits) = nullptr;
  Mask8 (*occluded8)(const void* accel, const RayPacket8& rays, Mask8 active) = nullptr;
  /// The Sobol' sampler's batch draws (engine/sampling/sobol.h; contract: bit-identical to
  /// those oracles, which are the defaults). The wavefront draws a decision's numbers for all
  /// its paths with one call when the scene's sampler is `sobol`.
  void (*sobol2d)(const uint32_t* pixel_seed, const uint32_t* index, uint32_t dim, size_t n,
                  float* x, float* y) = ScrambledSobol2DBatch;
  void (*sobol1d)(const uint32_t* pixel_seed, const uint32_t* index, uint32_t dim, size_t n,
                  float* x) = ScrambledSobol1DBatch;
  const char* name = "";
};

/// A backend that traces each lane with the scalar oracle (Intersect1 / Occluded1) on `bvh`,
/// which must outlive it: the packet render path with the reference traversal.
TraversalBackend8 ScalarTraversalBackend(const Bvh& bvh);

/// Seed of a pixel's random streams; every sample s of the pixel uses Pcg32(PixelSeed, s).
/// Must stay the seed render.cpp's scalar RenderTile uses.
inline uint64_t PixelSeed(uint64_t seed, uint64_t pixel) {
  return MixBits(seed * 0x9e3779b97f4a7c15ULL + pixel);
}

/// Thread time spent in each stage of the packet path (seconds of one thread, summed).
struct StageSeconds {
  double traversal = 0;  // Intersect8 / Occluded8 calls of the backend
  double shading = 0;    // hit points, emission, MIS weights, environment, accumulation
  double sampling = 0;   // camera rays, emitter samples, Russian roulette, BSDF sampling
  double film = 0;       // splatting into the film block

  StageSeconds& operator+=(const StageSeconds& o) {
    traversal += o.traversal, shading += o.shading, sampling += o.sampling, film += o.film;
    return *this;
  }
  double total() const { return traversal + shading + sampling + film; }
};

/// Rays traced and non-finite samples dropped while rendering one tile; the packet path also
/// counts packets (rays / (8 packets) is the lane occupancy) and times its stages.
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

struct TileSampleStats {
  uint64_t rays = 0;
  uint64_t packets = 0;
  uint64_t nonfinite = 0;
  int first_x = -1, first_y = -1;  // first dropped sample, in splat order
  StageSeconds seconds;
  double wall_seconds = 0;  // the tile's wall time on its thread, set by the render driver
};

/// Renders samples [s_begin, s_end) of pixels [x0, x1) x [y0, y1) into `block` as a wavefront
/// (wavefront.cpp): the paths of a few pixel rows and all the samples are generated as camera
/// packets of 4x2 pixels at one sample index, then bounce by bounce go through
///   traversal (Intersect8 per packet) -> shading (emission, environment) -> sampling (emitter
///   samples, roulette, BSDF) -> shadow traversal (Occluded8 per packet) -> accumulation,
/// the surviving paths' rays pushed in order into the next queue, so packets stay full. Each
/// path draws from its own Pcg32(PixelSeed(seed, pixel), s) in the scalar integrator's order
/// and samples are splatted in the scalar order (row, pixel, sample), so with a backend that
/// returns the oracle's hits (simd::Intersect8 does, bit for bit) the block is bit-identical to
/// RenderTileScalar's. Every integrator type is supported.
void RenderTilePacket8(const RenderContext& ctx, const TraversalBackend8& backend,
                       const Camera& camera, const PixelFilter& filter, int x0, int y0, int x1,
                       int y1, uint32_t s_begin, uint32_t s_end, uint64_t seed, FilmBlock* block,
                       TileSampleStats* stats, const PixelSampling* pixels = nullptr);

/// The scalar reference of RenderTilePacket8: one Li per sample, in the same splat order.
/// render.cpp uses it when no packet backend is given; tests and benchmarks compare the two.
void RenderTileScalar(const RenderContext& ctx, const Camera& camera, const PixelFilter& filter,
                      int x0, int y0, int x1, int y1, uint32_t s_begin, uint32_t s_end,
                      uint64_t seed, FilmBlock* block, TileSampleStats* stats,
                      const PixelSampling* pixels = nullptr);

}  // namespace ptlab
