// Bidirectional samples traced as a batch: the camera subpaths of every sample advance bounce by
// bounce together, then the light subpaths, then every connection's shadow ray at once, so the
// rays go through packet traversal (Intersect8 / Occluded8 of a kernel table) in groups of
// eight. Per sample the steps, their random numbers and their float operations are the
// one-ray-at-a-time oracle's (LiBidirectional is a batch of one traced by Intersect1), so the
// image is the oracle's bit for bit whenever the traversal returns the oracle's hits.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/bvh/bvh.h"
#include "engine/render/bdpt.h"

namespace ptlab {

struct WavefrontKernels;  // engine/wavefront/kernels.h

/// Where a batch's rays are traced: one at a time (Intersect1 / Occluded1 on ctx.bvh) or in
/// packets of eight through a kernel table's intersect8 / occluded8 (null: one at a time).
/// Counts the rays it traces and the packets it sends.
struct BidirectionalTracer {
  const Bvh* bvh = nullptr;
  const WavefrontKernels* kernels = nullptr;
  uint64_t rays = 0, packets = 0;

  /// hit[i] = 1 and hits[i] written for the rays that hit something, else hit[i] = 0.
  void Intersect(std::span<const Ray> rays, Hit* hits, uint8_t* hit);
  /// occluded[i] = whether rays[i] hits anything in (t_min, t_max).
  void Occluded(std::span<const Ray> rays, uint8_t* occluded);
};

/// One pixel sample's input: its camera ray and its sampler after the pixel and lens draws.
struct BidirectionalSampleInput {
  Ray ray;
  PathSampler sampler;
};

/// One strategy's MIS-weighted contribution to one sample (for per-strategy images): to its
/// camera radiance, or (t = 1) a splat at (sx, sy).
struct StrategyContribution {
  uint32_t sample = 0;
  int s = 0, t = 0;
  float sx = 0, sy = 0;  // t = 1 only
  Color3f value;
};

/// Traces the samples as one batch (bdpt or ptracer, scene.integrator): L[i] is sample i's
/// radiance (LiBidirectional's), its light-tracing splats are appended to *splats in sample
/// order. With `strategies`, every contribution (each term of L[i] and each splat) is also
/// appended there with its strategy. Memory: the batch's subpaths and connections, reused by
/// the calling thread.
void TraceBidirectionalBatch(const RenderContext& ctx, const BidirectionalSetup& setup,
                             BidirectionalTracer* tracer,
                             std::span<BidirectionalSampleInput> samples, Color3f* L,
                             std::vector<LightSplat>* splats,
                             std::vector<StrategyContribution>* strategies = nullptr);

/// Samples per batch of RenderTileBidirectional: 32 pixels × 8 samples, 32 packets a bounce.
inline constexpr size_t kBidirectionalBatch = 256;

}  // namespace ptlab
