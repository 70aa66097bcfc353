// Per-target kernel of simd/wavefront/vertices8.h (re-included once per Highway target): the
// sampling stage's decisions at a batch of path vertices, one row per 64-bit lane.

#if defined(PTLAB_SIMD_VERTEX_BATCH8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_VERTEX_BATCH8_INL_H_
#undef PTLAB_SIMD_VERTEX_BATCH8_INL_H_
#else
#define PTLAB_SIMD_VERTEX_BATCH8_INL_H_
#endif

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "engine/core/rng.h"
#include "engine/wavefront/vertices.h"
#include "engine/sampling/sampler.h"
#include "hwy/highway.h"
#include "simd/pcg8-inl.h"
#include "simd/store_selected-inl.h"
#include "simd/transpose4-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// Each draw's PCG32 state from the path's state at the vertex: draw j steps from the state j
// steps on (at most 3 for the emitter sample, 1 for the roulette, 3 for the BSDF, and the
// state after them).
inline constexpr std::array<Pcg32Jump, 8> kDrawJumps = {
    Pcg32JumpOf(0), Pcg32JumpOf(1), Pcg32JumpOf(2), Pcg32JumpOf(3),
    Pcg32JumpOf(4), Pcg32JumpOf(5), Pcg32JumpOf(6), Pcg32JumpOf(7)};

inline void DecideVerticesKernel(const Scene& scene, const VertexBatchRules& rules, size_t n,
                                 const VertexBatchInputs& in, const VertexBatchPaths& paths,
                                 VertexBatchOutputs* out) {
  const hn::CappedTag<uint64_t, 8> d;
  const hn::RebindToSigned<decltype(d)> di64;
  const hn::Rebind<uint32_t, decltype(d)> du;
  const hn::Rebind<int32_t, decltype(d)> di;
  const hn::Rebind<float, decltype(d)> df;
  const size_t lanes = hn::Lanes(d);
  // The rows read in place: PathSampler's first two words are its stream's state and
  // increment, a SurfaceInteraction starts with p and holds its material as 32 bits, Vec3f
  // and Color3f are three floats.
  static_assert(PathSampler::RowLayoutHolds());
  static_assert(offsetof(SurfaceInteraction, p) == 0 && sizeof(SurfaceInteraction) % 4 == 0 &&
                offsetof(SurfaceInteraction, material) % 4 == 0 && sizeof(MaterialRef) == 4 &&
                sizeof(EmitterRef) == 4);
  static_assert(sizeof(Vec3f) == 3 * sizeof(float) && sizeof(Color3f) == 3 * sizeof(float));
  constexpr int32_t kItsWords = int32_t(sizeof(SurfaceInteraction) / 4);
  constexpr int32_t kMaterialWord = int32_t(offsetof(SurfaceInteraction, material) / 4);
  const auto as_f = [](const auto* p) { return reinterpret_cast<const float*>(p); };
  const auto as_i = [](const auto* p) { return reinterpret_cast<const int32_t*>(p); };
  uint64_t* const rng = reinterpret_cast<uint64_t*>(paths.sampler);
  float* const throughput = reinterpret_cast<float*>(paths.throughput);
  float* const nee_throughput = reinterpret_cast<float*>(paths.nee_throughput);
  // The draws of a row, in the oracle's order: the emitter sample's pick and point, the
  // roulette's number, the BSDF's lobe and direction.
  const size_t roulette_draw = rules.emitter_sample ? 3 : 0;
  const size_t bsdf_draw = roulette_draw + (rules.roulette ? 1 : 0);
  // SelectEmitter: uniform, or the scan of the power CDF (VertexBatchFits).
  const EmitterSelectionTable& selection = scene.emitter_selection;
  const uint32_t emitters = uint32_t(scene.emitters.size());
  const bool uniform = scene.integrator.light_selection == LightSelection::kUniform;
  const auto last_emitter = hn::Set(di, int32_t(emitters) - 1);
  const auto index_bits = hn::Set(di, int32_t(0x0fffffff));  // EmitterRef / MaterialRef index
  const AreaPickColumns& a = out->area;
  const BsdfPickColumns& b = out->bsdf;
  // The requests of the whole vectors' rows: not traced (yet); the oracle sets the tail's.
  if (rules.emitter_sample)
    std::memset(out->request_traced + rules.first_request, 0, n - n % lanes);
  size_t r = 0;
  for (; r + lanes <= n; r += lanes) {
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
    // high, increment low, high) and each draw's number.
    const auto sampler_row = hn::ShiftLeft<2>(hn::PromoteTo(di64, path));
    hn::Vec<decltype(df)> words[4];
    LoadRowQuads(df, reinterpret_cast<const float*>(rng), sizeof(PathSampler) / sizeof(float), path,
                 {0}, words);
    const auto word64 = [&](hn::Vec<decltype(df)> lo, hn::Vec<decltype(df)> hi) {
      return hn::Or(hn::PromoteTo(d, hn::BitCast(du, lo)),
                    hn::ShiftLeft<32>(hn::PromoteTo(d, hn::BitCast(du, hi))));
    };
    const auto state = word64(words[0], words[1]), inc = word64(words[2], words[3]);
    const auto draw = [&](size_t j) {
      return Pcg32Float(d, Pcg32Advance(d, state, inc, kDrawJumps[j]));
    };
    const auto request = hn::Iota(du, rules.first_request + uint32_t(r));
    // The shading point's p (for the emitter sample) and material: the row's quads at floats 0
    // and 16 (LoadRowQuads), or the material alone.
    constexpr size_t kQuadOfMaterial = 16, kMaterialColumn = 4 + kMaterialWord - kQuadOfMaterial;
    static_assert(kMaterialWord >= int32_t(kQuadOfMaterial) && kMaterialColumn < 8);
    hn::Vec<decltype(df)> its_q[8];
    if (rules.emitter_sample) {
      LoadRowQuads(df, as_f(in.its), size_t(kItsWords), entry, {0, kQuadOfMaterial}, its_q);
    } else {
      its_q[kMaterialColumn] = hn::BitCast(
          df, hn::GatherIndex(di, as_i(in.its), hn::Add(its_row, hn::Set(di, kMaterialWord))));
    }
    if (rules.emitter_sample) {
      const auto pick = draw(0), u_x = draw(1), u_y = draw(2);
      hn::Vec<decltype(di)> k;
      hn::Vec<decltype(df)> pick_pmf;
      if (uniform) {
        // size_t(u * n), at most n - 1; 1/n.
        k = hn::Min(hn::ConvertTo(di, hn::Mul(pick, hn::Set(df, float(emitters)))), last_emitter);
        pick_pmf = hn::Set(df, 1.0f / float(emitters));
      } else {
        // GuidedUpperBound's scan: the CDF entries not above u, counted.
        auto count = hn::Zero(di);
        for (uint32_t e = 0; e < emitters; ++e) {
          const auto below = hn::Not(hn::Lt(pick, hn::Set(df, selection.cdf[e])));
          count = hn::Sub(count, hn::VecFromMask(di, hn::RebindMask(di, below)));
        }
        k = hn::Min(count, last_emitter);
        pick_pmf = hn::GatherIndex(df, selection.pmf.data(), k);
      }
      const auto light = hn::And(hn::GatherIndex(di, as_i(scene.emitters.data()), k), index_bits);
      const auto picked = hn::Lt(hn::Zero(df), pick_pmf);
      const auto picked_i = hn::RebindMask(di, picked);
      const auto picked_u = hn::RebindMask(du, picked);
      const size_t c = out->area_rows;
      const bool all_picked = hn::AllTrue(df, picked);
      StoreSelected(du, request, picked_u, all_picked, a.request + c);
      StoreSelected(di, entry, picked_i, all_picked, reinterpret_cast<int32_t*>(a.entry + c));
      StoreSelected(di, light, picked_i, all_picked, reinterpret_cast<int32_t*>(a.light + c));
      StoreSelected(df, pick_pmf, picked, all_picked, a.pick_pmf + c);
      StoreSelected(df, its_q[0], picked, all_picked, a.ref_x + c);
      StoreSelected(df, its_q[1], picked, all_picked, a.ref_y + c);
      StoreSelected(df, its_q[2], picked, all_picked, a.ref_z + c);
      StoreSelected(df, wo_x, picked, all_picked, a.wo_x + c);
      StoreSelected(df, wo_y, picked, all_picked, a.wo_y + c);
      StoreSelected(df, wo_z, picked, all_picked, a.wo_z + c);
      StoreSelected(df, u_x, picked, all_picked, a.u_x + c);
      StoreSelected(df, u_y, picked, all_picked, a.u_y + c);
      out->area_rows = c + hn::CountTrue(df, picked);
      // The request's path and the throughput at the vertex.
      hn::StoreU(path, di, reinterpret_cast<int32_t*>(out->nee_paths + rules.first_request + r));
      hn::ScatterIndex(t_r, df, nee_throughput, path_row);
      hn::ScatterIndex(t_g, df, nee_throughput, hn::Add(path_row, hn::Set(di, 1)));
      hn::ScatterIndex(t_b, df, nee_throughput, hn::Add(path_row, hn::Set(di, 2)));
      const auto finite = hn::And(hn::IsFinite(t_r), hn::And(hn::IsFinite(t_g), hn::IsFinite(t_b)));
      if (!hn::AllTrue(df, finite)) {
        const auto nonfinite = hn::RebindMask(du, hn::Not(finite));
        out->nonfinite_rows +=
            hn::CompressBlendedStore(request, nonfinite, du, out->nonfinite + out->nonfinite_rows);
      }
    }
    auto alive = hn::FirstN(df, lanes);
    if (rules.roulette) {
      // min(MaxComponent(throughput) * eta * eta, 0.99f) as std::max / std::min choose (the
      // first argument unless the second compares greater / less): the oracle's bits on NaN.
      const auto eta = hn::GatherIndex(df, in.eta, path);
      const auto max_gb = hn::IfThenElse(hn::Lt(t_g, t_b), t_b, t_g);
      const auto max_rgb = hn::IfThenElse(hn::Lt(t_r, max_gb), max_gb, t_r);
      const auto x = hn::Mul(hn::Mul(max_rgb, eta), eta);
      const auto cap = hn::Set(df, 0.99f);
      const auto q_continue = hn::IfThenElse(hn::Lt(cap, x), cap, x);
      alive = hn::Lt(draw(roulette_draw), q_continue);
      const auto scale = hn::Div(hn::Set(df, 1.0f), q_continue);
      hn::ScatterIndex(hn::IfThenElse(alive, hn::Mul(t_r, scale), t_r), df, throughput, path_row);
      hn::ScatterIndex(hn::IfThenElse(alive, hn::Mul(t_g, scale), t_g), df, throughput,
                       hn::Add(path_row, hn::Set(di, 1)));
      hn::ScatterIndex(hn::IfThenElse(alive, hn::Mul(t_b, scale), t_b), df, throughput,
                       hn::Add(path_row, hn::Set(di, 2)));
    }
    const auto lobe = draw(bsdf_draw), dir_x = draw(bsdf_draw + 1), dir_y = draw(bsdf_draw + 2);
    const auto alive_i = hn::RebindMask(di, alive);
    const size_t c = out->bsdf_rows;
    const bool all_alive = !rules.roulette || hn::AllTrue(df, alive);
    const auto material = hn::BitCast(di, its_q[kMaterialColumn]);
    StoreSelected(di, path, alive_i, all_alive, reinterpret_cast<int32_t*>(b.path + c));
    StoreSelected(di, entry, alive_i, all_alive, reinterpret_cast<int32_t*>(b.entry + c));
    StoreSelected(di, hn::And(material, index_bits), alive_i, all_alive,
                  reinterpret_cast<int32_t*>(b.material_index + c));
    StoreSelected(df, hn::Set(df, 1.0f), alive, all_alive, b.roulette_scale + c);
    StoreSelected(df, wo_x, alive, all_alive, b.wo_x + c);
    StoreSelected(df, wo_y, alive, all_alive, b.wo_y + c);
    StoreSelected(df, wo_z, alive, all_alive, b.wo_z + c);
    StoreSelected(df, lobe, alive, all_alive, b.u_lobe + c);
    StoreSelected(df, dir_x, alive, all_alive, b.u_x + c);
    StoreSelected(df, dir_y, alive, all_alive, b.u_y + c);
    out->bsdf_rows = c + hn::CountTrue(df, alive);
    // The streams, past the BSDF's draws (or the roulette's, for the paths that end there).
    auto next = Pcg32Advance(d, state, inc, kDrawJumps[bsdf_draw + 3]);
    if (rules.roulette) {
      const auto alive64 =
          hn::MaskFromVec(hn::BitCast(d, hn::PromoteTo(di64, hn::VecFromMask(di, alive_i))));
      next = hn::IfThenElse(alive64, next, Pcg32Advance(d, state, inc, kDrawJumps[bsdf_draw]));
    }
    hn::ScatterIndex(next, d, rng, sampler_row);
  }
  // The rows after the last whole vector: the oracle row by row.
  if (r == n) return;
  VertexBatchRules rest_rules = rules;
  rest_rules.first_request = rules.first_request + uint32_t(r);
  VertexBatchInputs rest = in;
  rest.entries = in.entries + r;
  ptlab::DecideVertices(scene, rest_rules, n - r, rest, paths, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_VERTEX_BATCH8_INL_H_
