// Per-target kernel of simd/wavefront/vertices8.h (re-included once per Highway target): the
// sampling stage's decisions at a batch of path vertices, one row per 64-bit lane.

#if defined(PTLAB_SIMD_VERTEX_BATCH8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_VERTEX_BATCH8_INL_H_
#undef PTLAB_SIMD_VERTEX_BATCH8_INL_H_
#else
#define PTLAB_SIMD_VERTEX_BATCH8_INL_H_
#endif

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "engine/core/rng.h"
#include "engine/render/integrator_common.h"
#include "engine/sampling/guide_table.h"
#include "engine/sampling/sampler.h"
#include "engine/wavefront/vertices.h"
#include "hwy/highway.h"
#include "simd/pcg8-inl.h"
#include "simd/store_selected-inl.h"
#include "simd/transpose4-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// Each draw's PCG32 state from the path's state at the vertex: draw j steps from the state j
// steps on (Pcg32JumpOf(j)), as two columns (multiplier, addend) that per-lane draws gather
// from. A row draws 3 per emitter sample, 1 for the roulette and 3 for the BSDF: with up to two
// emitter samples, the 16 jumps of kDrawJumps cover them (and the state after them); rows with
// more get a table of their own.
template <size_t kCount>
struct DrawJumpTable {
  std::array<uint64_t, kCount> mul{}, add{};
  constexpr DrawJumpTable() {
    Pcg32Jump jump;
    for (size_t j = 0; j < kCount; ++j) {
      mul[j] = jump.mul, add[j] = jump.add;
      jump = {jump.mul * kPcg32Multiplier, jump.add * kPcg32Multiplier + 1};
    }
  }
};
inline constexpr DrawJumpTable<16> kDrawJumps{};

/// Jumps 0..count - 1: kDrawJumps', or computed when it is too short.
class VertexDrawJumps {
 public:
  explicit VertexDrawJumps(size_t count) {
    if (count <= kDrawJumps.mul.size()) return;
    more_mul_.resize(count), more_add_.resize(count);
    Pcg32Jump jump;
    for (size_t j = 0; j < count; ++j) {
      more_mul_[j] = jump.mul, more_add_[j] = jump.add;
      jump = {jump.mul * kPcg32Multiplier, jump.add * kPcg32Multiplier + 1};
    }
    mul_ = more_mul_.data(), add_ = more_add_.data();
  }
  const uint64_t* mul() const { return mul_; }
  const uint64_t* add() const { return add_; }
  Pcg32Jump operator[](size_t j) const { return {mul_[j], add_[j]}; }

 private:
  const uint64_t* mul_ = kDrawJumps.mul.data();
  const uint64_t* add_ = kDrawJumps.add.data();
  std::vector<uint64_t> more_mul_, more_add_;
};

// One vector of emitter samples' picks (SelectEmitter: uniform, or the scan of the power CDF),
// appended to the area and other columns in lane order, the lanes `active` selects. `pick` is
// the pick number; with `fold` (Sobol') u_x is the pick number too and is remapped, as
// SelectEmitter's u_remapped.
template <class DF, class DI, class DU>
struct EmitterPicks {
  DF df;
  DI di;
  DU du;
  const Scene& scene;
  uint32_t emitters;
  bool uniform;

  using VF = hn::Vec<DF>;
  using VI = hn::Vec<DI>;
  using VU = hn::Vec<DU>;

  void operator()(hn::Mask<DF> active, VU request, VI entry, VF ref_x, VF ref_y, VF ref_z,
                  VF wo_x, VF wo_y, VF wo_z, VF pick, VF u_x, VF u_y, bool fold,
                  VertexBatchOutputs* out) const {
    const EmitterSelectionTable& selection = scene.emitter_selection;
    const auto last_emitter = hn::Set(di, int32_t(emitters) - 1);
    const auto one_minus_eps = hn::Set(df, kOneMinusEpsilon);
    // std::min(a, b) / std::max(a, b) as the oracle's: b when b < a / a < b, else a.
    const auto min = [](VF a, VF b) { return hn::IfThenElse(hn::Lt(b, a), b, a); };
    VI k;
    VF pick_pmf;
    if (uniform) {
      // size_t(u * n), at most n - 1; 1/n; u * n - k, below 1.
      const auto scaled = hn::Mul(pick, hn::Set(df, float(emitters)));
      k = hn::Min(hn::ConvertTo(di, scaled), last_emitter);
      pick_pmf = hn::Set(df, 1.0f / float(emitters));
      if (fold) u_x = min(hn::Sub(scaled, hn::ConvertTo(df, k)), one_minus_eps);
    } else {
      // GuidedUpperBound's scan: the CDF entries not above u, counted.
      auto count = hn::Zero(di);
      for (uint32_t e = 0; e < emitters; ++e) {
        const auto below = hn::Not(hn::Lt(pick, hn::Set(df, selection.cdf[e])));
        count = hn::Sub(count, hn::VecFromMask(di, hn::RebindMask(di, below)));
      }
      k = hn::Min(count, last_emitter);
      pick_pmf = hn::GatherIndex(df, selection.pmf.data(), k);
      if (fold) {
        // PickCdfBin's u_remapped: (u - lo) / width below 1, 0.5 for a bin of zero width, ≥ 0.
        const auto has_lo = hn::RebindMask(df, hn::Gt(k, hn::Zero(di)));
        const auto lo = hn::IfThenElseZero(
            has_lo, hn::GatherIndex(df, selection.cdf.data(),
                                    hn::Max(hn::Sub(k, hn::Set(di, 1)), hn::Zero(di))));
        const auto width = hn::Sub(hn::GatherIndex(df, selection.cdf.data(), k), lo);
        const auto v = hn::IfThenElse(hn::Gt(width, hn::Zero(df)),
                                      min(hn::Div(hn::Sub(pick, lo), width), one_minus_eps),
                                      hn::Set(df, 0.5f));
        u_x = hn::IfThenElse(hn::Lt(v, hn::Zero(df)), hn::Zero(df), v);
      }
    }
    const auto bits = hn::GatherIndex(di, reinterpret_cast<const int32_t*>(scene.emitters.data()), k);
    const auto index_bits = hn::Set(di, int32_t(0x0fffffff));  // EmitterRef's index
    const auto area = hn::RebindMask(df, hn::Eq(hn::AndNot(index_bits, bits), hn::Zero(di)));
    const auto picked = hn::And(active, hn::Lt(hn::Zero(df), pick_pmf));
    const auto to_area = hn::And(picked, area);
    if (!hn::AllFalse(df, to_area)) {
      const AreaPickColumns& a = out->area;
      const auto to_area_i = hn::RebindMask(di, to_area);
      const auto to_area_u = hn::RebindMask(du, to_area);
      const size_t c = out->area_rows;
      const bool all = hn::AllTrue(df, to_area);
      const auto light = hn::And(bits, index_bits);
      StoreSelected(du, request, to_area_u, all, a.request + c);
      StoreSelected(di, entry, to_area_i, all, reinterpret_cast<int32_t*>(a.entry + c));
      StoreSelected(di, light, to_area_i, all, reinterpret_cast<int32_t*>(a.light + c));
      StoreSelected(df, pick_pmf, to_area, all, a.pick_pmf + c);
      StoreSelected(df, ref_x, to_area, all, a.ref_x + c);
      StoreSelected(df, ref_y, to_area, all, a.ref_y + c);
      StoreSelected(df, ref_z, to_area, all, a.ref_z + c);
      StoreSelected(df, wo_x, to_area, all, a.wo_x + c);
      StoreSelected(df, wo_y, to_area, all, a.wo_y + c);
      StoreSelected(df, wo_z, to_area, all, a.wo_z + c);
      StoreSelected(df, u_x, to_area, all, a.u_x + c);
      StoreSelected(df, u_y, to_area, all, a.u_y + c);
      out->area_rows = c + hn::CountTrue(df, to_area);
    }
    const auto to_other = hn::AndNot(area, picked);
    if (!hn::AllFalse(df, to_other)) {
      const OtherPickColumns& o = out->other;
      const auto to_other_i = hn::RebindMask(di, to_other);
      const auto to_other_u = hn::RebindMask(du, to_other);
      const size_t c = out->other_rows;
      const bool all = hn::AllTrue(df, to_other);
      StoreSelected(du, request, to_other_u, all, o.request + c);
      StoreSelected(di, entry, to_other_i, all, reinterpret_cast<int32_t*>(o.entry + c));
      StoreSelected(di, bits, to_other_i, all, reinterpret_cast<int32_t*>(o.emitter + c));
      StoreSelected(df, pick_pmf, to_other, all, o.pick_pmf + c);
      StoreSelected(df, u_x, to_other, all, o.u_x + c);
      StoreSelected(df, u_y, to_other, all, o.u_y + c);
      out->other_rows = c + hn::CountTrue(df, to_other);
    }
  }
};

inline void DecideVerticesKernel(const Scene& scene, const VertexBatchRules& rules, size_t n,
                                 const VertexBatchInputs& in, const VertexBatchPaths& paths,
                                 VertexBatchOutputs* out) {
  using Roulette = VertexBatchRules::Roulette;
  const uint32_t emitters = uint32_t(scene.emitters.size());
  const bool uniform = scene.integrator.light_selection == LightSelection::kUniform;
  const bool picks = rules.emitter_sample && emitters > 0;
  // The selections the twin does not scan (power over more than kScanUpperBoundMax emitters:
  // SelectEmitter's guide table) take the oracle, every row.
  if (picks && !uniform && emitters > kScanUpperBoundMax) {
    ptlab::DecideVertices(scene, rules, n, in, paths, out);
    return;
  }
  const hn::CappedTag<uint64_t, 8> d;
  const hn::RebindToSigned<decltype(d)> di64;
  const hn::Rebind<uint32_t, decltype(d)> du;
  const hn::Rebind<int32_t, decltype(d)> di;
  const hn::Rebind<float, decltype(d)> df;
  const size_t lanes = hn::Lanes(d);
  // The rows read in place: PathSampler's first two words are its stream's state and
  // increment, a SurfaceInteraction starts with p and holds its material as 32 bits, Vec3f,
  // Vec2f and Color3f are three and two floats.
  static_assert(PathSampler::RowLayoutHolds());
  static_assert(offsetof(SurfaceInteraction, p) == 0 && sizeof(SurfaceInteraction) % 4 == 0 &&
                offsetof(SurfaceInteraction, material) % 4 == 0 && sizeof(MaterialRef) == 4 &&
                sizeof(EmitterRef) == 4);
  static_assert(sizeof(Vec3f) == 3 * sizeof(float) && sizeof(Color3f) == 3 * sizeof(float) &&
                sizeof(Vec2f) == 2 * sizeof(float));
  constexpr int32_t kItsWords = int32_t(sizeof(SurfaceInteraction) / 4);
  constexpr int32_t kMaterialWord = int32_t(offsetof(SurfaceInteraction, material) / 4);
  const auto as_f = [](const auto* p) { return reinterpret_cast<const float*>(p); };
  const auto as_i = [](const auto* p) { return reinterpret_cast<const int32_t*>(p); };
  uint64_t* const rng = reinterpret_cast<uint64_t*>(paths.sampler);
  float* const throughput = reinterpret_cast<float*>(paths.throughput);
  float* const nee_throughput = reinterpret_cast<float*>(paths.nee_throughput);
  const uint32_t n_light = uint32_t(rules.light_samples);
  const bool sobol = rules.sobol;
  // Whether the rows get a BSDF row (and a roulette first), and the draws of a row in the
  // oracle's order: the emitter samples' picks and points, the roulette's number, the BSDF's
  // lobe and direction.
  const bool whitted_ends =
      rules.roulette == Roulette::kWhitted && rules.depth >= integrator::kWhittedMaxDepth;
  const bool bsdf = !rules.ends_path && !whitted_ends;
  const bool roulette = bsdf && rules.roulette != Roulette::kNone;
  const size_t roulette_draw = picks ? 3 * size_t(n_light) : 0;
  const size_t bsdf_draw = roulette_draw + (roulette ? 1 : 0);
  const size_t end_draw = bsdf ? bsdf_draw + 3 : roulette_draw;
  const VertexDrawJumps jumps(sobol ? 0 : std::max(end_draw + 1, size_t(3) * n_light));
  const EmitterPicks<decltype(df), decltype(di), decltype(du)> pick_emitters{
      df, di, du, scene, emitters, uniform};
  const float roulette_scale =
      rules.roulette == Roulette::kWhitted ? 1.0f / integrator::kWhittedContinuation : 1.0f;
  const size_t whole = n - n % lanes;  // the rows of whole vectors; the rest take the oracle
  const auto word64 = [&](hn::Vec<decltype(df)> lo, hn::Vec<decltype(df)> hi) {
    return hn::Or(hn::PromoteTo(d, hn::BitCast(du, lo)),
                  hn::ShiftLeft<32>(hn::PromoteTo(d, hn::BitCast(du, hi))));
  };
  // The requests of the whole vectors' rows: not traced (yet); the oracle sets the tail's.
  if (rules.emitter_sample)
    std::memset(out->request_traced + rules.first_request, 0, whole * n_light);
  // More than one emitter sample per vertex: the samples of rows [0, whole) first, one per
  // lane in request order (sample s of a row draws from its stream 3 s steps on).
  if (picks && n_light > 1) {
    const size_t requests = whole * n_light;
    alignas(32) int32_t row_of[8] = {}, sample_of[8] = {};
    for (size_t f = 0; f < requests; f += lanes) {
      const size_t count = std::min(lanes, requests - f);
      for (size_t j = 0; j < lanes; ++j) {
        const size_t g = j < count ? f + j : f;
        row_of[j] = int32_t(g / n_light), sample_of[j] = int32_t(g % n_light);
      }
      const auto row = hn::LoadU(di, row_of), sample = hn::LoadU(di, sample_of);
      const auto active = hn::FirstN(df, count);
      const auto entry = hn::GatherIndex(di, as_i(in.entries), row);
      const auto its_row = hn::Mul(entry, hn::Set(di, kItsWords));
      const auto wo_row = hn::Mul(entry, hn::Set(di, 3));
      const auto wo_x = hn::GatherIndex(df, as_f(in.wo), wo_row);
      const auto wo_y = hn::GatherIndex(df, as_f(in.wo), hn::Add(wo_row, hn::Set(di, 1)));
      const auto wo_z = hn::GatherIndex(df, as_f(in.wo), hn::Add(wo_row, hn::Set(di, 2)));
      const auto p_x = hn::GatherIndex(df, as_f(in.its), its_row);
      const auto p_y = hn::GatherIndex(df, as_f(in.its), hn::Add(its_row, hn::Set(di, 1)));
      const auto p_z = hn::GatherIndex(df, as_f(in.its), hn::Add(its_row, hn::Set(di, 2)));
      hn::Vec<decltype(df)> pick, u_x, u_y;
      if (sobol) {
        const auto at = hn::ShiftLeft<1>(
            hn::Add(hn::Mul(sample, hn::Set(di, int32_t(in.light_stride))), row));
        u_x = hn::GatherIndex(df, as_f(in.light_point), at);
        u_y = hn::GatherIndex(df, as_f(in.light_point), hn::Add(at, hn::Set(di, 1)));
        pick = u_x;
      } else {
        const auto path = hn::GatherIndex(di, as_i(in.owner), entry);
        hn::Vec<decltype(df)> words[4];
        LoadRowQuads(df, reinterpret_cast<const float*>(rng), sizeof(PathSampler) / sizeof(float),
                     path, {0}, words);
        const auto state = word64(words[0], words[1]), inc = word64(words[2], words[3]);
        const auto first = hn::PromoteTo(di64, hn::Mul(sample, hn::Set(di, 3)));
        const auto draw = [&](int64_t t) {
          const auto j = hn::Add(first, hn::Set(di64, t));
          const auto mul = hn::GatherIndex(d, jumps.mul(), j);
          const auto add = hn::GatherIndex(d, jumps.add(), j);
          return Pcg32Float(d, hn::Add(hn::Mul(state, mul), hn::Mul(inc, add)));
        };
        pick = draw(0), u_x = draw(1), u_y = draw(2);
      }
      const auto request = hn::Iota(du, rules.first_request + uint32_t(f));
      pick_emitters(active, request, entry, p_x, p_y, p_z, wo_x, wo_y, wo_z, pick, u_x, u_y,
                    sobol, out);
    }
  }
  const BsdfPickColumns& b = out->bsdf;
  size_t r = 0;
  for (; r < whole; r += lanes) {
    const auto entry = hn::LoadU(di, as_i(in.entries + r));
    const auto path = hn::GatherIndex(di, as_i(in.owner), entry);
    const auto its_row = hn::Mul(entry, hn::Set(di, kItsWords));
    const auto wo_row = hn::Mul(entry, hn::Set(di, 3));
    const auto wo_x = hn::GatherIndex(df, as_f(in.wo), wo_row);
    const auto wo_y = hn::GatherIndex(df, as_f(in.wo), hn::Add(wo_row, hn::Set(di, 1)));
    const auto wo_z = hn::GatherIndex(df, as_f(in.wo), hn::Add(wo_row, hn::Set(di, 2)));
    const auto path_row = hn::Mul(path, hn::Set(di, 3));
    const auto t_r = hn::GatherIndex(df, throughput, path_row);
    const auto t_g = hn::GatherIndex(df, throughput, hn::Add(path_row, hn::Set(di, 1)));
    const auto t_b = hn::GatherIndex(df, throughput, hn::Add(path_row, hn::Set(di, 2)));
    // The path's stream (PathSampler's words 0 and 1, one quad of 32-bit halves: state low,
    // high, increment low, high) and each draw's number (independent sampler).
    const auto sampler_row = hn::ShiftLeft<2>(hn::PromoteTo(di64, path));
    auto state = hn::Zero(d), inc = hn::Zero(d);
    if (!sobol) {
      hn::Vec<decltype(df)> words[4];
      LoadRowQuads(df, reinterpret_cast<const float*>(rng), sizeof(PathSampler) / sizeof(float),
                   path, {0}, words);
      state = word64(words[0], words[1]), inc = word64(words[2], words[3]);
    }
    const auto draw = [&](size_t j) {
      return Pcg32Float(d, Pcg32Advance(d, state, inc, jumps[j]));
    };
    // The shading point's p (for the emitter sample) and material: the row's quads at floats 0
    // and 16 (LoadRowQuads), or the material alone.
    constexpr size_t kQuadOfMaterial = 16, kMaterialColumn = 4 + kMaterialWord - kQuadOfMaterial;
    static_assert(kMaterialWord >= int32_t(kQuadOfMaterial) && kMaterialColumn < 8);
    const bool one_pick = picks && n_light == 1;
    hn::Vec<decltype(df)> its_q[8];
    if (one_pick) {
      LoadRowQuads(df, as_f(in.its), size_t(kItsWords), entry, {0, kQuadOfMaterial}, its_q);
    } else if (bsdf) {
      its_q[kMaterialColumn] = hn::BitCast(
          df, hn::GatherIndex(di, as_i(in.its), hn::Add(its_row, hn::Set(di, kMaterialWord))));
    }
    if (one_pick) {
      const auto request = hn::Iota(du, rules.first_request + uint32_t(r));
      if (sobol) {
        const auto at = hn::ShiftLeft<1>(hn::Iota(di, 0));
        const float* const point = as_f(in.light_point + r);
        const auto u_x = hn::GatherIndex(df, point, at);
        const auto u_y = hn::GatherIndex(df, point, hn::Add(at, hn::Set(di, 1)));
        pick_emitters(hn::FirstN(df, lanes), request, entry, its_q[0], its_q[1], its_q[2], wo_x,
                      wo_y, wo_z, u_x, u_x, u_y, true, out);
      } else {
        pick_emitters(hn::FirstN(df, lanes), request, entry, its_q[0], its_q[1], its_q[2], wo_x,
                      wo_y, wo_z, draw(0), draw(1), draw(2), false, out);
      }
    }
    if (rules.emitter_sample) {
      // The request's path and the throughput at the vertex.
      hn::StoreU(path, di,
                 reinterpret_cast<int32_t*>(out->nee_paths + rules.first_request / n_light + r));
      hn::ScatterIndex(t_r, df, nee_throughput, path_row);
      hn::ScatterIndex(t_g, df, nee_throughput, hn::Add(path_row, hn::Set(di, 1)));
      hn::ScatterIndex(t_b, df, nee_throughput, hn::Add(path_row, hn::Set(di, 2)));
      const auto finite = hn::And(hn::IsFinite(t_r), hn::And(hn::IsFinite(t_g), hn::IsFinite(t_b)));
      if (n_light == 1 && !hn::AllTrue(df, finite)) {
        const auto request = hn::Iota(du, rules.first_request + uint32_t(r));
        const auto nonfinite = hn::RebindMask(du, hn::Not(finite));
        out->nonfinite_rows +=
            hn::CompressBlendedStore(request, nonfinite, du, out->nonfinite + out->nonfinite_rows);
      }
    }
    auto alive = hn::FirstN(df, lanes);
    if (roulette) {
      const auto u = sobol ? hn::LoadU(df, in.roulette + r) : draw(roulette_draw);
      if (rules.roulette == Roulette::kNori) {
        // min(MaxComponent(throughput) * eta * eta, 0.99f) as std::max / std::min choose (the
        // first argument unless the second compares greater / less): the oracle's bits on NaN.
        const auto eta = hn::GatherIndex(df, in.eta, path);
        const auto max_gb = hn::IfThenElse(hn::Lt(t_g, t_b), t_b, t_g);
        const auto max_rgb = hn::IfThenElse(hn::Lt(t_r, max_gb), max_gb, t_r);
        const auto x = hn::Mul(hn::Mul(max_rgb, eta), eta);
        const auto cap = hn::Set(df, 0.99f);
        const auto q_continue = hn::IfThenElse(hn::Lt(cap, x), cap, x);
        alive = hn::Lt(u, q_continue);
        const auto scale = hn::Div(hn::Set(df, 1.0f), q_continue);
        hn::ScatterIndex(hn::IfThenElse(alive, hn::Mul(t_r, scale), t_r), df, throughput, path_row);
        hn::ScatterIndex(hn::IfThenElse(alive, hn::Mul(t_g, scale), t_g), df, throughput,
                         hn::Add(path_row, hn::Set(di, 1)));
        hn::ScatterIndex(hn::IfThenElse(alive, hn::Mul(t_b, scale), t_b), df, throughput,
                         hn::Add(path_row, hn::Set(di, 2)));
      } else {
        alive = hn::Not(hn::Ge(u, hn::Set(df, integrator::kWhittedContinuation)));
      }
    }
    if (bsdf) {
      hn::Vec<decltype(df)> lobe, dir_x, dir_y;
      if (sobol) {
        const auto at = hn::ShiftLeft<1>(hn::Iota(di, 0));
        const float* const direction = as_f(in.bsdf_direction + r);
        lobe = hn::LoadU(df, in.bsdf_lobe + r);
        dir_x = hn::GatherIndex(df, direction, at);
        dir_y = hn::GatherIndex(df, direction, hn::Add(at, hn::Set(di, 1)));
      } else {
        lobe = draw(bsdf_draw), dir_x = draw(bsdf_draw + 1), dir_y = draw(bsdf_draw + 2);
      }
      const auto alive_i = hn::RebindMask(di, alive);
      const size_t c = out->bsdf_rows;
      const bool all_alive = !roulette || hn::AllTrue(df, alive);
      const auto material = hn::BitCast(di, its_q[kMaterialColumn]);
      const auto index_bits = hn::Set(di, int32_t(0x0fffffff));  // MaterialRef's index
      StoreSelected(di, path, alive_i, all_alive, reinterpret_cast<int32_t*>(b.path + c));
      StoreSelected(di, entry, alive_i, all_alive, reinterpret_cast<int32_t*>(b.entry + c));
      StoreSelected(di, hn::And(material, index_bits), alive_i, all_alive,
                    reinterpret_cast<int32_t*>(b.material_index + c));
      StoreSelected(df, hn::Set(df, roulette_scale), alive, all_alive, b.roulette_scale + c);
      StoreSelected(df, wo_x, alive, all_alive, b.wo_x + c);
      StoreSelected(df, wo_y, alive, all_alive, b.wo_y + c);
      StoreSelected(df, wo_z, alive, all_alive, b.wo_z + c);
      StoreSelected(df, lobe, alive, all_alive, b.u_lobe + c);
      StoreSelected(df, dir_x, alive, all_alive, b.u_x + c);
      StoreSelected(df, dir_y, alive, all_alive, b.u_y + c);
      out->bsdf_rows = c + hn::CountTrue(df, alive);
    }
    // The streams, past the row's draws (or the roulette's, for the paths that end there).
    if (!sobol && end_draw > 0) {
      auto next = Pcg32Advance(d, state, inc, jumps[end_draw]);
      if (roulette) {
        const auto alive64 = hn::MaskFromVec(
            hn::BitCast(d, hn::PromoteTo(di64, hn::VecFromMask(di, hn::RebindMask(di, alive)))));
        next = hn::IfThenElse(alive64, next, Pcg32Advance(d, state, inc, jumps[bsdf_draw]));
      }
      hn::ScatterIndex(next, d, rng, sampler_row);
    }
  }
  // The rows after the last whole vector: the oracle row by row.
  if (r == n) return;
  VertexBatchRules rest_rules = rules;
  rest_rules.first_request = rules.first_request + uint32_t(r) * n_light;
  VertexBatchInputs rest = in;
  rest.entries = in.entries + r;
  if (sobol) {
    if (rest.light_point != nullptr) rest.light_point += r;
    if (rest.roulette != nullptr) rest.roulette += r;
    if (rest.bsdf_lobe != nullptr) rest.bsdf_lobe += r;
    if (rest.bsdf_direction != nullptr) rest.bsdf_direction += r;
  }
  ptlab::DecideVertices(scene, rest_rules, n - r, rest, paths, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_VERTEX_BATCH8_INL_H_
