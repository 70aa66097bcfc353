// The scalar tile loop (Li per sample) and the bidirectional one (batches of samples,
// bdpt_batch.h); the packet path (the wavefront) is engine/wavefront/.
#include "engine/render/packet_render.h"

#include <tuple>
#include <utility>

#include "engine/render/bdpt_batch.h"

namespace ptlab {

void RenderTileScalar(const RenderContext& ctx, const Camera& camera, const PixelFilter& filter,
                      int x0, int y0, int x1, int y1, uint32_t s_begin, uint32_t s_end,
                      uint64_t seed, FilmBlock* block, TileSampleStats* stats,
                      const PixelSampling* pixels, const BidirectionalSetup* bidirectional,
                      std::vector<LightSplat>* splats) {
  RayCounters counters;
  const uint64_t width = uint64_t(camera.width());
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const uint64_t pixel = uint64_t(y) * width + uint64_t(x);
      if (pixels && pixels->active && !pixels->active[pixel]) continue;
      PixelMoments* moments = pixels && pixels->moments ? &pixels->moments[pixel] : nullptr;
      for (uint32_t s = s_begin; s < s_end; ++s) {
        PathSampler sampler(ctx.scene.sampler.type, PixelSeed(seed, pixel), s);
        const Vec2f jitter = sampler.Get2D(kDimensionPixel);
        const Vec2f lens = sampler.Get2D(kDimensionLens);
        const float sx = float(x) + jitter.x, sy = float(y) + jitter.y;
        const Ray ray = camera.GenerateRay(sx, sy, lens);
        const Color3f L = bidirectional != nullptr
                              ? LiBidirectional(ctx, *bidirectional, ray, sampler, &counters, splats)
                              : Li(ctx, ray, sampler, &counters);
        if (moments) AddPixelSample(L, moments);
        if (!IsFinite(L)) {
          if (stats->nonfinite++ == 0) stats->first_x = x, stats->first_y = y;
          continue;
        }
        block->Splat(filter, sx, sy, L);
      }
    }
  }
  stats->rays += counters.rays;
}

void RenderTileBidirectional(const RenderContext& ctx, const WavefrontKernels* kernels,
                             const Camera& camera, const PixelFilter& filter, int x0, int y0,
                             int x1, int y1, uint32_t s_begin, uint32_t s_end, uint64_t seed,
                             FilmBlock* block, TileSampleStats* stats,
                             const BidirectionalSetup& bidirectional,
                             std::vector<LightSplat>* splats) {
  BidirectionalTracer tracer{.bvh = &ctx.bvh, .kernels = kernels};
  const uint64_t width = uint64_t(camera.width());
  std::vector<BidirectionalSampleInput> batch;
  std::vector<Vec2f> film_pos;
  std::vector<std::pair<int, int>> pixel_of;  // for the first dropped sample's report
  batch.reserve(kBidirectionalBatch), film_pos.reserve(kBidirectionalBatch);
  Color3f L[kBidirectionalBatch];
  // The batch's samples go on the film in sample order, as RenderTileScalar splats them.
  auto flush = [&] {
    TraceBidirectionalBatch(ctx, bidirectional, &tracer, batch, L, splats);
    for (size_t i = 0; i < batch.size(); ++i) {
      const float sx = film_pos[i].x, sy = film_pos[i].y;
      if (!IsFinite(L[i])) {
        if (stats->nonfinite++ == 0) std::tie(stats->first_x, stats->first_y) = pixel_of[i];
        continue;
      }
      block->Splat(filter, sx, sy, L[i]);
    }
    batch.clear(), film_pos.clear(), pixel_of.clear();
  };
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const uint64_t pixel = uint64_t(y) * width + uint64_t(x);
      for (uint32_t s = s_begin; s < s_end; ++s) {
        PathSampler sampler(ctx.scene.sampler.type, PixelSeed(seed, pixel), s);
        const Vec2f jitter = sampler.Get2D(kDimensionPixel);
        const Vec2f lens = sampler.Get2D(kDimensionLens);
        const float sx = float(x) + jitter.x, sy = float(y) + jitter.y;
        batch.push_back({camera.GenerateRay(sx, sy, lens), sampler});
        film_pos.push_back({sx, sy});
        pixel_of.push_back({x, y});
        if (batch.size() == kBidirectionalBatch) flush();
      }
    }
  }
  if (!batch.empty()) flush();
  stats->rays += tracer.rays;
  stats->packets += tracer.packets;
}

}  // namespace ptlab
