// The wavefront render path: a tile's paths as SoA packets through the stages of the kernel
// table (kernels.h); wave.h holds its state, wave.cpp the driver, wave_*.cpp the stages.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "engine/render/camera.h"
#include "engine/render/film.h"
#include "engine/render/filter.h"
#include "engine/render/packet_render.h"
#include "engine/wavefront/kernels.h"

namespace ptlab {

class Wavefront;  // wave.h

/// A worker thread's wavefront: path state, ray queues and per-bounce columns, kept from tile to
/// tile. Its containers are cleared between waves and tiles, never shrunk, so a thread
/// allocates in its first tiles only and Bytes() is its high-water mark.
class WavefrontWorkspace {
 public:
  WavefrontWorkspace();
  ~WavefrontWorkspace();
  WavefrontWorkspace(WavefrontWorkspace&&) noexcept;
  WavefrontWorkspace& operator=(WavefrontWorkspace&&) noexcept;

  /// Heap bytes of every queue and column: capacity × element size.
  size_t Bytes() const;
  /// The wavefront itself (wave.h; RenderTilePacket8 runs it).
  Wavefront& wave() { return *wave_; }

 private:
  std::unique_ptr<Wavefront> wave_;
};

/// Renders samples [s_begin, s_end) of pixels [x0, x1) x [y0, y1) into `block` as a wavefront:
/// the paths of a few pixel rows and all the samples are generated as camera packets of 4x2
/// pixels at one sample index, then bounce by bounce go through
///   traversal (intersect8 per packet) -> shading (emission, environment) -> sampling (emitter
///   samples, roulette, BSDF) -> shadow traversal (occluded8 per packet) -> accumulation,
/// the surviving paths' rays written into the next queue (grouped by material tag, each group in
/// queue order, a deterministic order that changes no result), so packets stay full. Each
/// path draws from its own Pcg32(PixelSeed(seed, pixel), s) in the scalar integrator's order
/// and samples are splatted in the scalar order (row, pixel, sample). With the oracle's table the
/// block is bit-identical to RenderTileScalar's; with simd/'s the BSDF, area-light request (its
/// BSDF evaluation), environment and distant-disk kernels differ from their oracles by a few
/// ulp (simd/wavefront/bsdf8.h, simd/wavefront/area_request8.h, simd/wavefront/environment8.h, simd/wavefront/distant_disk8.h), so the
/// image agrees with the oracle's within the render contract of tests/simd/traverse8_test.cpp
/// (relMSE, block means) but not bit for bit.
/// Every integrator type is supported. The paths run in `workspace` (one per thread, reused from
/// tile to tile; null: a workspace for this tile alone).
void RenderTilePacket8(const RenderContext& ctx, const WavefrontKernels& kernels,
                       const Camera& camera, const PixelFilter& filter, int x0, int y0, int x1,
                       int y1, uint32_t s_begin, uint32_t s_end, uint64_t seed, FilmBlock* block,
                       TileSampleStats* stats, const PixelSampling* pixels = nullptr,
                       WavefrontWorkspace* workspace = nullptr);

}  // namespace ptlab
