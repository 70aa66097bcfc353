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
  size_t r = 0;
  for (; r + lanes <= n; r += lanes) {
    const auto pdf = hn::LoadU(df, in.pdf + r);
    const auto sampled = hn::Lt(zero, pdf);  // pdf > 0: false on NaN
    if (hn::AllFalse(df, sampled)) continue;
    const auto path = hn::LoadU(di, as_i(in.path + r));
    const auto path_row = hn::Mul(path, hn::Set(di, 3));
    const auto path_g = hn::Add(path_row, one), path_b = hn::Add(path_row, two);
    // throughput *= weight (weight · roulette_scale first, as Color3f * float does), eta *= eta.
    auto w_r = hn::LoadU(df, in.weight_r + r);
    auto w_g = hn::LoadU(df, in.weight_g + r);
    auto w_b = hn::LoadU(df, in.weight_b + r);
    if (in.roulette_scale != nullptr) {
      const auto scale = hn::LoadU(df, in.roulette_scale + r);
      w_r = hn::Mul(w_r, scale), w_g = hn::Mul(w_g, scale), w_b = hn::Mul(w_b, scale);
    }
    const auto t_r = hn::GatherIndex(df, throughput, path_row);
    const auto t_g = hn::GatherIndex(df, throughput, path_g);
    const auto t_b = hn::GatherIndex(df, throughput, path_b);
    const auto n_r = hn::Mul(t_r, w_r), n_g = hn::Mul(t_g, w_g), n_b = hn::Mul(t_b, w_b);
    const auto eta = hn::GatherIndex(df, paths.eta, path);
    // Lanes without a sample write back what they gathered.
    hn::ScatterIndex(hn::IfThenElse(sampled, n_r, t_r), df, throughput, path_row);
    hn::ScatterIndex(hn::IfThenElse(sampled, n_g, t_g), df, throughput, path_g);
    hn::ScatterIndex(hn::IfThenElse(sampled, n_b, t_b), df, throughput, path_b);
    hn::ScatterIndex(hn::IfThenElse(sampled, hn::Mul(eta, hn::LoadU(df, in.eta + r)), eta), df,
                     paths.eta, path);
    // The paths that go on: sampled, and (cut_black) not black.
    auto goes_on = sampled;
    if (rules.cut_black) {
      const auto black = hn::And(hn::Eq(n_r, zero), hn::And(hn::Eq(n_g, zero), hn::Eq(n_b, zero)));
      goes_on = hn::AndNot(black, sampled);
    }
    const auto goes_on_i = hn::RebindMask(di, goes_on);
    const auto entry = hn::LoadU(di, as_i(in.entry + r));
    const auto its_row = hn::Mul(entry, hn::Set(di, kItsWords));
    auto p_x = hn::GatherIndex(df, its, its_row);
    auto p_y = hn::GatherIndex(df, its, hn::Add(its_row, one));
    auto p_z = hn::GatherIndex(df, its, hn::Add(its_row, two));
    auto flag = specular;
    auto prev_pdf = pdf;
    if (!hn::AllTrue(df, goes_on)) {
      // The paths that end here keep their state: their lanes write back what they gather.
      flag = hn::IfThenElse(goes_on_i, flag, hn::GatherIndex(di, specular_flags, path));
      prev_pdf = hn::IfThenElse(goes_on, prev_pdf, hn::GatherIndex(df, paths.prev_pdf, path));
      p_x = hn::IfThenElse(goes_on, p_x, hn::GatherIndex(df, prev_p, path_row));
      p_y = hn::IfThenElse(goes_on, p_y, hn::GatherIndex(df, prev_p, path_g));
      p_z = hn::IfThenElse(goes_on, p_z, hn::GatherIndex(df, prev_p, path_b));
    }
    hn::ScatterIndex(flag, di, specular_flags, path);
    hn::ScatterIndex(prev_pdf, df, paths.prev_pdf, path);
    hn::ScatterIndex(p_x, df, prev_p, path_row);
    hn::ScatterIndex(p_y, df, prev_p, path_g);
    hn::ScatterIndex(p_z, df, prev_p, path_b);
    // Their spawn rows and owners, in row order.
    const size_t m = out->rows;
    hn::CompressBlendedStore(entry, goes_on_i, di, reinterpret_cast<int32_t*>(out->entry + m));
    hn::CompressBlendedStore(hn::LoadU(df, in.wi_x + r), goes_on, df, out->wi_x + m);
    hn::CompressBlendedStore(hn::LoadU(df, in.wi_y + r), goes_on, df, out->wi_y + m);
    hn::CompressBlendedStore(hn::LoadU(df, in.wi_z + r), goes_on, df, out->wi_z + m);
    out->rows = m + hn::CompressBlendedStore(path, goes_on_i, di,
                                             reinterpret_cast<int32_t*>(out->owner + m));
  }
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
