// Per-target kernel of simd/continue8.h (re-included once per Highway target): the BSDF
// stage's finish at a batch of sampled vertices, one row per 32-bit lane.

#if defined(PTLAB_SIMD_CONTINUE8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_CONTINUE8_INL_H_
#undef PTLAB_SIMD_CONTINUE8_INL_H_
#else
#define PTLAB_SIMD_CONTINUE8_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include "engine/render/continue_batch.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

inline void ContinuePathsKernel(const ContinueBatchRules& rules, size_t n,
                                const ContinueBatchInputs& in, const ContinueBatchPaths& paths,
                                ContinueBatchOutputs* out) {
  const hn::CappedTag<float, 8> df;
  const hn::RebindToSigned<decltype(df)> di;
  const size_t lanes = hn::Lanes(df);
  // The rows read in place: a SurfaceInteraction starts with p, Vec3f and Color3f are three
  // floats.
  static_assert(offsetof(SurfaceInteraction, p) == 0 && sizeof(SurfaceInteraction) % 4 == 0);
  static_assert(sizeof(Vec3f) == 3 * sizeof(float) && sizeof(Color3f) == 3 * sizeof(float));
  constexpr int32_t kItsWords = int32_t(sizeof(SurfaceInteraction) / 4);
  const auto as_i = [](const auto* p) { return reinterpret_cast<const int32_t*>(p); };
  const float* const its = reinterpret_cast<const float*>(in.its);
  float* const throughput = reinterpret_cast<float*>(paths.throughput);
  float* const prev_p = reinterpret_cast<float*>(paths.prev_p);
  int32_t* const specular_flags = reinterpret_cast<int32_t*>(paths.specular);
  const auto one = hn::Set(di, 1), two = hn::Set(di, 2);
  const auto zero = hn::Zero(df);
  const auto specular = hn::Set(di, rules.specular ? 1 : 0);
  // The batch's columns, read through locals: the compiler cannot tell that the scatters
  // below leave `in` alone, and would load each pointer again per vector.
  const int32_t* const path_col = as_i(in.path);
  const int32_t* const entry_col = as_i(in.entry);
  const float* const weight_r = in.weight_r;
  const float* const weight_g = in.weight_g;
  const float* const weight_b = in.weight_b;
  const float* const roulette_scale = in.roulette_scale;
  const float* const pdf_col = in.pdf;
  const float* const eta_col = in.eta;
  const float* const wi_x = in.wi_x;
  const float* const wi_y = in.wi_y;
  const float* const wi_z = in.wi_z;
  float* const path_eta = paths.eta;
  float* const path_prev_pdf = paths.prev_pdf;
  int32_t* const out_entry = reinterpret_cast<int32_t*>(out->entry);
  int32_t* const out_owner = reinterpret_cast<int32_t*>(out->owner);
  float* const out_wi_x = out->wi_x;
  float* const out_wi_y = out->wi_y;
  float* const out_wi_z = out->wi_z;
  size_t m = out->rows;
  size_t r = 0;
  for (; r + lanes <= n; r += lanes) {
    const auto pdf = hn::LoadU(df, pdf_col + r);
    const auto sampled = hn::Lt(zero, pdf);  // pdf > 0: false on NaN
    if (hn::AllFalse(df, sampled)) continue;
    // Every gather first, then the scatters: the loads overlap instead of waiting on stores
    // that might alias them.
    const auto path = hn::LoadU(di, path_col + r);
    const auto path_row = hn::Mul(path, hn::Set(di, 3));
    const auto path_g = hn::Add(path_row, one), path_b = hn::Add(path_row, two);
    const auto entry = hn::LoadU(di, entry_col + r);
    const auto its_row = hn::Mul(entry, hn::Set(di, kItsWords));
    const auto t_r = hn::GatherIndex(df, throughput, path_row);
    const auto t_g = hn::GatherIndex(df, throughput, path_g);
    const auto t_b = hn::GatherIndex(df, throughput, path_b);
    const auto eta = hn::GatherIndex(df, path_eta, path);
    auto p_x = hn::GatherIndex(df, its, its_row);
    auto p_y = hn::GatherIndex(df, its, hn::Add(its_row, one));
    auto p_z = hn::GatherIndex(df, its, hn::Add(its_row, two));
    // throughput *= weight (weight · roulette_scale first, as Color3f * float does), eta *= eta.
    auto w_r = hn::LoadU(df, weight_r + r);
    auto w_g = hn::LoadU(df, weight_g + r);
    auto w_b = hn::LoadU(df, weight_b + r);
    if (roulette_scale != nullptr) {
      const auto scale = hn::LoadU(df, roulette_scale + r);
      w_r = hn::Mul(w_r, scale), w_g = hn::Mul(w_g, scale), w_b = hn::Mul(w_b, scale);
    }
    const auto n_r = hn::Mul(t_r, w_r), n_g = hn::Mul(t_g, w_g), n_b = hn::Mul(t_b, w_b);
    const auto n_eta = hn::Mul(eta, hn::LoadU(df, eta_col + r));
    // The paths that go on: sampled, and (cut_black) not black.
    auto goes_on = sampled;
    if (rules.cut_black) {
      const auto black = hn::And(hn::Eq(n_r, zero), hn::And(hn::Eq(n_g, zero), hn::Eq(n_b, zero)));
      goes_on = hn::AndNot(black, sampled);
    }
    const auto goes_on_i = hn::RebindMask(di, goes_on);
    auto flag = specular;
    auto prev_pdf = pdf;
    if (!hn::AllTrue(df, goes_on)) {
      // The paths that end here keep their state: their lanes write back what they gather.
      flag = hn::IfThenElse(goes_on_i, flag, hn::GatherIndex(di, specular_flags, path));
      prev_pdf = hn::IfThenElse(goes_on, prev_pdf, hn::GatherIndex(df, path_prev_pdf, path));
      p_x = hn::IfThenElse(goes_on, p_x, hn::GatherIndex(df, prev_p, path_row));
      p_y = hn::IfThenElse(goes_on, p_y, hn::GatherIndex(df, prev_p, path_g));
      p_z = hn::IfThenElse(goes_on, p_z, hn::GatherIndex(df, prev_p, path_b));
    }
    // Lanes without a sample write back the throughput and eta they gathered.
    hn::ScatterIndex(hn::IfThenElse(sampled, n_r, t_r), df, throughput, path_row);
    hn::ScatterIndex(hn::IfThenElse(sampled, n_g, t_g), df, throughput, path_g);
    hn::ScatterIndex(hn::IfThenElse(sampled, n_b, t_b), df, throughput, path_b);
    hn::ScatterIndex(hn::IfThenElse(sampled, n_eta, eta), df, path_eta, path);
    hn::ScatterIndex(flag, di, specular_flags, path);
    hn::ScatterIndex(prev_pdf, df, path_prev_pdf, path);
    hn::ScatterIndex(p_x, df, prev_p, path_row);
    hn::ScatterIndex(p_y, df, prev_p, path_g);
    hn::ScatterIndex(p_z, df, prev_p, path_b);
    // Their spawn rows and owners, in row order.
    hn::CompressBlendedStore(entry, goes_on_i, di, out_entry + m);
    hn::CompressBlendedStore(hn::LoadU(df, wi_x + r), goes_on, df, out_wi_x + m);
    hn::CompressBlendedStore(hn::LoadU(df, wi_y + r), goes_on, df, out_wi_y + m);
    hn::CompressBlendedStore(hn::LoadU(df, wi_z + r), goes_on, df, out_wi_z + m);
    m += hn::CompressBlendedStore(path, goes_on_i, di, out_owner + m);
  }
  out->rows = m;
  // The rows after the last whole vector: the oracle row by row.
  if (r == n) return;
  ContinueBatchInputs rest = in;
  rest.path += r, rest.entry += r, rest.weight_r += r, rest.weight_g += r, rest.weight_b += r;
  if (rest.roulette_scale != nullptr) rest.roulette_scale += r;
  rest.pdf += r, rest.eta += r, rest.wi_x += r, rest.wi_y += r, rest.wi_z += r;
  ptlab::ContinuePaths(rules, n - r, rest, paths, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_CONTINUE8_INL_H_
