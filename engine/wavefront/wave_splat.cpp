// Wavefront stage: a wave's samples splatted into the film block in the scalar loop's order.
#include "engine/wavefront/wave.h"

namespace ptlab {

// Splats the wave's samples in the scalar loop's order (row, pixel, sample) with the kernel
// table's splat slot; non-finite samples are dropped and counted.
void Wavefront::Splat(const PixelFilter& filter, int x0, int y0, int x1, int y1, size_t samples,
                      FilmBlock* block, const PixelSampling* pixels) {
  const auto t0 = StageClock();
  splat_.Clear(path_of_slot_.size());
  const size_t tile_w = size_t(x1 - x0);
  for (int y = y0; y < y1; ++y) {
    for (size_t px = 0; px < tile_w; ++px) {
      PixelMoments* moments =
          pixels && pixels->moments
              ? &pixels->moments[uint64_t(y) * pixels->width + uint64_t(x0) + px]
              : nullptr;
      for (size_t s = 0; s < samples; ++s) {
        const uint32_t i = path_of_slot_[(size_t(y - y0) * tile_w + px) * samples + s];
        if (i == kNoPath) continue;  // an inactive pixel (adaptive sampling)
        const Color3f L = L_[i];
        if (moments) AddPixelSample(L, moments);
        if (!IsFinite(L)) {
          if (stats_->nonfinite++ == 0) stats_->first_x = x0 + int(px), stats_->first_y = y;
          continue;
        }
        splat_.Push(gen_sx_[i], gen_sy_[i], L);
      }
    }
  }
  kernels_->splat(filter, splat_.View(), block);
  stats_->seconds.film += Seconds(t0, StageClock());
}

}  // namespace ptlab
