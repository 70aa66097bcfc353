// The wavefront's driver: a tile wave by wave, each wave bounce by bounce through the stages
// (wave_*.cpp); and the per-thread workspace.
#include "engine/wavefront/wave.h"

#include <algorithm>
#include <memory>
#include <utility>

#include "engine/core/check.h"

namespace ptlab {

// Every integrator of integrator.cpp as one set of vertex rules.
Wavefront::VertexRules Wavefront::RulesFor(const IntegratorDesc& desc) {
  using Type = IntegratorDesc::Type;
  VertexRules r;
  switch (desc.type) {
    case Type::kNormals:
      r.normals = true;
      break;
    case Type::kDirectEms:
    case Type::kDirectMats:
    case Type::kDirectMis:
      r.nee = desc.type != Type::kDirectMats;
      r.mis = desc.type == Type::kDirectMis;
      r.nee_on_delta = true;
      r.bsdf_sampling = desc.type != Type::kDirectEms;
      r.max_depth = 1;
      break;
    case Type::kWhitted:
      r.nee = true;
      r.nee_ends_path = true;
      r.roulette = VertexRules::Roulette::kWhitted;
      break;
    case Type::kPathMats:
    case Type::kPathEms:
    case Type::kPathMis:
      r.nee = desc.type != Type::kPathMats;
      r.mis = desc.type == Type::kPathMis;
      r.cut_black = true;
      r.max_depth = desc.max_depth;
      r.light_samples = std::max(1, desc.light_samples);
      r.roulette = VertexRules::Roulette::kNori;
      break;
    case Type::kBdpt:
    case Type::kPtracer:
      // Not a wavefront integrator yet: render.cpp runs them on the scalar path.
      PTLAB_CHECK(false && "bdpt and ptracer have no wavefront rules");
      break;
  }
  return r;
}

void Wavefront::RenderTile(const RenderContext& ctx, const WavefrontKernels& kernels,
                           TileSampleStats* stats, const Camera& camera, const PixelFilter& filter,
                           int x0, int y0, int x1, int y1, uint32_t s_begin, uint32_t s_end,
                           uint64_t seed, FilmBlock* block, const PixelSampling* pixels) {
  scene_ = &ctx.scene, kernels_ = &kernels, stats_ = stats;
  rules_ = RulesFor(ctx.scene.integrator);
  sobol_ = ctx.scene.sampler.type == SamplerType::kSobol;
  environment_.resize(ctx.scene.environment_maps.size());
  distant_disk_.resize(ctx.scene.distant_disks.size());
  for (int y = y0; y < y1; y += kWaveRows) {
    const int wy1 = std::min(y1, y + kWaveRows);
    Generate(camera, x0, y, x1, wy1, s_begin, s_end, seed, pixels);
    for (int depth = 0; rays_.size() > 0; ++depth) Bounce(depth);
    Splat(filter, x0, y, x1, wy1, s_end - s_begin, block, pixels);
  }
}

size_t Wavefront::Bytes() const {
  size_t bytes = VectorsBytes(sampler_, gen_px_, gen_py_, gen_s_, gen_sx_, gen_sy_, jitter_, lens_,
                              all_paths_, continuing_, roulette_, bsdf_lobe_, light_point_,
                              bsdf_direction_, draw_seed_, draw_index_, draw_x_, draw_y_);
  bytes += VectorsBytes(L_, throughput_, nee_throughput_, eta_, prev_pdf_, prev_p_, specular_,
                        path_of_slot_);
  bytes += rays_.Bytes() + next_rays_.Bytes() + shadows_.Bytes();
  bytes += VectorsBytes(hits_, hit_mask_, its_, wo_, goes_on_, area_hits_, request_traced_,
                        request_contribution_, occluded_, nee_paths_, nonfinite_nee_);
  bytes += bsdf_.Bytes() + spawn_.Bytes() + area_.Bytes() + splat_.Bytes() + shadow_rows_.Bytes();
  bytes += other_picks_.Bytes();
  bytes += VectorsBytes(environment_, distant_disk_);
  bytes += escaped_.Bytes();
  for (const InfiniteLightColumns& e : environment_) bytes += e.Bytes();
  for (const InfiniteLightColumns& e : distant_disk_) bytes += e.Bytes();
  return bytes;
}

void Wavefront::Bounce(int depth) {
  const auto t0 = StageClock();
  Traverse();
  const auto t1 = StageClock();
  Shade(depth);
  const auto t2 = StageClock();
  Sample(depth);
  const auto t3 = StageClock();
  TraceShadows();
  const auto t4 = StageClock();
  AddEmitterSamples();
  std::swap(rays_, next_rays_);
  const auto t5 = StageClock();
  stats_->seconds.traversal += Seconds(t0, t1) + Seconds(t3, t4);
  stats_->seconds.shading += Seconds(t1, t2) + Seconds(t4, t5);
  stats_->seconds.sampling += Seconds(t2, t3);
}

WavefrontWorkspace::WavefrontWorkspace() : wave_(std::make_unique<Wavefront>()) {}
WavefrontWorkspace::~WavefrontWorkspace() = default;
WavefrontWorkspace::WavefrontWorkspace(WavefrontWorkspace&&) noexcept = default;
WavefrontWorkspace& WavefrontWorkspace::operator=(WavefrontWorkspace&&) noexcept = default;

size_t WavefrontWorkspace::Bytes() const { return wave_ != nullptr ? wave_->Bytes() : 0; }

void RenderTilePacket8(const RenderContext& ctx, const WavefrontKernels& kernels,
                       const Camera& camera, const PixelFilter& filter, int x0, int y0, int x1,
                       int y1, uint32_t s_begin, uint32_t s_end, uint64_t seed, FilmBlock* block,
                       TileSampleStats* stats, const PixelSampling* pixels,
                       WavefrontWorkspace* workspace) {
  if (x1 <= x0 || y1 <= y0 || s_end <= s_begin) return;
  if (workspace == nullptr) {
    WavefrontWorkspace local;  // one tile alone: its containers go when it is done
    return RenderTilePacket8(ctx, kernels, camera, filter, x0, y0, x1, y1, s_begin, s_end, seed,
                             block, stats, pixels, &local);
  }
  workspace->wave().RenderTile(ctx, kernels, stats, camera, filter, x0, y0, x1, y1, s_begin, s_end,
                               seed, block, pixels);
}

}  // namespace ptlab
