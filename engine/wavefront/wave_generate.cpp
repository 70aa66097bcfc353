// Wavefront stage: the camera rays of a wave's pixels and samples (path state set, film and
// lens numbers drawn).
#include "engine/wavefront/wave.h"

namespace ptlab {

// Camera rays of pixels [x0, x1) x [y0, y1), samples [s_begin, s_end), in 4x2-pixel packets
// at one sample index each; path id = generation order, result slot = scalar splat order.
// Pixels that `pixels` marks inactive get no paths (their slots stay unused).
void Wavefront::Generate(const Camera& camera, int x0, int y0, int x1, int y1, uint32_t s_begin,
                         uint32_t s_end, uint64_t seed, const PixelSampling* pixels) {
  const auto t0 = StageClock();
  const uint64_t width = uint64_t(camera.width());
  const size_t samples = s_end - s_begin, tile_w = size_t(x1 - x0);
  const size_t n = size_t(y1 - y0) * tile_w * samples;
  // Room for every slot's path, padded to whole packets; rows [0, id) are written below, one
  // pass per path (state, numbers, film position), instead of zero-filling every column.
  const size_t room = (n + kPacketWidth - 1) / kPacketWidth * kPacketWidth;
  GrowColumns(room, &sampler_, &L_, &throughput_, &nee_throughput_, &eta_, &prev_pdf_, &prev_p_,
              &specular_, &gen_sx_, &gen_sy_, &lens_);
  path_of_slot_.assign(n, kNoPath);
  GrowColumns(room, &gen_px_, &gen_py_, &gen_s_);
  uint32_t id = 0;
  for (int y = y0; y < y1; y += 2) {
    for (int bx = x0; bx < x1; bx += 4) {
      for (uint32_t s = s_begin; s < s_end; ++s) {
        for (int j = 0; j < kLanes; ++j) {
          const int px = bx + (j & 3), py = y + (j >> 2);
          if (px >= x1 || py >= y1) continue;
          const uint64_t pixel = uint64_t(py) * width + uint64_t(px);
          if (pixels && pixels->active && !pixels->active[pixel]) continue;
          gen_px_[id] = px, gen_py_[id] = py, gen_s_[id] = s;
          const size_t pixel_slot = (size_t(py - y0) * tile_w + size_t(px - x0)) * samples;
          path_of_slot_[pixel_slot + (s - s_begin)] = id;
          L_[id] = Color3f{}, throughput_[id] = Color3f{1, 1, 1};
          eta_[id] = 1.0f, prev_pdf_[id] = 0.0f;
          specular_[id] = 1;  // the camera ray counts as specular: emission is always seen
          ++id;
        }
      }
    }
  }
  // Each path's stream and, with the independent sampler, its film and lens numbers.
  kernels_->camera_paths(scene_->sampler.type, seed, width, id,
                         {gen_px_.data(), gen_py_.data(), gen_s_.data()},
                         {sampler_.data(), gen_sx_.data(), gen_sy_.data(), lens_.data()});
  // With `sobol`, film and lens positions as one batch draw per dimension for all the paths.
  if (sobol_) {
    all_paths_.resize(id), jitter_.resize(id);
    for (uint32_t i = 0; i < id; ++i) all_paths_[i] = i;
    FillSobolRows(all_paths_, 0, 1);
    DrawSobol2D(kDimensionPixel, jitter_.data());
    DrawSobol2D(kDimensionLens, lens_.data());
    for (uint32_t i = 0; i < id; ++i) {
      gen_sx_[i] = float(gen_px_[i]) + jitter_[i].x;
      gen_sy_[i] = float(gen_py_[i]) + jitter_[i].y;
    }
  }
  // The camera rays eight at a time, path i in lane i % 8 of packet i / 8 (the order Push
  // would give); the padding lanes' rays are made and never read (Active masks them).
  const size_t packets = (size_t(id) + kPacketWidth - 1) / kPacketWidth;
  const size_t padded = packets * kPacketWidth;
  for (size_t i = id; i < padded; ++i) gen_sx_[i] = gen_sy_[i] = 0.5f, lens_[i] = {0.5f, 0.5f};
  rays_.Clear();
  rays_.packets.resize(packets);
  rays_.owner.resize(id);
  for (uint32_t i = 0; i < id; ++i) rays_.owner[i] = i;
  for (size_t k = 0; k < packets; ++k) {
    const size_t i = k * kPacketWidth;
    camera.GenerateRay8(&gen_sx_[i], &gen_sy_[i], &lens_[i], &rays_.packets[k]);
  }
  stats_->seconds.sampling += Seconds(t0, StageClock());
}

}  // namespace ptlab
