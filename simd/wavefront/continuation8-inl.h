// Per-target kernel of simd/wavefront/continuation8.h (re-included once per Highway target): the BSDF
// stage's finish at a batch of sampled vertices, one row per 32-bit lane.

#if defined(PTLAB_SIMD_CONTINUE8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_CONTINUE8_INL_H_
#undef PTLAB_SIMD_CONTINUE8_INL_H_
#else
#define PTLAB_SIMD_CONTINUE8_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include "engine/wavefront/continuation.h"
#include "hwy/highway.h"
#include "simd/store_selected-inl.h"
#include "simd/transpose4-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// 256-bit targets (AVX2, AVX3): the 3-float rows (Color3f, Vec3f) are written lane by lane as
// one 3-lane masked store each, after a transpose, instead of three scatters of one float a
// lane: 8 stores instead of 24, and stores are what this kernel is bound by.
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX2
#define PTLAB_CONTINUE8_ROW_STORES 1
// Row j of (x, y, z) to base + row[j] (3 floats; the row's 4th float is not written), j < 8:
// DF is CappedTag<float, 8>, whose vectors are 256 bits on these targets.
template <class DF, class V>
HWY_INLINE void StoreRows3(DF df, V x, V y, V z, const int32_t* row, float* base) {
  const hn::Half<DF> dh;
  const auto mask = hn::FirstN(dh, 3);
  // x0 y0 z0 z0 | x4 y4 z4 z4 and so on: rows j and j + 4 in the two blocks.
  V r04, r15, r26, r37;
  TransposeQuads(df, x, y, z, z, &r04, &r15, &r26, &r37);
  hn::BlendedStore(hn::LowerHalf(dh, r04), mask, dh, base + row[0]);
  hn::BlendedStore(hn::LowerHalf(dh, r15), mask, dh, base + row[1]);
  hn::BlendedStore(hn::LowerHalf(dh, r26), mask, dh, base + row[2]);
  hn::BlendedStore(hn::LowerHalf(dh, r37), mask, dh, base + row[3]);
  hn::BlendedStore(hn::UpperHalf(dh, r04), mask, dh, base + row[4]);
  hn::BlendedStore(hn::UpperHalf(dh, r15), mask, dh, base + row[5]);
  hn::BlendedStore(hn::UpperHalf(dh, r26), mask, dh, base + row[6]);
  hn::BlendedStore(hn::UpperHalf(dh, r37), mask, dh, base + row[7]);
}
#else
#define PTLAB_CONTINUE8_ROW_STORES 0
#endif

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
    if (in.delta != nullptr)  // matB: the row's own lobe (ContinueBatchInputs::delta)
      flag = hn::IfThenElseZero(hn::RebindMask(di, hn::Ne(hn::LoadU(df, in.delta + r), zero)),
                                one);
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
#if PTLAB_CONTINUE8_ROW_STORES
    HWY_ALIGN int32_t rows[8];
    hn::Store(path_row, di, rows);
    StoreRows3(df, hn::IfThenElse(sampled, n_r, t_r), hn::IfThenElse(sampled, n_g, t_g),
               hn::IfThenElse(sampled, n_b, t_b), rows, throughput);
#else
    hn::ScatterIndex(hn::IfThenElse(sampled, n_r, t_r), df, throughput, path_row);
    hn::ScatterIndex(hn::IfThenElse(sampled, n_g, t_g), df, throughput, path_g);
    hn::ScatterIndex(hn::IfThenElse(sampled, n_b, t_b), df, throughput, path_b);
#endif
    hn::ScatterIndex(hn::IfThenElse(sampled, n_eta, eta), df, path_eta, path);
    hn::ScatterIndex(flag, di, specular_flags, path);
    hn::ScatterIndex(prev_pdf, df, path_prev_pdf, path);
#if PTLAB_CONTINUE8_ROW_STORES
    StoreRows3(df, p_x, p_y, p_z, rows, prev_p);
#else
    hn::ScatterIndex(p_x, df, prev_p, path_row);
    hn::ScatterIndex(p_y, df, prev_p, path_g);
    hn::ScatterIndex(p_z, df, prev_p, path_b);
#endif
    // Their spawn rows and owners, in row order.
    const bool all = hn::AllTrue(df, goes_on);
    StoreSelected(di, entry, goes_on_i, all, out_entry + m);
    StoreSelected(df, hn::LoadU(df, wi_x + r), goes_on, all, out_wi_x + m);
    StoreSelected(df, hn::LoadU(df, wi_y + r), goes_on, all, out_wi_y + m);
    StoreSelected(df, hn::LoadU(df, wi_z + r), goes_on, all, out_wi_z + m);
    StoreSelected(di, path, goes_on_i, all, out_owner + m);
    m += hn::CountTrue(df, goes_on);
  }
  out->rows = m;
  // The rows after the last whole vector: the oracle row by row.
  if (r == n) return;
  ContinueBatchInputs rest = in;
  rest.path += r, rest.entry += r, rest.weight_r += r, rest.weight_g += r, rest.weight_b += r;
  if (rest.roulette_scale != nullptr) rest.roulette_scale += r;
  rest.pdf += r, rest.eta += r, rest.wi_x += r, rest.wi_y += r, rest.wi_z += r;
  if (rest.delta != nullptr) rest.delta += r;
  ptlab::ContinuePaths(rules, n - r, rest, paths, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#undef PTLAB_CONTINUE8_ROW_STORES  // defined again for the next target
#endif  // PTLAB_SIMD_CONTINUE8_INL_H_
