// The memory a render will take (see render_memory.h).
#include "engine/render/render_memory.h"

#include <algorithm>
#include <cmath>

#include "engine/core/memory_budget.h"
#include "engine/render/packet_render.h"

namespace ptlab {
namespace {

// Render::Render's tiles are 32x32 pixels; a worker's wavefront holds one tile's paths of one
// pass.
constexpr double kTilePixels = 32.0 * 32.0;
// Bytes per path in flight and per emitter-sample row of a path (plus per infinite light, whose
// columns every row fills), from --stats' "wavefronts" on an 8x8-sphere scene (one area light),
// one thread, 64x64 film, 1 spp: 0.1 MiB at -l 1, 5.9 MiB at -l 256, 94.1 MiB at -l 4096, i.e.
// about 100 bytes a path and 23.5 a row; 405 MiB at -l 16384 on 32x24 (34 a row, the columns'
// growth by doubling). Rounded up, so the estimate errs high.
constexpr double kWavefrontBytesPerPath = 128;
constexpr double kWavefrontBytesPerEmitterRow = 40;
constexpr double kWavefrontBytesPerInfiniteLightRow = 16;

}  // namespace

RenderMemoryEstimate EstimateRenderMemory(const Scene& scene, const RenderOptions& options) {
  RenderMemoryEstimate e;
  const double w = scene.camera.width, h = scene.camera.height, pixels = w * h;
  const double border = std::ceil(double(scene.filter.radius));
  // The film's and the blocks' RGB+weight floats (blocks overlap by the filter's border), the
  // resolved RGB image and the PNG's bytes.
  const double block_area = (32.0 + 2 * border) * (32.0 + 2 * border) / kTilePixels;
  e.film = pixels * (16.0 + 16.0 * block_area + 12.0 + 4.0);
  const bool adaptive = options.adaptive.batch > 0 && options.distribution == nullptr;
  if (adaptive) e.adaptive = pixels * (2.0 * sizeof(PixelMoments) + 1.0 + 4.0);
  const double per_pass = PassSamples(options);
  const double tiles = std::ceil(w / 32.0) * std::ceil(h / 32.0);
  const double workers = std::min(double(std::max(1, options.threads)), tiles);
  const double paths = std::min(kTilePixels, pixels) * per_pass;
  const double rows = double(std::max(1, scene.integrator.light_samples));
  const double infinite = double(scene.environment_maps.size() + scene.distant_disks.size());
  e.wavefront = workers * paths *
                (kWavefrontBytesPerPath +
                 (kWavefrontBytesPerEmitterRow + kWavefrontBytesPerInfiniteLightRow * infinite) *
                     rows);
  return e;
}

std::string RenderOverMemoryBudget(const Scene& scene, const RenderOptions& options,
                                   double scene_bytes) {
  const RenderMemoryEstimate e = EstimateRenderMemory(scene, options);
  return OverMemoryBudget(
      e.total() + scene_bytes,
      "the render (film " + FormatBytes(e.film) + ", adaptive sampling " +
          FormatBytes(e.adaptive) + ", wavefronts " + FormatBytes(e.wavefront) + " for -l " +
          std::to_string(scene.integrator.light_samples) + ", scene " + FormatBytes(scene_bytes) +
          ")");
}

}  // namespace ptlab
