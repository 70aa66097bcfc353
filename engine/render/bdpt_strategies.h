// Per-strategy images of bidirectional path tracing (Veach's thesis, fig. 10.3): what each
// strategy (s, t) adds to the image, its MIS weight included.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/bvh/bvh.h"
#include "engine/image/image.h"
#include "engine/scene/scene.h"

namespace ptlab {

struct WavefrontKernels;  // engine/wavefront/kernels.h

/// Strategy (s, t): s light vertices, t camera vertices (s + t - 2 bounces).
struct StrategyImage {
  int s = 0, t = 0;
  Image image;
};

/// Renders the bdpt (or ptracer) image of `scene` with the samples Render(scene, bvh, {spp,
/// seed}) takes (the same pixel samples and subpaths), split by strategy: image (s, t) is the
/// camera film's weighted mean of that strategy's contributions (Σ f L_st / Σ f, the weights
/// of every sample) plus its light-tracing splats / spp. The images sum to Render's image up to
/// float rounding. Sorted by s + t, then s; strategies that contributed nothing are left out.
/// One thread; batches through `kernels`' packet traversal (null: one ray at a time).
std::vector<StrategyImage> RenderStrategyImages(const Scene& scene, const Bvh& bvh,
                                                const WavefrontKernels* kernels, uint32_t spp,
                                                uint64_t seed);

}  // namespace ptlab
