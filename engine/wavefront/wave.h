// The wavefront's state, private to engine/wavefront/: path state (SoA, by path id), ray
// queues, the stages' columns, and one member function per step, defined in the stage
// files wave_*.cpp (wave.cpp sequences them).
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/core/memory.h"
#include "engine/render/integrator_common.h"
#include "engine/wavefront/interaction.h"
#include "engine/wavefront/soa.h"
#include "engine/wavefront/splat.h"
#include "engine/wavefront/vertices.h"
#include "engine/wavefront/wavefront.h"

// The column lists of the wave's SoA batches, X(container, element type, name), one column a
// line (engine/wavefront/soa.h); the structs below say what each batch's rows are.

#define PTLAB_WAVE_BSDF_COLUMNS(X)         \
  X(std::vector, uint32_t, path)           \
  X(std::vector, uint32_t, entry)          \
  X(std::vector, uint32_t, material_index) \
  X(std::vector, float, roulette_scale)    \
  X(AlignedVector, float, wo_x)            \
  X(AlignedVector, float, wo_y)            \
  X(AlignedVector, float, wo_z)            \
  X(AlignedVector, float, u_lobe)          \
  X(AlignedVector, float, u_x)             \
  X(AlignedVector, float, u_y)             \
  X(AlignedVector, float, wi_x)            \
  X(AlignedVector, float, wi_y)            \
  X(AlignedVector, float, wi_z)            \
  X(AlignedVector, float, weight_r)        \
  X(AlignedVector, float, weight_g)        \
  X(AlignedVector, float, weight_b)        \
  X(AlignedVector, float, pdf)             \
  X(AlignedVector, float, eta)             \
  X(AlignedVector, float, delta)

#define PTLAB_WAVE_SPAWN_COLUMNS(X) \
  X(std::vector, uint32_t, entry)   \
  X(AlignedVector, float, wi_x)     \
  X(AlignedVector, float, wi_y)     \
  X(AlignedVector, float, wi_z)

#define PTLAB_WAVE_EMITTER_COLUMNS(X) \
  X(std::vector, uint32_t, request)   \
  X(std::vector, uint32_t, entry)     \
  X(std::vector, uint32_t, light)     \
  X(std::vector, float, pick_pmf)     \
  X(AlignedVector, float, ref_x)      \
  X(AlignedVector, float, ref_y)      \
  X(AlignedVector, float, ref_z)      \
  X(AlignedVector, float, wo_x)       \
  X(AlignedVector, float, wo_y)       \
  X(AlignedVector, float, wo_z)       \
  X(AlignedVector, float, u_x)        \
  X(AlignedVector, float, u_y)        \
  X(AlignedVector, float, p_x)        \
  X(AlignedVector, float, p_y)        \
  X(AlignedVector, float, p_z)        \
  X(AlignedVector, float, n_x)        \
  X(AlignedVector, float, n_y)        \
  X(AlignedVector, float, n_z)        \
  X(AlignedVector, float, ng_x)       \
  X(AlignedVector, float, ng_y)       \
  X(AlignedVector, float, ng_z)       \
  X(AlignedVector, float, pdf)        \
  X(std::vector, uint8_t, traced)     \
  X(AlignedVector, float, o_x)        \
  X(AlignedVector, float, o_y)        \
  X(AlignedVector, float, o_z)        \
  X(AlignedVector, float, d_x)        \
  X(AlignedVector, float, d_y)        \
  X(AlignedVector, float, d_z)        \
  X(AlignedVector, float, r)          \
  X(AlignedVector, float, g)          \
  X(AlignedVector, float, b)

#define PTLAB_WAVE_OTHER_PICK_COLUMNS(X) \
  X(std::vector, uint32_t, request)      \
  X(std::vector, uint32_t, entry)        \
  X(std::vector, uint32_t, emitter)      \
  X(std::vector, float, pick_pmf)        \
  X(std::vector, float, u_x)             \
  X(std::vector, float, u_y)

#define PTLAB_WAVE_INFINITE_LIGHT_COLUMNS(X) \
  X(std::vector, uint32_t, request)          \
  X(std::vector, uint32_t, entry)            \
  X(std::vector, float, pick_pmf)            \
  X(AlignedVector, float, u_x)               \
  X(AlignedVector, float, u_y)               \
  X(AlignedVector, float, wi_x)              \
  X(AlignedVector, float, wi_y)              \
  X(AlignedVector, float, wi_z)              \
  X(AlignedVector, float, r)                 \
  X(AlignedVector, float, g)                 \
  X(AlignedVector, float, b)                 \
  X(AlignedVector, float, pdf)

#define PTLAB_WAVE_SHADOW_ROW_COLUMNS(X) \
  X(std::vector, uint32_t, request)      \
  X(AlignedVector, float, o_x)           \
  X(AlignedVector, float, o_y)           \
  X(AlignedVector, float, o_z)           \
  X(AlignedVector, float, d_x)           \
  X(AlignedVector, float, d_y)           \
  X(AlignedVector, float, d_z)           \
  X(AlignedVector, float, r)             \
  X(AlignedVector, float, g)             \
  X(AlignedVector, float, b)

#define PTLAB_WAVE_SPLAT_COLUMNS(X) \
  X(AlignedVector, float, sx)       \
  X(AlignedVector, float, sy)       \
  X(AlignedVector, float, r)        \
  X(AlignedVector, float, g)        \
  X(AlignedVector, float, b)

#define PTLAB_WAVE_ESCAPED_COLUMNS(X) \
  X(std::vector, uint32_t, q)         \
  X(std::vector, uint8_t, mis)        \
  X(std::vector, float, w_x)          \
  X(std::vector, float, w_y)          \
  X(std::vector, float, w_z)          \
  X(std::vector, float, r)            \
  X(std::vector, float, g)            \
  X(std::vector, float, b)            \
  X(std::vector, float, pdf)          \
  X(std::vector, Color3f, light)

namespace ptlab {

/// One tile's paths, wave by wave. Path state is SoA, indexed by path id (generation order);
/// the per-bounce scratch (hits, interactions) is indexed by queue entry. Each worker thread has
/// one on the heap, cache-line aligned so that no two threads' wavefronts share a line (the
/// vectors' end pointers are written at every push).
class alignas(kColumnAlignment) Wavefront {
 public:
  void RenderTile(const RenderContext& ctx, const WavefrontKernels& kernels, TileSampleStats* stats,
                  const Camera& camera, const PixelFilter& filter, int x0, int y0, int x1, int y1,
                  uint32_t s_begin, uint32_t s_end, uint64_t seed, FilmBlock* block,
                  const PixelSampling* pixels);

  /// Heap bytes of the path state, queues and columns: capacity × element size. They only grow
  /// (cleared, never shrunk), so this is the high-water mark of every tile rendered so far.
  size_t Bytes() const;

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr int kLanes = static_cast<int>(kPacketWidth);
  /// Pixel rows of a tile traced together as one wave (even: camera packets are 4x2 pixels).
  /// With 16 samples per pass and 32-pixel tiles a wave holds 2048 paths.
  static constexpr int kWaveRows = 4;
  /// A result slot without a path (its pixel is inactive).
  static constexpr uint32_t kNoPath = ~uint32_t{0};

  /// What each integrator does at a path vertex. Every integrator of integrator.cpp is one set of
  /// rules over the same vertex stages; the rules reproduce its operations in its order.
  struct VertexRules {
    using Roulette = VertexBatchRules::Roulette;  // the vertices slot's (vertices.h)
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

  /// The rules of `desc`.
  static VertexRules RulesFor(const IntegratorDesc& desc);

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

  static double Seconds(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  }

  // Gives each column at least `capacity` rows (columns written in place only grow, so a wave
  // sizes them once).
  template <class... Columns>
  static void GrowColumns(size_t capacity, Columns*... columns) {
    ((columns->size() < capacity ? columns->resize(capacity) : void()), ...);
  }

  // wave.cpp
  void Bounce(int depth);

  // wave_generate.cpp
  void Generate(const Camera& camera, int x0, int y0, int x1, int y1, uint32_t s_begin,
                uint32_t s_end, uint64_t seed, const PixelSampling* pixels);

  // wave_traverse.cpp
  void Traverse();
  void TraceShadows();
  void AddEmitterSample(uint32_t i, const Color3f& contribution);
  void AddNonFiniteEmitterSamples();
  void AddEmitterSamples();

  // wave_shade.cpp
  void Shade(int depth);
  bool EscapedRaysBatch() const;
  void ShadeEscaped();

  // wave_sample.cpp
  void Sample(int depth);
  void GroupEntries();
  void SampleGroup(int depth, bool delta, int g, size_t k, size_t end);
  void RouteOtherPicks(size_t n);
  void DrawVertexNumbers(int depth);
  void FillSobolRows(const std::vector<uint32_t>& paths, uint32_t sub, uint32_t sub_count);
  void DrawSobol1D(uint32_t dim, float* out);
  void DrawSobol2D(uint32_t dim, Vec2f* out);

  // wave_emitters.cpp
  void SampleAreaLights();
  void QueueShadowRows(size_t m);
  void SampleInfiniteLights();

  // wave_bsdfs.cpp
  void SampleBsdfs();

  // wave_splat.cpp
  void Splat(const PixelFilter& filter, int x0, int y0, int x1, int y1, size_t samples,
             FilmBlock* block, const PixelSampling* pixels);

  // Inline: called per row from more than one stage file.
  // Now, for the stage times; the epoch when the tile's stats do not time its stages.
  Clock::time_point StageClock() const {
    return stats_->time_stages ? Clock::now() : Clock::time_point{};
  }

  // Row r of the request columns from a finished request; the row's flag is already 0 and
  // stays so when the request traces nothing. Field by field, so the request stays in
  // registers instead of being assembled on the stack and copied. The shadow ray goes straight
  // into the shadow queue (owner r), in the order the requests finish (delta lights, then
  // area lights by material tag, environment, disk batches): TraceShadows answers by owner, so
  // the order changes no result, and with one kind of emitter and material it is request order.
  void StoreRequest(uint32_t r, const integrator::EmitterSampleRequest& req) {
    if (!req.traced) return;
    request_traced_[r] = 1;
    shadows_.Push(req.shadow, r);
    Color3f& contribution = request_contribution_[r];
    contribution.r = req.contribution.r, contribution.g = req.contribution.g;
    contribution.b = req.contribution.b;
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
    PTLAB_SOA_COLUMNS(PTLAB_WAVE_BSDF_COLUMNS)
    // Groups 0..kMaterialTagCount - 1 by tag, group kMaterialTagCount: no material.
    uint32_t begin[kMaterialGroups] = {}, next[kMaterialGroups] = {};
    size_t rows = 0;

    size_t size() const { return rows; }
    /// As EmitterColumns::Clear: room for `capacity` rows (inputs and outputs), written in
    /// place; only grows. group_rows: the most rows each group can get (they sum to at most
    /// capacity).
    void Clear(size_t capacity, const uint32_t (&group_rows)[kMaterialGroups]) {
      rows = 0;
      Grow(capacity);
      uint32_t at = 0;
      for (int g = 0; g < kMaterialGroups; ++g) begin[g] = next[g] = at, at += group_rows[g];
    }
  };

  /// The spawn stage's SoA columns, one row per path that goes on, in next-queue order: the
  /// queue entry of its shading point and the sampled direction in that point's frame.
  struct SpawnColumns {
    PTLAB_SOA_COLUMNS(PTLAB_WAVE_SPAWN_COLUMNS)
    /// Room for `capacity` rows, written in place; only grows.
    void Clear(size_t capacity) { Grow(capacity); }
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
    PTLAB_SOA_COLUMNS(PTLAB_WAVE_EMITTER_COLUMNS)
    uint32_t begin[kMaterialGroups] = {}, next[kMaterialGroups] = {};
    size_t rows = 0;
    /// The light samples' radiance (AreaLightBatchOutputs' le columns): sized, as the columns
    /// above, only in a scene with textured area lights; empty otherwise.
    AlignedVector<float> le_r, le_g, le_b;

    size_t size() const { return rows; }
    /// Empties the columns and makes room for up to `capacity` rows (sized, not pushed: the
    /// rows are written in place, which keeps the per-sample loop free of push_back calls).
    /// The columns only grow, so a wave sizes them once. group_rows: the most rows each
    /// group can get (they sum to at most capacity).
    void Clear(size_t capacity, const uint32_t (&group_rows)[kMaterialGroups]) {
      rows = 0;
      Grow(capacity);
      uint32_t at = 0;
      for (int t = 0; t < kMaterialGroups; ++t) begin[t] = next[t] = at, at += group_rows[t];
    }
  };

  /// The vertices slot's picks of emitters other than area lights (environment maps, distant
  /// disks, delta lights), one group's, in request order: its request, queue entry, emitter
  /// (EmitterRef's bits), pick probability and numbers. RouteOtherPicks hands each to its stage.
  struct OtherPickColumns {
    PTLAB_SOA_COLUMNS(PTLAB_WAVE_OTHER_PICK_COLUMNS)
    /// Room for `capacity` rows, written in place; only grows.
    void Clear(size_t capacity) { Grow(capacity); }
  };

  /// The emitter stage's SoA columns of one infinite light (an environment map or a distant
  /// disk), one row per emitter sample that picked it (in request order): its request, queue
  /// entry, pick probability and numbers (inputs); the sample (outputs, written by the
  /// environment or distant_disk slot).
  struct InfiniteLightColumns {
    PTLAB_SOA_COLUMNS(PTLAB_WAVE_INFINITE_LIGHT_COLUMNS)
    size_t rows = 0;

    size_t size() const { return rows; }
    /// As EmitterColumns::Clear: room for `capacity` rows, written in place; only grows.
    void Clear(size_t capacity) {
      rows = 0;
      Grow(capacity);
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
    PTLAB_SOA_COLUMNS(PTLAB_WAVE_SHADOW_ROW_COLUMNS)
    /// Room for `capacity` rows, written in place; only grows.
    void Clear(size_t capacity) { Grow(capacity); }
    ShadowRowOutputs Outputs() {
      return {request.data(), o_x.data(), o_y.data(), o_z.data(), d_x.data(),
              d_y.data(),     d_z.data(), r.data(),   g.data(),   b.data()};
    }
  };

  /// The splat stage's SoA columns: film position and radiance of each finite sample, rows
  /// [0, rows).
  struct SplatColumns {
    PTLAB_SOA_COLUMNS(PTLAB_WAVE_SPLAT_COLUMNS)
    size_t rows = 0;
    /// Room for `capacity` rows, written in place (no push_back's capacity check per column
    /// and row); only grows.
    void Clear(size_t capacity) {
      rows = 0;
      Grow(capacity);
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
  // Generation scratch (each path's pixel and sample index, film position, lens point) and
  // the Sobol' numbers of the current vertex (sobol_ only).
  std::vector<int32_t> gen_px_, gen_py_;
  std::vector<uint32_t> gen_s_;
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
    // q: queue entry; mis: 1 when MIS-weighted against the previous BSDF sample; w: unit
    // direction (world); r, g, b, pdf: one map's radiance and emitter-sampling pdf; light: the
    // maps' sum.
    PTLAB_SOA_COLUMNS(PTLAB_WAVE_ESCAPED_COLUMNS)
    void Clear() { q.clear(), mis.clear(), w_x.clear(), w_y.clear(), w_z.clear(); }
    void Push(uint32_t entry, const Vec3f& w, bool weighted) {
      q.push_back(entry), mis.push_back(uint8_t(weighted));
      w_x.push_back(w.x), w_y.push_back(w.y), w_z.push_back(w.z);
    }
  };
  EscapedColumns escaped_;
  std::vector<uint8_t> occluded_;
  std::vector<uint32_t> nee_paths_;
  std::vector<uint32_t> nonfinite_nee_;  // requests of nee paths whose throughput is not finite
  BsdfColumns bsdf_;
  SpawnColumns spawn_;
  EmitterColumns area_;
  OtherPickColumns other_picks_;
  std::vector<InfiniteLightColumns> environment_;   // one per environment map of the scene
  std::vector<InfiniteLightColumns> distant_disk_;  // one per distant disk of the scene
  SplatColumns splat_;
  ShadowRowColumns shadow_rows_;
};

}  // namespace ptlab
