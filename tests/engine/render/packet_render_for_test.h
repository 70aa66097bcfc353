// Renders as `ptlab render` does by default: BVH, BVH8 and the 8-wide packet traversal.
#pragma once

#include "engine/bvh/bvh.h"
#include "engine/render/render.h"
#include "engine/render/wavefront.h"
#include "simd/bvh8.h"
#include "simd/wavefront_kernels.h"

namespace ptlab {

/// Render(scene) through the packet path (within the render contract of RenderTilePacket8 of
/// the scalar path, wavefront.h; not bit-identical since the SIMD shading stage).
inline RenderResult RenderWithPackets(const Scene& scene, RenderOptions options) {
  const Bvh bvh = BuildBvh(scene.triangles, scene.spheres);
  const simd::Bvh8 bvh8 = simd::BuildBvh8(bvh);
  const simd::TriangleRows rows = simd::BuildTriangleRows(scene);
  const WavefrontKernels kernels = simd::SimdWavefrontKernels(bvh8, rows);
  options.kernels = &kernels;
  return Render(scene, bvh, options);
}

/// Render(scene) through the wavefront with the oracle's kernel table: bit-identical to the
/// scalar path (tests the wavefront's staging alone).
inline RenderResult RenderWithOracleWavefront(const Scene& scene, RenderOptions options) {
  const Bvh bvh = BuildBvh(scene.triangles, scene.spheres);
  const WavefrontKernels kernels = OracleWavefrontKernels(bvh);
  options.kernels = &kernels;
  return Render(scene, bvh, options);
}

}  // namespace ptlab
