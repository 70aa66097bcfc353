// Renders as `ptlab render` does, through RenderSetup: by default BVH, BVH8 and the 8-wide
// packet kernels; or the wavefront with the oracle's table (`--scalar`).
#pragma once

#include "engine/render/render.h"
#include "simd/render_setup.h"

namespace ptlab {

/// Render(scene) through the packet path (within the render contract of RenderTilePacket8 of
/// the scalar path, wavefront.h; not bit-identical since the SIMD shading stage).
inline RenderResult RenderWithPackets(const Scene& scene, RenderOptions options) {
  const RenderSetup setup(scene, KernelChoice::kSimd);
  return Render(scene, setup, options);
}

/// Render(scene) through the wavefront with the oracle's kernel table: bit-identical to the
/// scalar path (tests the wavefront's staging alone).
inline RenderResult RenderWithOracleWavefront(const Scene& scene, RenderOptions options) {
  const RenderSetup setup(scene, KernelChoice::kOracle);
  return Render(scene, setup, options);
}

}  // namespace ptlab
