// The camera-path slot's oracle: PathSampler and its first draws, row by row.
#include "engine/wavefront/camera_paths.h"

namespace ptlab {

void StartCameraPaths(SamplerType type, uint64_t seed, uint64_t width, size_t n,
                      const CameraPathInputs& in, const CameraPathOutputs& out) {
  for (size_t k = 0; k < n; ++k) {
    const uint64_t pixel = uint64_t(in.py[k]) * width + uint64_t(in.px[k]);
    PathSampler& sampler = out.sampler[k];
    sampler = PathSampler(type, PixelSeed(seed, pixel), in.sample[k]);
    if (type != SamplerType::kIndependent) continue;
    // Film, then lens position: the path's stream in the scalar order.
    const Vec2f jitter = sampler.Get2D(kDimensionPixel);
    out.sx[k] = float(in.px[k]) + jitter.x, out.sy[k] = float(in.py[k]) + jitter.y;
    out.lens[k] = sampler.Get2D(kDimensionLens);
  }
}

}  // namespace ptlab
