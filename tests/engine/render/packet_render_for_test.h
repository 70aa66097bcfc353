// Renders as `ptlab render` does by default: BVH, BVH8 and the 8-wide packet traversal.
#pragma once

#include "engine/bvh/bvh.h"
#include "engine/render/render.h"
#include "simd/bvh8.h"
#include "simd/wavefront_kernels.h"

namespace ptlab {

/// Render(scene) through the packet path (bit-identical to the scalar path, only faster).
inline RenderResult RenderWithPackets(const Scene& scene, RenderOptions options) {
  const Bvh bvh = BuildBvh(scene.triangles, scene.spheres);
  const simd::Bvh8 bvh8 = simd::BuildBvh8(bvh);
  const WavefrontKernels kernels = simd::SimdWavefrontKernels(bvh8);
  options.kernels = &kernels;
  return Render(scene, bvh, options);
}

}  // namespace ptlab
