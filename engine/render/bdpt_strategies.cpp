// Per-strategy images of bidirectional path tracing (bdpt_strategies.h).
#include "engine/render/bdpt_strategies.h"

#include <algorithm>
#include <map>
#include <utility>

#include "engine/render/bdpt_batch.h"
#include "engine/render/camera.h"
#include "engine/render/film.h"
#include "engine/render/filter.h"
#include "engine/render/light_film.h"
#include "engine/render/packet_render.h"

namespace ptlab {

std::vector<StrategyImage> RenderStrategyImages(const Scene& scene, const Bvh& bvh,
                                                const WavefrontKernels* kernels, uint32_t spp,
                                                uint64_t seed) {
  const Camera camera(scene.camera);
  const PixelFilter filter(scene.filter);
  const RenderContext ctx{scene, bvh};
  const BidirectionalSetup setup(scene);
  const int width = camera.width(), height = camera.height();
  BidirectionalTracer tracer{.bvh = &bvh, .kernels = kernels};
  // Every sample's filter weight (the denominators all strategies share), and per strategy the
  // weighted sums of its camera contributions and its light film.
  FilmBlock weights(0, 0, width, height);
  struct Films {
    FilmBlock camera;
    LightFilm light;
  };
  std::map<std::pair<int, int>, Films> films;
  auto films_of = [&](int s, int t) -> Films& {
    auto it = films.find({s, t});
    if (it == films.end())
      it = films
               .emplace(std::pair{s, t},
                        Films{FilmBlock(0, 0, width, height), LightFilm(filter, width, height)})
               .first;
    return it->second;
  };

  std::vector<BidirectionalSampleInput> batch;
  std::vector<Vec2f> film_pos;
  std::vector<LightSplat> splats;
  std::vector<StrategyContribution> contributions;
  Color3f L[kBidirectionalBatch];
  auto flush = [&] {
    splats.clear(), contributions.clear();
    TraceBidirectionalBatch(ctx, setup, &tracer, batch, L, &splats, &contributions);
    for (size_t i = 0; i < batch.size(); ++i)
      if (IsFinite(L[i])) weights.Splat(filter, film_pos[i].x, film_pos[i].y, Color3f{});
    for (const StrategyContribution& c : contributions) {
      Films& f = films_of(c.s, c.t);
      if (c.t == 1) {
        f.light.Splat(c.sx, c.sy, c.value);
      } else if (IsFinite(L[c.sample])) {  // the render drops a non-finite sample whole
        f.camera.Splat(filter, film_pos[c.sample].x, film_pos[c.sample].y, c.value);
      }
    }
    batch.clear(), film_pos.clear();
  };
  const uint64_t w64 = uint64_t(width);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const uint64_t pixel = uint64_t(y) * w64 + uint64_t(x);
      for (uint32_t s = 0; s < spp; ++s) {
        PathSampler sampler(scene.sampler.type, PixelSeed(seed, pixel), s);
        const Vec2f jitter = sampler.Get2D(kDimensionPixel);
        const Vec2f lens = sampler.Get2D(kDimensionLens);
        const float sx = float(x) + jitter.x, sy = float(y) + jitter.y;
        batch.push_back({camera.GenerateRay(sx, sy, lens), sampler});
        film_pos.push_back({sx, sy});
        if (batch.size() == kBidirectionalBatch) flush();
      }
    }
  }
  if (!batch.empty()) flush();

  std::vector<StrategyImage> out;
  for (auto& [st, f] : films) {
    // The strategy's sums over every sample's weight, then its light film joins as Render's.
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) f.camera.PixelSums(x, y)[3] = weights.PixelSums(x, y)[3];
    FilmBlock composed;
    f.light.ComposeInto(f.camera, spp, &composed);
    out.push_back({st.first, st.second, composed.Resolve()});
  }
  std::sort(out.begin(), out.end(), [](const StrategyImage& a, const StrategyImage& b) {
    return a.s + a.t != b.s + b.t ? a.s + a.t < b.s + b.t : a.s < b.s;
  });
  return out;
}

}  // namespace ptlab
