// 8-wide render path: camera rays in 4x2-pixel packets and batched shadow rays, traced through a
// registered packet backend, with scalar shading that reproduces the scalar integrators' bits.
#pragma once

#include <cstdint>

#include "engine/bvh/bvh.h"
#include "engine/core/packet8.h"
#include "engine/render/camera.h"
#include "engine/render/film.h"
#include "engine/render/filter.h"
#include "engine/render/integrator.h"

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

/// Rays traced and non-finite samples dropped while rendering one tile.
struct TileSampleStats {
  uint64_t rays = 0;
  uint64_t nonfinite = 0;
  int first_x = -1, first_y = -1;  // first dropped sample, in splat order
};

/// Renders samples [s_begin, s_end) of pixels [x0, x1) x [y0, y1) into `block`, like the scalar
/// tile loop of render.cpp, but eight samples at a time: the lanes are the 4x2 pixels of a
/// tile block at the same sample index, so camera rays, bounce rays and shadow rays go to the
/// backend as packets. Each lane draws from its own Pcg32(PixelSeed(seed, pixel), s) in the
/// scalar integrator's order, shading is the scalar code, and samples are splatted in the
/// scalar order (row, then pixel, then sample), so with a backend that returns the oracle's
/// hits (simd::Intersect8 does, bit for bit) the block is bit-identical to the scalar one.
/// Every integrator type is supported.
void RenderTilePacket8(const RenderContext& ctx, const TraversalBackend8& backend,
                       const Camera& camera, const PixelFilter& filter, int x0, int y0, int x1,
                       int y1, uint32_t s_begin, uint32_t s_end, uint64_t seed, FilmBlock* block,
                       TileSampleStats* stats);

/// The scalar reference of RenderTilePacket8: render.cpp's tile loop (Li per sample). Kept
/// here so that tests and benchmarks can compare the two paths before and after wiring.
void RenderTileScalar(const RenderContext& ctx, const Camera& camera, const PixelFilter& filter,
                      int x0, int y0, int x1, int y1, uint32_t s_begin, uint32_t s_end,
                      uint64_t seed, FilmBlock* block, TileSampleStats* stats);

}  // namespace ptlab
