// The memory a render will take, estimated before it starts from what scales with the options:
// the film (its size), adaptive sampling's per-pixel moments, and each worker's wavefront
// (a tile's paths of one pass, times the emitter samples per vertex, -l). -l 65536 on a 32x24
// film took 4.6 GB; now it is refused up front when over the memory budget.
#pragma once

#include <cstdint>
#include <string>

#include "engine/render/render.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// What the estimate counts, in bytes.
struct RenderMemoryEstimate {
  double film = 0;       ///< the film, its per-tile blocks and the output image
  double adaptive = 0;   ///< adaptive sampling's moments and flags
  double wavefront = 0;  ///< all workers' wavefronts
  double total() const { return film + adaptive + wavefront; }
};

/// The estimate for rendering `scene` with `options` (spp, threads, adaptive) through the
/// wavefront (either kernel table); within a factor of about 2 of what --stats reports.
RenderMemoryEstimate EstimateRenderMemory(const Scene& scene, const RenderOptions& options);

/// Empty when the estimate plus `scene_bytes` fits MemoryBudgetBytes(); else a message with
/// the estimate's parts and the budget (engine/core/memory_budget.h).
std::string RenderOverMemoryBudget(const Scene& scene, const RenderOptions& options,
                                   double scene_bytes);

}  // namespace ptlab
