// The packet render path as a wavefront: SoA ray queues of 8-wide packets, compacted between
// bounces, through traversal, shading, sampling and shadow stages for all integrators; and the
// oracle's kernel table.
#include "engine/render/wavefront.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "engine/bvh/intersect1.h"
#include "engine/core/memory.h"
#include "engine/render/integrator_common.h"
#include "engine/render/interaction.h"
#include "engine/render/spawn_batch.h"
#include "engine/sampling/sobol.h"

namespace ptlab {
namespace {

using integrator::DrawBsdfNumbers;
using integrator::EmitterSampleRequest;
using integrator::Escaped;
using integrator::InfiniteEmitterSampleRequest;
using integrator::kWhittedContinuation;
using integrator::kWhittedMaxDepth;
using integrator::MisWeight;
using integrator::NoriContinuation;
using integrator::PrepareEmitterSampleFrom;
using Type = IntegratorDesc::Type;
using Clock = std::chrono::steady_clock;

constexpr int kLanes = static_cast<int>(kPacketWidth);
/// Pixel rows of a tile traced together as one wave (even: camera packets are 4x2 pixels).
/// With 16 samples per pass and 32-pixel tiles a wave holds 2048 paths.
constexpr int kWaveRows = 4;
/// A result slot without a path (its pixel is inactive).
constexpr uint32_t kNoPath = ~uint32_t{0};

/// What each integrator does at a path vertex. Every integrator of integrator.cpp is one set of
/// rules over the same vertex stages; the rules reproduce its operations in its order.
struct VertexRules {
  enum class Roulette { kNone, kNori, kWhitted };
  bool normals = false;        // first hit's |n|, nothing else
  bool nee = false;            // emitter sampling (next-event estimation) at vertices
  bool mis = false;            // MIS between emitter and BSDF sampling
  bool nee_on_delta = false;   // direct_*: emitters are sampled even on delta materials
  bool nee_ends_path = false;  // whitted: a non-delta vertex ends the path after its sample
  bool bsdf_sampling = true;   // false (direct_ems): the path ends after the first vertex
  bool cut_black = false;      // path_*: a path whose throughput turns black ends
  int max_depth = -1;          // last vertex that is shaded (emission only); -1: unbounded
  int light_samples = 1;
  Roulette roulette = Roulette::kNone;
};

VertexRules RulesFor(const IntegratorDesc& desc) {
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
  }
  return r;
}

/// Rays in SoA packets of eight; entry q is lane q % 8 of packet q / 8 and belongs to owner[q]
/// (a path, or an emitter-sample request for shadow rays). Pushing in order keeps it compact.
struct RayQueue {
  std::vector<RayPacket8> packets;
  std::vector<uint32_t> owner;

  size_t size() const { return owner.size(); }
  size_t Bytes() const { return VectorsBytes(packets, owner); }
  void Clear() {
    packets.clear();
    owner.clear();
  }
  void Push(const Ray& r, uint32_t who) {
    const size_t q = owner.size();
    // A new packet starts as a copy of an empty one: emplace_back's zeroing compiles to a
    // `rep stos` of 256 bytes, whose start-up cost showed at every eighth push.
    static constexpr RayPacket8 kEmptyPacket{};
    if (q % kLanes == 0) packets.push_back(kEmptyPacket);
    SetLaneRay(&packets.back(), int(q % kLanes), r);
    owner.push_back(who);
  }
  /// Makes it a queue of n rays whose owners and packets ((n + 7) / 8) the caller writes, every
  /// lane of them: an entry-by-entry Push in bulk.
  void Resize(size_t n) {
    packets.resize((n + kLanes - 1) / kLanes);
    owner.resize(n);
  }
  Vec3f Direction(size_t q) const {
    const RayPacket8& p = packets[q / kLanes];
    const size_t j = q % kLanes;
    return {p.dir_x[j], p.dir_y[j], p.dir_z[j]};
  }
  /// Active lanes of packet k: all eight except in the last, partial packet.
  Mask8 Active(size_t k) const {
    const size_t n = std::min<size_t>(kLanes, size() - k * kLanes);
    return n == kLanes ? kAllLanes : (1u << n) - 1u;
  }
};

double Seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// Gives each column at least `capacity` rows (columns written in place only grow, so a wave
// sizes them once).
template <class... Columns>
void GrowColumns(size_t capacity, Columns*... columns) {
  ((columns->size() < capacity ? columns->resize(capacity) : void()), ...);
}

}  // namespace

/// One tile's paths, wave by wave. Path state is SoA, indexed by path id (generation order);
/// the per-bounce scratch (hits, interactions) is indexed by queue entry. Each worker thread has
/// one on the heap, cache-line aligned so that no two threads' wavefronts share a line (the
/// vectors' end pointers are written at every push).
class alignas(kColumnAlignment) Wavefront {
 public:
  void RenderTile(const RenderContext& ctx, const WavefrontKernels& kernels, TileSampleStats* stats,
                  const Camera& camera, const PixelFilter& filter, int x0, int y0, int x1, int y1,
                  uint32_t s_begin, uint32_t s_end, uint64_t seed, FilmBlock* block,
                  const PixelSampling* pixels) {
    scene_ = &ctx.scene, kernels_ = &kernels, stats_ = stats;
    rules_ = RulesFor(ctx.scene.integrator);
    sobol_ = ctx.scene.sampler.type == SamplerType::kSobol;
    vertex_batch_ = !sobol_ && rules_.light_samples == 1 && rules_.bsdf_sampling &&
                    !rules_.nee_ends_path && rules_.roulette != VertexRules::Roulette::kWhitted &&
                    VertexBatchFits(ctx.scene);
    environment_.resize(ctx.scene.environment_maps.size());
    distant_disk_.resize(ctx.scene.distant_disks.size());
    for (int y = y0; y < y1; y += kWaveRows) {
      const int wy1 = std::min(y1, y + kWaveRows);
      Generate(camera, x0, y, x1, wy1, s_begin, s_end, seed, pixels);
      for (int depth = 0; rays_.size() > 0; ++depth) Bounce(depth);
      Splat(filter, x0, y, x1, wy1, s_end - s_begin, block, pixels);
    }
  }

  /// Heap bytes of the path state, queues and columns: capacity × element size. They only grow
  /// (cleared, never shrunk), so this is the high-water mark of every tile rendered so far.
  size_t Bytes() const {
    size_t bytes = VectorsBytes(sampler_, gen_px_, gen_py_, gen_sx_, gen_sy_, jitter_, lens_, all_paths_, continuing_,
                                roulette_, bsdf_lobe_, light_point_, bsdf_direction_, draw_seed_,
                                draw_index_, draw_x_, draw_y_);
    bytes += VectorsBytes(L_, throughput_, nee_throughput_, eta_, prev_pdf_, prev_p_, specular_,
                          path_of_slot_);
    bytes += rays_.Bytes() + next_rays_.Bytes() + shadows_.Bytes();
    bytes += VectorsBytes(hits_, hit_mask_, its_, wo_, goes_on_, area_hits_, request_traced_,
                          request_contribution_, occluded_, nee_paths_, nonfinite_nee_);
    bytes += bsdf_.Bytes() + spawn_.Bytes() + area_.Bytes() + splat_.Bytes() + shadow_rows_.Bytes();
    bytes += VectorsBytes(environment_, distant_disk_);
    bytes += escaped_.Bytes();
    for (const InfiniteLightColumns& e : environment_) bytes += e.Bytes();
    for (const InfiniteLightColumns& e : distant_disk_) bytes += e.Bytes();
    return bytes;
  }

 private:
  // Camera rays of pixels [x0, x1) x [y0, y1), samples [s_begin, s_end), in 4x2-pixel packets
  // at one sample index each; path id = generation order, result slot = scalar splat order.
  // Pixels that `pixels` marks inactive get no paths (their slots stay unused).
  void Generate(const Camera& camera, int x0, int y0, int x1, int y1, uint32_t s_begin,
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
    if (sobol_) GrowColumns(room, &gen_px_, &gen_py_);
    uint32_t id = 0;
    for (int y = y0; y < y1; y += 2) {
      for (int bx = x0; bx < x1; bx += 4) {
        for (uint32_t s = s_begin; s < s_end; ++s) {
          for (int j = 0; j < kLanes; ++j) {
            const int px = bx + (j & 3), py = y + (j >> 2);
            if (px >= x1 || py >= y1) continue;
            const uint64_t pixel = uint64_t(py) * width + uint64_t(px);
            if (pixels && pixels->active && !pixels->active[pixel]) continue;
            PathSampler& sampler = sampler_[id];
            sampler = PathSampler(scene_->sampler.type, PixelSeed(seed, pixel), s);
            const size_t pixel_slot = (size_t(py - y0) * tile_w + size_t(px - x0)) * samples;
            path_of_slot_[pixel_slot + (s - s_begin)] = id;
            L_[id] = Color3f{}, throughput_[id] = Color3f{1, 1, 1};
            eta_[id] = 1.0f, prev_pdf_[id] = 0.0f;
            specular_[id] = 1;  // the camera ray counts as specular: emission is always seen
            if (sobol_) {
              gen_px_[id] = px, gen_py_[id] = py;
            } else {
              // Film, then lens position: the path's stream in the scalar order.
              const Vec2f jitter = sampler.Get2D(kDimensionPixel);
              gen_sx_[id] = float(px) + jitter.x, gen_sy_[id] = float(py) + jitter.y;
              lens_[id] = sampler.Get2D(kDimensionLens);
            }
            ++id;
          }
        }
      }
    }
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

  // Now, for the stage times; the epoch when the tile's stats do not time its stages.
  Clock::time_point StageClock() const {
    return stats_->time_stages ? Clock::now() : Clock::time_point{};
  }

  void Bounce(int depth) {
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

  // Closest hits of every queued ray, one kernel call per packet.
  void Traverse() {
    const size_t packets = rays_.packets.size();
    hits_.resize(packets), hit_mask_.resize(packets);
    for (size_t k = 0; k < packets; ++k) {
      const Mask8 active = rays_.Active(k);
      hit_mask_[k] =
          kernels_->intersect8(kernels_->accel, rays_.packets[k], active, &hits_[k]) & active;
    }
    // Every queued ray is in an active lane (the queue is compact): no popcount per packet,
    // which the baseline target makes a library call.
    stats_->rays += rays_.size();
    stats_->packets += packets;
  }

  // Emission at hits, environment light for escaped rays; lists the entries that go on to the
  // sampling stage (goes_on_; its_ / wo_ hold their shading points). The interaction slot
  // writes the shading points for the whole wave, frames and wo included, and lists the hits
  // (all, and those on area lights) with their material groups' counts, so that this stage
  // visits only the hits that emit and the escaped rays.
  void Shade(int depth) {
    const size_t packets = rays_.packets.size();
    // Eight rows per packet: the SIMD slot may write every row of a packet with a hit and the
    // lists' room past their counts. Only grown: a resize up would construct each new row, and
    // the queue shrinks and grows back every wave.
    GrowColumns(packets * kLanes, &its_, &wo_, &goes_on_, &area_hits_);
    const bool batch_escaped = EscapedRaysBatch();
    escaped_.Clear();
    HitLists lists{goes_on_.data(), area_hits_.data()};
    kernels_->interaction(kernels_->accel, *scene_, rays_.packets.data(), hits_.data(),
                          hit_mask_.data(), packets, {its_.data(), wo_.data()}, &lists);
    if (rules_.normals) {
      // The first hit's |n|, nothing else: no path goes on.
      for (uint32_t h = 0; h < lists.hits; ++h) {
        const uint32_t q = goes_on_[h];
        const Vec3f a = Abs(its_[q].frame.n);
        L_[rays_.owner[q]] = {a.x, a.y, a.z};
      }
      n_goes_on_ = 0;
      std::fill(std::begin(goes_on_tags_), std::end(goes_on_tags_), 0u);
      return;
    }
    // Without infinite lights an escaped ray brings no light: Escaped's zero times a finite
    // throughput adds ±0, which leaves L as it is (it starts at +0 and never becomes -0), so only
    // the paths whose throughput is not finite (0 times Inf or NaN is NaN) take the loop below.
    const bool infinite = scene_->environment_maps.size() + scene_->distant_disks.size() != 0;
    for (size_t k = 0; k < packets; ++k) {
      for (Mask8 todo = rays_.Active(k) & ~hit_mask_[k]; todo != 0; todo &= todo - 1) {
        // Escaped: environment light, counted unless emitter sampling already did (after a
        // non-specular bounce), MIS-weighted when mis is on.
        const size_t q = k * kLanes + size_t(std::countr_zero(todo));
        const uint32_t i = rays_.owner[q];
        if (!infinite && IsFinite(throughput_[i])) continue;
        const Vec3f d = rays_.Direction(q);
        const Vec3f w = d / Length(d);
        const bool plain = !rules_.nee || specular_[i];
        if (!plain && !rules_.mis) continue;
        if (batch_escaped) {
          escaped_.Push(uint32_t(q), w, !plain);
        } else {
          L_[i] += throughput_[i] * Escaped(*scene_, w, !plain, plain ? 0.0f : prev_pdf_[i]);
        }
      }
    }
    // Only area lights emit at a surface (Emitted's test; EmitterRef::None's tag is not kArea).
    if (lists.area_hits != 0) {
      kernels_->emission(
          *scene_, {.nee = rules_.nee, .mis = rules_.mis}, lists.area_hits,
          {area_hits_.data(), rays_.packets.data(), rays_.owner.data(), its_.data()},
          {throughput_.data(), specular_.data(), prev_pdf_.data(), prev_p_.data(), L_.data()});
    }
    // Past the last vertex that is shaded no hit goes on; otherwise every hit does.
    const bool goes_on = rules_.max_depth < 0 || depth < rules_.max_depth;
    n_goes_on_ = goes_on ? lists.hits : 0;
    for (int g = 0; g < kMaterialGroups; ++g) goes_on_tags_[g] = goes_on ? lists.group_hits[g] : 0;
    if (batch_escaped) ShadeEscaped();
  }

  // Whether the escaped rays take the environment_eval batch: when every infinite emitter is
  // an environment map, listed among the emitters in table order (so that summing the maps
  // per row in that order is integrator::Escaped's sum, with and without MIS). Distant disks
  // keep the per-row integrator::Escaped.
  bool EscapedRaysBatch() const {
    if (scene_->environment_maps.size() == 0 || scene_->distant_disks.size() != 0) return false;
    uint32_t next = 0;
    for (const EmitterRef e : scene_->emitters)
      if (IsInfiniteLight(e) && (e.tag() != EmitterTag::kEnvironment || e.index() != next++))
        return false;
    return next == scene_->environment_maps.size();
  }

  // The escaped rays' environment light as one batch per map: radiance (and, for MIS, the
  // emitter-sampling pdf) through the kernel table's environment_eval slot, summed per row over
  // the maps in integrator::Escaped's order and operations.
  void ShadeEscaped() {
    EscapedColumns& e = escaped_;
    const size_t m = e.q.size();
    if (m == 0) return;
    const bool any_mis = std::find(e.mis.begin(), e.mis.end(), uint8_t(1)) != e.mis.end();
    e.light.assign(m, Color3f{});
    e.r.resize(m), e.g.resize(m), e.b.resize(m), e.pdf.resize(m);
    for (const EmitterRef emitter : scene_->emitters) {
      if (!IsInfiniteLight(emitter)) continue;
      kernels_->environment_eval(
          scene_->environment_maps, emitter.index(), m, {e.w_x.data(), e.w_y.data(), e.w_z.data()},
          {e.r.data(), e.g.data(), e.b.data(), any_mis ? e.pdf.data() : nullptr});
      const float pmf = EmitterSelectionPmf(*scene_, emitter);
      for (size_t row = 0; row < m; ++row) {
        const Color3f Le{e.r[row], e.g[row], e.b[row]};
        if (!e.mis[row]) {
          e.light[row] += Le;
        } else if (!IsBlack(Le)) {
          const uint32_t i = rays_.owner[e.q[row]];
          e.light[row] +=
              Le * MisWeight(prev_pdf_[i], e.pdf[row] * pmf, scene_->integrator.power_heuristic);
        }
      }
    }
    for (size_t row = 0; row < m; ++row) {
      const uint32_t i = rays_.owner[e.q[row]];
      L_[i] += throughput_[i] * e.light[row];
    }
  }

  // Emitter samples (shadow rays queued), Russian roulette and BSDF sampling, in the scalar
  // integrators' order of random numbers; continuing paths form the next, compact ray queue.
  // The BSDF numbers are drawn here, per path in that order, into the BSDF stage's columns
  // (group by group: through the vertices slot where it serves, else row by row);
  // SampleBsdfs then runs the kernel table's bsdf slot over them and continues the paths.
  void Sample(int depth) {
    const int n_light = rules_.light_samples;
    next_rays_.Clear(), shadows_.Clear();
    nee_paths_.clear(), nonfinite_nee_.clear();
    bsdf_.Clear(rays_.size(), goes_on_tags_);
    const size_t emitter_rows = rules_.nee ? rays_.size() * size_t(n_light) : 0;
    // Requests are SoA columns written in place (a row's flag, its ray and contribution only
    // when it traces): no request struct per row. The columns only grow.
    n_requests_ = 0;
    GrowColumns(emitter_rows, &request_traced_, &request_contribution_);
    uint32_t area_rows[kMaterialGroups] = {};
    if (rules_.nee)
      for (int t = 0; t < kMaterialGroups; ++t) area_rows[t] = goes_on_tags_[t] * uint32_t(n_light);
    area_.Clear(emitter_rows, area_rows);
    for (InfiniteLightColumns& e : environment_) e.Clear(emitter_rows);
    for (InfiniteLightColumns& e : distant_disk_) e.Clear(emitter_rows);
    GroupEntries();
    if (sobol_) DrawVertexNumbers(depth);
    // Group by group (the BSDF and emitter columns' groups): a group's rows share their tag, so
    // whether the vertex takes emitter samples is known per group, and its rows go to the
    // columns' slots one after the other.
    size_t k = 0;
    for (int g = 0; g < kMaterialGroups; ++g) {
      const size_t end = k + goes_on_tags_[g];
      if (k == end) continue;
      const bool delta = g < kMaterialTagCount && IsDeltaMaterial(static_cast<MaterialTag>(g));
      SampleGroup(depth, delta, g, k, end);
      k = end;
    }
    SampleAreaLights();
    SampleInfiniteLights();
    SampleBsdfs();
  }

  // goes_on_[0, n_goes_on_) in stable order by material group (a counting sort, whose counts
  // are goes_on_tags_); as it is when one group holds every entry.
  void GroupEntries() {
    uint32_t at[kMaterialGroups];
    uint32_t sum = 0, groups = 0;
    for (int g = 0; g < kMaterialGroups; ++g) {
      at[g] = sum, sum += goes_on_tags_[g];
      groups += goes_on_tags_[g] != 0 ? 1u : 0u;
    }
    if (groups < 2) return;
    GrowColumns(goes_on_.size(), &grouped_);
    for (size_t k = 0; k < n_goes_on_; ++k) {
      const uint32_t q = goes_on_[k];
      grouped_[at[MaterialGroup(its_[q].material)]++] = q;
    }
    std::swap(goes_on_, grouped_);
  }

  // SampleGroup through the kernel table's vertices slot (vertex_batch_: the independent
  // sampler, one emitter sample per vertex, only area lights, no Whitted rules).
  void SampleGroupBatch(int depth, bool delta, int g, size_t k, size_t end) {
    VertexBatchRules rules;
    rules.depth = depth;
    rules.emitter_sample = rules_.nee && (!delta || rules_.nee_on_delta);
    rules.roulette = rules_.roulette == VertexRules::Roulette::kNori && depth >= 3;
    rules.first_request = uint32_t(n_requests_);
    const size_t n = end - k;
    if (rules.emitter_sample) {
      n_requests_ += n;
      nee_paths_.resize(n_requests_);
    }
    EmitterColumns& a = area_;
    BsdfColumns& b = bsdf_;
    const uint32_t area_at = a.next[g], bsdf_at = b.next[g];
    VertexBatchOutputs out;
    out.area = {a.request.data() + area_at,  a.entry.data() + area_at, a.light.data() + area_at,
                a.pick_pmf.data() + area_at, a.ref_x.data() + area_at, a.ref_y.data() + area_at,
                a.ref_z.data() + area_at,    a.wo_x.data() + area_at,  a.wo_y.data() + area_at,
                a.wo_z.data() + area_at,     a.u_x.data() + area_at,   a.u_y.data() + area_at};
    out.bsdf = {b.path.data() + bsdf_at,
                b.entry.data() + bsdf_at,
                b.material_index.data() + bsdf_at,
                b.roulette_scale.data() + bsdf_at,
                b.wo_x.data() + bsdf_at,
                b.wo_y.data() + bsdf_at,
                b.wo_z.data() + bsdf_at,
                b.u_lobe.data() + bsdf_at,
                b.u_x.data() + bsdf_at,
                b.u_y.data() + bsdf_at};
    out.request_traced = request_traced_.data();
    out.nee_paths = nee_paths_.data();
    const size_t nonfinite_at = nonfinite_nee_.size();
    nonfinite_nee_.resize(nonfinite_at + n);
    out.nonfinite = nonfinite_nee_.data() + nonfinite_at;
    const VertexBatchInputs in{goes_on_.data() + k, rays_.owner.data(), its_.data(), wo_.data(),
                               eta_.data()};
    const VertexBatchPaths paths{sampler_.data(), throughput_.data(), nee_throughput_.data()};
    kernels_->vertices(*scene_, rules, n, in, paths, &out);
    nonfinite_nee_.resize(nonfinite_at + out.nonfinite_rows);
    a.rows += out.area_rows, a.next[g] += uint32_t(out.area_rows);
    b.rows += out.bsdf_rows, b.next[g] += uint32_t(out.bsdf_rows);
  }

  // Sample's rows [k, end) of goes_on_, all of material group g (delta: its tag's lobes are all
  // Dirac deltas).
  void SampleGroup(int depth, bool delta, int g, size_t k, size_t end) {
    if (vertex_batch_) {
      SampleGroupBatch(depth, delta, g, k, end);
      return;
    }
    const int n_light = rules_.light_samples;
    const bool emitters = !scene_->emitters.empty();
    const size_t m = continuing_.size();  // with sobol: entry c of the drawn numbers
    uint32_t area_at = area_.next[g], bsdf_at = bsdf_.next[g];
    for (; k < end; ++k) {
      const uint32_t q = goes_on_[k];
      const uint32_t i = rays_.owner[q];
      const SurfaceInteraction& its = its_[q];
      const Vec3f& wo = wo_[q];
      PathSampler& sampler = sampler_[i];
      if (rules_.nee && (!delta || rules_.nee_on_delta)) {
        for (int s = 0; s < n_light; ++s) {
          const uint32_t request = uint32_t(n_requests_++);
          request_traced_[request] = 0;
          if (!emitters) continue;
          // PrepareEmitterSample's numbers and pick (DrawEmitterNumbers, PickEmitter), as
          // plain floats; area-light, environment-map and distant-disk picks go to the emitter
          // stage's batches, the delta lights are prepared here.
          float pick_pmf = 0.0f;
          EmitterRef emitter;
          Vec2f u;
          if (sobol_) {
            u = light_point_[size_t(s) * m + k];
            emitter = SelectEmitter(*scene_, u.x, &pick_pmf, &u.x);
          } else {
            const float pick = sampler.Get1D(DecisionDimension(depth, Decision::kLightPick),
                                             uint32_t(s), uint32_t(n_light));
            u = sampler.Get2D(DecisionDimension(depth, Decision::kLightPoint), uint32_t(s),
                              uint32_t(n_light));
            emitter = SelectEmitter(*scene_, pick, &pick_pmf);
          }
          if (!(pick_pmf > 0)) continue;
          switch (emitter.tag()) {
            case EmitterTag::kArea:
              area_.Put(area_at++, request, uint32_t(q), emitter.index(), pick_pmf, its.p, wo, u);
              break;
            case EmitterTag::kEnvironment:
              environment_[emitter.index()].Push(request, uint32_t(q), pick_pmf, u);
              break;
            case EmitterTag::kDistantDisk:
              distant_disk_[emitter.index()].Push(request, uint32_t(q), pick_pmf, u);
              break;
            // Delta lights: one position or direction each, nothing to batch.
            case EmitterTag::kPoint:
            case EmitterTag::kDirectional:
            case EmitterTag::kSpot:
              StoreRequest(request, PrepareEmitterSampleFrom(*scene_, its, wo, rules_.mis,
                                                             emitter, pick_pmf, u));
              break;
          }
        }
        // With one sample per vertex, the request of nee path p is row p.
        if (n_light == 1 && !IsFinite(throughput_[i])) nonfinite_nee_.push_back(n_requests_ - 1);
        nee_paths_.push_back(i);
        nee_throughput_[i] = throughput_[i];
        if (rules_.nee_ends_path && !delta) continue;
      }
      if (!rules_.bsdf_sampling) continue;
      const auto roulette = [&] {
        return sobol_ ? roulette_[k]
                      : sampler.Get1D(DecisionDimension(depth, Decision::kRoulette));
      };
      float roulette_scale = 1.0f;
      if (rules_.roulette == VertexRules::Roulette::kNori && depth >= 3) {
        const float q_continue = NoriContinuation(throughput_[i], eta_[i]);
        if (!(roulette() < q_continue)) continue;
        throughput_[i] *= 1.0f / q_continue;
      } else if (rules_.roulette == VertexRules::Roulette::kWhitted) {
        if (depth >= kWhittedMaxDepth || roulette() >= kWhittedContinuation) continue;
        roulette_scale = 1.0f / kWhittedContinuation;
      }
      // The lobe number, then the direction (SampleBsdf's order).
      float u_lobe;
      Vec2f u_dir;
      if (sobol_) {
        u_lobe = bsdf_lobe_[k], u_dir = bsdf_direction_[k];
      } else {
        DrawBsdfNumbers(sampler, depth, &u_lobe, &u_dir);
      }
      bsdf_.Put(bsdf_at++, i, uint32_t(q), its.material, wo, u_lobe, u_dir, roulette_scale);
    }
    area_.rows += area_at - area_.next[g], area_.next[g] = area_at;
    bsdf_.rows += bsdf_at - bsdf_.next[g], bsdf_.next[g] = bsdf_at;
  }

  // Row r of the request columns from a finished request; the row's flag is already 0 and
  // stays so when the request traces nothing. Field by field, so the request stays in
  // registers instead of being assembled on the stack and copied. The shadow ray goes straight
  // into the shadow queue (owner r), in the order the requests finish (delta lights, then
  // area lights by material tag, environment, disk batches): TraceShadows answers by owner, so
  // the order changes no result, and with one kind of emitter and material it is request order.
  void StoreRequest(uint32_t r, const EmitterSampleRequest& req) {
    if (!req.traced) return;
    request_traced_[r] = 1;
    shadows_.Push(req.shadow, r);
    Color3f& contribution = request_contribution_[r];
    contribution.r = req.contribution.r, contribution.g = req.contribution.g;
    contribution.b = req.contribution.b;
  }

  // The emitter stage: per material tag, the kernel table's area_light slot over the tag's
  // area-light picks, then its area_request slot (shadow ray, contribution: PrepareEmitterSample's
  // finish); then, tag by tag in request order, each traced request's row and shadow ray
  // (StoreRequest's; reading the columns in their order, not through a slot per row).
  void SampleAreaLights() {
    EmitterColumns& a = area_;
    const size_t n = a.size();
    if (n == 0) return;
    for (int t = 0; t < kMaterialTagCount; ++t) {
      const size_t b = a.begin[t], count = a.next[t] - b;
      if (count == 0) continue;
      const AreaLightBatchInputs in{a.light.data() + b, a.ref_x.data() + b, a.ref_y.data() + b,
                                    a.ref_z.data() + b, a.u_x.data() + b,   a.u_y.data() + b};
      const AreaLightBatchOutputs out{a.p_x.data() + b,  a.p_y.data() + b,  a.p_z.data() + b,
                                      a.n_x.data() + b,  a.n_y.data() + b,  a.n_z.data() + b,
                                      a.ng_x.data() + b, a.ng_y.data() + b, a.ng_z.data() + b,
                                      a.pdf.data() + b};
      kernels_->area_light(kernels_->accel, *scene_, scene_->integrator.triangle_sampling, count,
                           in, out);
      const AreaRequestInputs request_in{
          its_.data(),        a.entry.data() + b,    a.ref_x.data() + b, a.ref_y.data() + b,
          a.ref_z.data() + b, a.wo_x.data() + b,     a.wo_y.data() + b,  a.wo_z.data() + b,
          a.light.data() + b, a.pick_pmf.data() + b, a.p_x.data() + b,   a.p_y.data() + b,
          a.p_z.data() + b,   a.n_x.data() + b,      a.n_y.data() + b,   a.n_z.data() + b,
          a.ng_x.data() + b,  a.ng_y.data() + b,     a.ng_z.data() + b,  a.pdf.data() + b};
      const AreaRequestOutputs request_out{a.traced.data() + b, a.o_x.data() + b, a.o_y.data() + b,
                                           a.o_z.data() + b,    a.d_x.data() + b, a.d_y.data() + b,
                                           a.d_z.data() + b,    a.r.data() + b,   a.g.data() + b,
                                           a.b.data() + b};
      kernels_->area_request(*scene_, static_cast<MaterialTag>(t), rules_.mis, count, request_in,
                             request_out);
    }
    // Group by group (rows of no material trace nothing: BsdfEval is 0), each in request order:
    // the traced rows compacted through the shadow_rows slot, then queued a packet at a time.
    ShadowRowColumns& st = shadow_rows_;
    st.Clear(n);
    size_t m = 0;
    for (int t = 0; t < kMaterialTagCount; ++t) {
      const size_t b = a.begin[t], count = a.next[t] - b;
      if (count == 0) continue;
      const ShadowRowInputs in{a.traced.data() + b, a.request.data() + b, a.o_x.data() + b,
                               a.o_y.data() + b,    a.o_z.data() + b,     a.d_x.data() + b,
                               a.d_y.data() + b,    a.d_z.data() + b,     a.r.data() + b,
                               a.g.data() + b,      a.b.data() + b};
      m += kernels_->shadow_rows(count, in, st.Outputs().From(m));
    }
    QueueShadowRows(m);
  }

  // Rows [0, m) of shadow_rows_ into the shadow queue (owner: the request), a packet's run of
  // lanes at a time, and each request's flag and contribution (StoreRequest's).
  void QueueShadowRows(size_t m) {
    const ShadowRowColumns& st = shadow_rows_;
    size_t e = shadows_.size();
    shadows_.Resize(e + m);
    const auto copy = [&](RayPacket8& p, size_t j, size_t k, size_t run) {
      std::copy_n(&st.o_x[k], run, &p.org_x[j]), std::copy_n(&st.o_y[k], run, &p.org_y[j]);
      std::copy_n(&st.o_z[k], run, &p.org_z[j]), std::copy_n(&st.d_x[k], run, &p.dir_x[j]);
      std::copy_n(&st.d_y[k], run, &p.dir_y[j]), std::copy_n(&st.d_z[k], run, &p.dir_z[j]);
      std::fill_n(&p.t_min[j], run, 0.0f), std::fill_n(&p.t_max[j], run, 1.0f);
    };
    size_t k = 0;
    // Whole packets (a constant run: eight-float moves), after the partial one the queue ends
    // in and before the last.
    if (e % kLanes != 0) {
      const size_t run = std::min(kLanes - e % kLanes, m);
      copy(shadows_.packets[e / kLanes], e % kLanes, 0, run);
      k += run, e += run;
    }
    for (; k + kLanes <= m; k += kLanes, e += kLanes)
      copy(shadows_.packets[e / kLanes], 0, k, kLanes);
    if (k < m) copy(shadows_.packets[e / kLanes], 0, k, m - k);
    std::copy_n(st.request.data(), m, shadows_.owner.data() + shadows_.size() - m);
    for (k = 0; k < m; ++k) {
      const uint32_t r = st.request[k];
      request_traced_[r] = 1;
      request_contribution_[r] = {st.r[k], st.g[k], st.b[k]};
    }
  }

  // The emitter stage's infinite lights: the kernel table's environment slot over each map's
  // picks and its distant_disk slot over each disk's, then each returned sample's request as
  // PrepareEmitterSample finishes it.
  void SampleInfiniteLights() {
    // A row without a sample (pdf 0: a black light) keeps its empty request.
    const auto finish = [this](const InfiniteLightColumns& e) {
      for (size_t c = 0; c < e.size(); ++c) {
        if (!(e.pdf[c] > 0)) continue;
        const EnvironmentSample es{
            {e.wi_x[c], e.wi_y[c], e.wi_z[c]}, {e.r[c], e.g[c], e.b[c]}, e.pdf[c]};
        const size_t q = e.entry[c];
        StoreRequest(e.request[c], InfiniteEmitterSampleRequest(*scene_, its_[q], wo_[q],
                                                                rules_.mis, es, e.pick_pmf[c]));
      }
    };
    for (uint32_t map = 0; map < environment_.size(); ++map) {
      InfiniteLightColumns& e = environment_[map];
      if (e.size() == 0) continue;
      kernels_->environment(scene_->environment_maps, map, e.size(), e.Inputs(), e.Outputs());
      finish(e);
    }
    for (uint32_t disk = 0; disk < distant_disk_.size(); ++disk) {
      InfiniteLightColumns& e = distant_disk_[disk];
      if (e.size() == 0) continue;
      kernels_->distant_disk(scene_->distant_disks, disk, e.size(), e.Inputs(), e.Outputs());
      finish(e);
    }
  }

  // The BSDF stage: the kernel table's bsdf slot over the columns, one call per material tag
  // on its group of slots (Sample pushed the rows there; the rows of ShadeHitsWith's batches,
  // without its counting sort, gather and scatter); then each sampled path's throughput and
  // state, as the scalar integrators do (the continuation slot, one call per tag), and the
  // next rays of those that go on as one batch of the spawn slot.
  void SampleBsdfs() {
    BsdfColumns& b = bsdf_;
    const size_t n = b.size();
    if (n == 0) return;
    for (int t = 0; t < kMaterialTagCount; ++t) {
      const size_t begin = b.begin[t], count = b.next[t] - begin;
      if (count == 0) continue;
      ShadeInputs in;
      in.wo = {b.wo_x.data() + begin, b.wo_y.data() + begin, b.wo_z.data() + begin};
      in.u_lobe = b.u_lobe.data() + begin, in.u_x = b.u_x.data() + begin;
      in.u_y = b.u_y.data() + begin;
      ShadeOutputs out;
      out.wi = {b.wi_x.data() + begin, b.wi_y.data() + begin, b.wi_z.data() + begin};
      out.weight = {b.weight_r.data() + begin, b.weight_g.data() + begin,
                    b.weight_b.data() + begin};
      out.pdf = b.pdf.data() + begin, out.eta = b.eta.data() + begin;
      kernels_->bsdf(scene_->materials, static_cast<MaterialTag>(t),
                     b.material_index.data() + begin, count, in, out);
    }
    // Group by group, each in queue order, each sampled path's throughput and state, as the
    // scalar integrators do, through the kernel table's continuation slot, one call per tag; a
    // path that goes on gets the next row of the spawn stage and the next entry of the queue.
    // So the next queue holds the paths of each material tag together (the order changes no
    // result: each path's numbers and state are its own), and the slot reads the columns in
    // their order instead of in queue order through an index. Rows of no material (no group of
    // ShadeHitsWith) sample nothing.
    SpawnColumns& sp = spawn_;
    sp.Clear(n);
    next_rays_.owner.resize(n);
    ContinueBatchOutputs out{sp.entry.data(), sp.wi_x.data(), sp.wi_y.data(), sp.wi_z.data(),
                             next_rays_.owner.data()};
    const ContinueBatchPaths paths{throughput_.data(), eta_.data(), specular_.data(),
                                   prev_pdf_.data(), prev_p_.data()};
    const bool whitted = rules_.roulette == VertexRules::Roulette::kWhitted;
    for (int t = 0; t < kMaterialTagCount; ++t) {
      const size_t begin = b.begin[t], count = b.next[t] - begin;
      if (count == 0) continue;
      const ContinueBatchRules rules{IsDeltaMaterial(static_cast<MaterialTag>(t)),
                                     rules_.cut_black};
      const ContinueBatchInputs in{
          b.path.data() + begin,     b.entry.data() + begin,
          b.weight_r.data() + begin, b.weight_g.data() + begin,
          b.weight_b.data() + begin, whitted ? b.roulette_scale.data() + begin : nullptr,
          b.pdf.data() + begin,      b.eta.data() + begin,
          b.wi_x.data() + begin,     b.wi_y.data() + begin,
          b.wi_z.data() + begin,     its_.data()};
      kernels_->continuation(rules, count, in, paths, &out);
    }
    const size_t m = out.rows;
    // Their rays (integrator::SpawnOrigin, the sample's world direction) through the kernel
    // table's spawn slot, straight into the queue's packets.
    next_rays_.Resize(m);
    kernels_->spawn(its_.data(), m, sp.Inputs(), next_rays_.packets.data());
  }

  // Sobol' numbers of every decision of vertex `depth` for the paths that go on (continuing_,
  // in queue order), one batch draw per dimension (and emitter sub-sample).
  void DrawVertexNumbers(int depth) {
    continuing_.clear();
    for (size_t k = 0; k < n_goes_on_; ++k) continuing_.push_back(rays_.owner[goes_on_[k]]);
    const size_t m = continuing_.size();
    const uint32_t n_light = uint32_t(rules_.light_samples);
    if (rules_.nee && !scene_->emitters.empty()) {
      // No pick numbers: the pick is folded into the point's x (EmitterNumbers).
      light_point_.resize(m * n_light);
      for (uint32_t s = 0; s < n_light; ++s) {
        FillSobolRows(continuing_, s, n_light);
        DrawSobol2D(DecisionDimension(depth, Decision::kLightPoint), light_point_.data() + s * m);
      }
    }
    if (!rules_.bsdf_sampling) return;
    // With one emitter sample per vertex, its rows (sub 0 of 1) are the BSDF decisions' rows.
    const bool emitter_rows_fit = rules_.nee && !scene_->emitters.empty() && n_light == 1;
    if (!emitter_rows_fit) FillSobolRows(continuing_, 0, 1);
    roulette_.resize(m), bsdf_lobe_.resize(m), bsdf_direction_.resize(m);
    // Roulette numbers only where Sample reads them (Nori's from depth 3, Whitted's always).
    const bool roulette = rules_.roulette == VertexRules::Roulette::kWhitted ||
                          (rules_.roulette == VertexRules::Roulette::kNori && depth >= 3);
    if (roulette)
      DrawSobol1D(DecisionDimension(depth, Decision::kRoulette), roulette_.data());
    DrawSobol1D(DecisionDimension(depth, Decision::kBsdfLobe), bsdf_lobe_.data());
    DrawSobol2D(DecisionDimension(depth, Decision::kBsdfDirection), bsdf_direction_.data());
  }

  // The rows of the next draws: the given paths' pixel seeds and sample indices (sub-sample
  // sub of sub_count); each DrawSobol then draws one dimension for all of them with the kernel
  // table's batch kernel.
  void FillSobolRows(const std::vector<uint32_t>& paths, uint32_t sub, uint32_t sub_count) {
    const size_t m = paths.size();
    draw_seed_.resize(m), draw_index_.resize(m), draw_x_.resize(m), draw_y_.resize(m);
    for (size_t k = 0; k < m; ++k) {
      const PathSampler& p = sampler_[paths[k]];
      draw_seed_[k] = p.pixel_seed32();
      draw_index_[k] = p.index() * sub_count + sub;
    }
  }
  void DrawSobol1D(uint32_t dim, float* out) {
    kernels_->sobol1d(draw_seed_.data(), draw_index_.data(), dim, draw_seed_.size(), out);
  }
  void DrawSobol2D(uint32_t dim, Vec2f* out) {
    const size_t m = draw_seed_.size();
    kernels_->sobol2d(draw_seed_.data(), draw_index_.data(), dim, m, draw_x_.data(),
                     draw_y_.data());
    for (size_t k = 0; k < m; ++k) out[k] = {draw_x_[k], draw_y_[k]};
  }

  // The shadow rays, one kernel call per packet. With one emitter sample per vertex, each
  // unoccluded sample's light is added to its path here (AddEmitterSamples' sum for that path,
  // its operations in its order), while the packet's owners are at hand: no per-request flag
  // and no second pass over the paths.
  void TraceShadows() {
    const bool add_here = rules_.light_samples == 1;
    if (!add_here) occluded_.assign(n_requests_, 0);
    for (size_t k = 0; k < shadows_.packets.size(); ++k) {
      const Mask8 active = shadows_.Active(k);
      const Mask8 occ = kernels_->occluded8(kernels_->accel, shadows_.packets[k], active) & active;
      const uint32_t* owner = shadows_.owner.data() + k * kLanes;
      if (!add_here) {
        for (Mask8 m = occ; m != 0; m &= m - 1) occluded_[owner[std::countr_zero(m)]] = 1;
        continue;
      }
      for (Mask8 m = active & ~occ; m != 0; m &= m - 1) {
        const uint32_t r = owner[std::countr_zero(m)];
        AddEmitterSample(nee_paths_[r], request_contribution_[r]);
      }
      // An occluded sample's zero goes through AddNonFiniteEmitterSamples like an untraced one.
      for (Mask8 m = occ; m != 0; m &= m - 1) request_traced_[owner[std::countr_zero(m)]] = 0;
    }
    if (add_here) AddNonFiniteEmitterSamples();
    stats_->rays += shadows_.size();  // as in Traverse: every queued ray is an active lane
    stats_->packets += shadows_.packets.size();
  }

  // One emitter sample's light (sum `direct`, of n_light = 1 samples) weighted by the path's
  // throughput at the vertex: AddEmitterSamples' last line.
  void AddEmitterSample(uint32_t i, const Color3f& contribution) {
    Color3f direct;
    direct += contribution;
    L_[i] += nee_throughput_[i] * direct * 1.0f;
  }

  // With one emitter sample per vertex: the zero light of the untraced or occluded samples of
  // paths whose throughput is not finite. Their zero is skipped everywhere else, which changes
  // no bit for a finite throughput (L starts at +0 and never becomes -0); here it makes the
  // NaN that Inf or NaN times zero gives, as AddEmitterSamples does.
  void AddNonFiniteEmitterSamples() {
    for (const uint32_t r : nonfinite_nee_) {
      if (!request_traced_[r]) AddEmitterSample(nee_paths_[r], Color3f{});
    }
  }

  // Each path's emitter samples, summed in sample order, weighted by its throughput at the
  // vertex (the scalar integrators add them before shading the next vertex; so does this).
  // With one sample per vertex TraceShadows has added them already.
  void AddEmitterSamples() {
    const int n_light = rules_.light_samples;
    if (n_light == 1) return;
    const float inv_n = 1.0f / float(n_light);
    for (size_t p = 0; p < nee_paths_.size(); ++p) {
      const uint32_t i = nee_paths_[p];
      Color3f direct;
      for (int s = 0; s < n_light; ++s) {
        const size_t r = p * size_t(n_light) + size_t(s);
        // EmitterSampleResult: adding its zero for an untraced or occluded sample changes no
        // bit (direct starts at +0 and never becomes -0), so those rows are skipped.
        if (request_traced_[r] && !occluded_[r]) direct += request_contribution_[r];
      }
      L_[i] += nee_throughput_[i] * direct * inv_n;
    }
  }

  // Splats the wave's samples in the scalar loop's order (row, pixel, sample) with the kernel
  // table's splat slot; non-finite samples are dropped and counted.
  void Splat(const PixelFilter& filter, int x0, int y0, int x1, int y1, size_t samples,
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

  /// The BSDF stage's SoA columns, one row per entry that samples its BSDF at this vertex,
  /// grouped by material tag: a tag's rows are contiguous slots [begin[t], next[t]), one batch
  /// for the bsdf slot as it is (ShadeHitsWith's partition, gather and scatter are not needed),
  /// each group in queue order. The groups are sized by a count of the entries that go on (an
  /// upper bound: roulette and whitted end some first). Per slot: the path, its queue entry
  /// (for the shading point), material row, wo in the local frame and the numbers (inputs);
  /// wi (local), weight f·|cos θi|/pdf, pdf (0: no sample) and eta (outputs, written by the
  /// bsdf slot).
  struct BsdfColumns {
    std::vector<uint32_t> path, entry, material_index;
    std::vector<float> roulette_scale;
    AlignedVector<float> wo_x, wo_y, wo_z, u_lobe, u_x, u_y;
    AlignedVector<float> wi_x, wi_y, wi_z, weight_r, weight_g, weight_b, pdf, eta;
    // Groups 0..kMaterialTagCount - 1 by tag, group kMaterialTagCount: no material.
    uint32_t begin[kMaterialGroups] = {}, next[kMaterialGroups] = {};
    size_t rows = 0;

    size_t size() const { return rows; }
    size_t Bytes() const {
      return VectorsBytes(path, entry, material_index, roulette_scale, wo_x, wo_y, wo_z, u_lobe,
                          u_x, u_y, wi_x, wi_y, wi_z, weight_r, weight_g, weight_b, pdf, eta);
    }
    /// As EmitterColumns::Clear: room for `capacity` rows (inputs and outputs), written in
    /// place; only grows. group_rows: the most rows each group can get (they sum to at most
    /// capacity).
    void Clear(size_t capacity, const uint32_t (&group_rows)[kMaterialGroups]) {
      rows = 0;
      GrowColumns(capacity, &path, &entry, &material_index, &roulette_scale, &wo_x, &wo_y, &wo_z,
                  &u_lobe, &u_x, &u_y, &wi_x, &wi_y, &wi_z, &weight_r, &weight_g, &weight_b, &pdf,
                  &eta);
      uint32_t at = 0;
      for (int g = 0; g < kMaterialGroups; ++g) begin[g] = next[g] = at, at += group_rows[g];
    }
    /// Writes slot c of the group being filled (the caller advances next and rows).
    void Put(uint32_t c, uint32_t path_id, uint32_t queue_entry, MaterialRef ref, const Vec3f& wo,
             float lobe, const Vec2f& dir, float scale) {
      path[c] = path_id, entry[c] = queue_entry, roulette_scale[c] = scale;
      material_index[c] = ref.index();
      wo_x[c] = wo.x, wo_y[c] = wo.y, wo_z[c] = wo.z;
      u_lobe[c] = lobe, u_x[c] = dir.x, u_y[c] = dir.y;
    }
  };

  /// The spawn stage's SoA columns, one row per path that goes on, in next-queue order: the
  /// queue entry of its shading point and the sampled direction in that point's frame.
  struct SpawnColumns {
    std::vector<uint32_t> entry;
    AlignedVector<float> wi_x, wi_y, wi_z;
    size_t Bytes() const { return VectorsBytes(entry, wi_x, wi_y, wi_z); }
    /// Room for `capacity` rows, written in place; only grows.
    void Clear(size_t capacity) { GrowColumns(capacity, &entry, &wi_x, &wi_y, &wi_z); }
    SpawnInputs Inputs() const { return {entry.data(), wi_x.data(), wi_y.data(), wi_z.data()}; }
  };

  /// The emitter stage's SoA columns, one row per emitter sample that picked an area light,
  /// grouped by the material tag of its shading point as BsdfColumns is (a tag's rows are
  /// contiguous slots [begin[t], next[t]) in request order, one batch for the area_light and
  /// area_request slots; the groups are sized by the entries that go on times the emitter
  /// samples per vertex). Per slot: its request, queue
  /// entry (for the shading point), light, pick probability, reference point (the shading
  /// point), wo (local) and numbers (inputs); the light sample (written by the area_light slot);
  /// the request: traced flag, shadow ray and contribution (written by the area_request slot).
  struct EmitterColumns {
    std::vector<uint32_t> request, entry, light;
    std::vector<float> pick_pmf;
    AlignedVector<float> ref_x, ref_y, ref_z, wo_x, wo_y, wo_z, u_x, u_y;
    AlignedVector<float> p_x, p_y, p_z, n_x, n_y, n_z, ng_x, ng_y, ng_z, pdf;
    std::vector<uint8_t> traced;
    AlignedVector<float> o_x, o_y, o_z, d_x, d_y, d_z, r, g, b;
    uint32_t begin[kMaterialGroups] = {}, next[kMaterialGroups] = {};
    size_t rows = 0;

    size_t size() const { return rows; }
    size_t Bytes() const {
      return VectorsBytes(request, entry, light, pick_pmf, ref_x, ref_y, ref_z, wo_x, wo_y, wo_z,
                          u_x, u_y, p_x, p_y, p_z, n_x, n_y, n_z, ng_x, ng_y, ng_z, pdf, traced,
                          o_x, o_y, o_z, d_x, d_y, d_z, r, g, b);
    }
    /// Empties the columns and makes room for up to `capacity` rows (sized, not pushed: the
    /// rows are written in place, which keeps the per-sample loop free of push_back calls).
    /// The columns only grow, so a wave sizes them once. group_rows: the most rows each
    /// group can get (they sum to at most capacity).
    void Clear(size_t capacity, const uint32_t (&group_rows)[kMaterialGroups]) {
      rows = 0;
      GrowColumns(capacity, &request, &entry, &light, &pick_pmf, &ref_x, &ref_y, &ref_z, &wo_x,
                  &wo_y, &wo_z, &u_x, &u_y, &p_x, &p_y, &p_z, &n_x, &n_y, &n_z, &ng_x, &ng_y, &ng_z,
                  &pdf);
      GrowColumns(capacity, &traced, &o_x, &o_y, &o_z, &d_x, &d_y, &d_z, &r, &g, &b);
      uint32_t at = 0;
      for (int t = 0; t < kMaterialGroups; ++t) begin[t] = next[t] = at, at += group_rows[t];
    }
    /// Writes slot c of the group being filled (the caller advances next and rows).
    void Put(uint32_t c, uint32_t req, uint32_t queue_entry, uint32_t light_row, float pmf,
             const Vec3f& ref, const Vec3f& wo, const Vec2f& u) {
      request[c] = req, entry[c] = queue_entry, light[c] = light_row, pick_pmf[c] = pmf;
      ref_x[c] = ref.x, ref_y[c] = ref.y, ref_z[c] = ref.z, u_x[c] = u.x, u_y[c] = u.y;
      wo_x[c] = wo.x, wo_y[c] = wo.y, wo_z[c] = wo.z;
    }
  };

  /// The emitter stage's SoA columns of one infinite light (an environment map or a distant
  /// disk), one row per emitter sample that picked it (in request order): its request, queue
  /// entry, pick probability and numbers (inputs); the sample (outputs, written by the
  /// environment or distant_disk slot).
  struct InfiniteLightColumns {
    std::vector<uint32_t> request, entry;
    std::vector<float> pick_pmf;
    AlignedVector<float> u_x, u_y, wi_x, wi_y, wi_z, r, g, b, pdf;
    size_t rows = 0;

    size_t size() const { return rows; }
    size_t Bytes() const {
      return VectorsBytes(request, entry, pick_pmf, u_x, u_y, wi_x, wi_y, wi_z, r, g, b, pdf);
    }
    /// As EmitterColumns::Clear: room for `capacity` rows, written in place; only grows.
    void Clear(size_t capacity) {
      rows = 0;
      GrowColumns(capacity, &request, &entry, &pick_pmf, &u_x, &u_y, &wi_x, &wi_y, &wi_z, &r, &g,
                  &b, &pdf);
    }
    void Push(uint32_t req, uint32_t queue_entry, float pmf, const Vec2f& u) {
      const size_t c = rows++;
      request[c] = req, entry[c] = queue_entry, pick_pmf[c] = pmf, u_x[c] = u.x, u_y[c] = u.y;
    }
    EnvironmentBatchInputs Inputs() const { return {u_x.data(), u_y.data()}; }
    EnvironmentBatchOutputs Outputs() {
      return {wi_x.data(), wi_y.data(), wi_z.data(), r.data(), g.data(), b.data(), pdf.data()};
    }
  };

  /// The shadow_rows slot's output: the traced area-light rows of a bounce, compacted.
  struct ShadowRowColumns {
    std::vector<uint32_t> request;
    AlignedVector<float> o_x, o_y, o_z, d_x, d_y, d_z, r, g, b;
    size_t Bytes() const { return VectorsBytes(request, o_x, o_y, o_z, d_x, d_y, d_z, r, g, b); }
    /// Room for `capacity` rows, written in place; only grows.
    void Clear(size_t capacity) {
      GrowColumns(capacity, &request, &o_x, &o_y, &o_z, &d_x, &d_y, &d_z, &r, &g, &b);
    }
    ShadowRowOutputs Outputs() {
      return {request.data(), o_x.data(), o_y.data(), o_z.data(), d_x.data(),
              d_y.data(),     d_z.data(), r.data(),   g.data(),   b.data()};
    }
  };

  /// The splat stage's SoA columns: film position and radiance of each finite sample, rows
  /// [0, rows).
  struct SplatColumns {
    AlignedVector<float> sx, sy, r, g, b;
    size_t rows = 0;
    size_t Bytes() const { return VectorsBytes(sx, sy, r, g, b); }
    /// Room for `capacity` rows, written in place (no push_back's capacity check per column
    /// and row); only grows.
    void Clear(size_t capacity) {
      rows = 0;
      GrowColumns(capacity, &sx, &sy, &r, &g, &b);
    }
    void Push(float x, float y, const Color3f& L) {
      const size_t c = rows++;
      sx[c] = x, sy[c] = y, r[c] = L.r, g[c] = L.g, b[c] = L.b;
    }
    FilmSamples View() const { return {sx.data(), sy.data(), r.data(), g.data(), b.data(), rows}; }
  };

  // The tile being rendered (RenderTile sets them).
  const Scene* scene_ = nullptr;
  const WavefrontKernels* kernels_ = nullptr;
  VertexRules rules_;
  TileSampleStats* stats_ = nullptr;

  // Path state (SoA, by path id).
  std::vector<PathSampler> sampler_;
  bool sobol_ = false;
  bool vertex_batch_ = false;  // Sample's groups take the vertices slot (SampleGroupBatch)
  // Generation scratch and the Sobol' numbers of the current vertex (sobol_ only).
  std::vector<int> gen_px_, gen_py_;
  std::vector<float> gen_sx_, gen_sy_;
  std::vector<Vec2f> jitter_, lens_;
  std::vector<uint32_t> all_paths_, continuing_;
  std::vector<float> roulette_, bsdf_lobe_;
  std::vector<Vec2f> light_point_, bsdf_direction_;
  std::vector<uint32_t> draw_seed_, draw_index_;
  std::vector<float> draw_x_, draw_y_;
  std::vector<Color3f> L_, throughput_, nee_throughput_;
  std::vector<float> eta_, prev_pdf_;
  std::vector<Vec3f> prev_p_;
  std::vector<uint32_t> specular_;  // a flag; 32 bits so that a SIMD kernel can scatter it
  // The path of each result slot (scalar splat order: row, pixel, sample), kNoPath for the
  // slots of inactive pixels; Splat reads the path's film position and radiance through it.
  std::vector<uint32_t> path_of_slot_;
  // Queues and per-bounce scratch.
  RayQueue rays_, next_rays_, shadows_;
  std::vector<HitPacket8> hits_;
  std::vector<Mask8> hit_mask_;
  std::vector<SurfaceInteraction> its_;
  std::vector<Vec3f> wo_;
  // The entries that go on to the sampling stage, in queue order, rows [0, n_goes_on_): a list
  // rather than a flag per entry, so that Sample has no branch per entry on whether its path
  // ended here. The interaction slot writes it (HitLists::entries) with room for 8 per packet.
  std::vector<uint32_t> goes_on_, grouped_;  // grouped_: GroupEntries' scratch
  size_t n_goes_on_ = 0;
  uint32_t goes_on_tags_[kMaterialGroups] = {};  // entries that go on, by material group
  std::vector<uint32_t> area_hits_;              // entries whose hit is on an area light (HitLists)
  // The emitter samples' requests (EmitterSampleRequest as columns), rows [0, n_requests_).
  std::vector<uint8_t> request_traced_;
  std::vector<Color3f> request_contribution_;
  size_t n_requests_ = 0;
  // A wave's escaped rays, when they go through the environment_eval batch (ShadeEscaped).
  struct EscapedColumns {
    std::vector<uint32_t> q;           // queue entry
    std::vector<uint8_t> mis;          // 1: MIS-weighted against the previous BSDF sample
    std::vector<float> w_x, w_y, w_z;  // unit direction (world)
    std::vector<float> r, g, b, pdf;   // one map's radiance and emitter-sampling pdf
    std::vector<Color3f> light;        // the maps' sum
    void Clear() { q.clear(), mis.clear(), w_x.clear(), w_y.clear(), w_z.clear(); }
    void Push(uint32_t entry, const Vec3f& w, bool weighted) {
      q.push_back(entry), mis.push_back(uint8_t(weighted));
      w_x.push_back(w.x), w_y.push_back(w.y), w_z.push_back(w.z);
    }
    size_t Bytes() const { return VectorsBytes(q, mis, w_x, w_y, w_z, r, g, b, pdf, light); }
  };
  EscapedColumns escaped_;
  std::vector<uint8_t> occluded_;
  std::vector<uint32_t> nee_paths_;
  std::vector<uint32_t> nonfinite_nee_;  // requests of nee paths whose throughput is not finite
  BsdfColumns bsdf_;
  SpawnColumns spawn_;
  EmitterColumns area_;
  std::vector<InfiniteLightColumns> environment_;   // one per environment map of the scene
  std::vector<InfiniteLightColumns> distant_disk_;  // one per distant disk of the scene
  SplatColumns splat_;
  ShadowRowColumns shadow_rows_;
};

namespace {

// The oracle's traversal kernels: each active lane alone through Intersect1 / Occluded1.
Mask8 OracleIntersect8(const WavefrontAccel& accel, const RayPacket8& rays, Mask8 active,
                       HitPacket8* hits) {
  Mask8 got = 0;
  for (Mask8 todo = active & kAllLanes; todo != 0; todo &= todo - 1) {
    const int j = std::countr_zero(todo);
    Hit h;
    if (!Intersect1(*accel.bvh, GetLaneRay(rays, j), &h)) continue;
    SetLaneHit(hits, j, h.t, h.b1, h.b2, h.prim);
    got |= LaneBit(j);
  }
  return got;
}

Mask8 OracleOccluded8(const WavefrontAccel& accel, const RayPacket8& rays, Mask8 active) {
  Mask8 got = 0;
  for (Mask8 todo = active & kAllLanes; todo != 0; todo &= todo - 1) {
    const int j = std::countr_zero(todo);
    if (Occluded1(*accel.bvh, GetLaneRay(rays, j))) got |= LaneBit(j);
  }
  return got;
}

void OracleAreaLight(const WavefrontAccel&, const Scene& scene, TriangleSampling mode, size_t n,
                     const AreaLightBatchInputs& in, const AreaLightBatchOutputs& out) {
  SampleAreaLightBatch(scene, mode, n, in, out);
}

void OracleInteraction(const WavefrontAccel&, const Scene& scene, const RayPacket8* rays,
                       const HitPacket8* hits, const Mask8* hit_mask, size_t packets,
                       const InteractionRows& out, HitLists* lists) {
  MakeInteractionBatch(scene, rays, hits, hit_mask, packets, out, lists);
}

}  // namespace

WavefrontKernels OracleWavefrontKernels(const Bvh& bvh) {
  return {.accel = {.bvh = &bvh},
          .intersect8 = OracleIntersect8,
          .occluded8 = OracleOccluded8,
          .sobol2d = ScrambledSobol2DBatch,
          .sobol1d = ScrambledSobol1DBatch,
          .bsdf = ShadeBatch,
          .splat = SplatSamples,
          .area_light = OracleAreaLight,
          .area_request = AreaEmitterRequestBatch,
          .shadow_rows = CompactShadowRows,
          .environment = SampleEnvironmentBatch,
          .environment_eval = EvalEnvironmentBatch,
          .distant_disk = SampleDistantDiskBatch,
          .interaction = OracleInteraction,
          .spawn = SpawnRayBatch,
          .vertices = DecideVertices,
          .continuation = ContinuePaths,
          .emission = AddAreaEmissions,
          .name = "scalar-oracle"};
}

bool ForceScalar() {
  const char* v = std::getenv("PTLAB_FORCE_SCALAR");
  return v != nullptr && v[0] != '\0' && std::strcmp(v, "0") != 0;
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
