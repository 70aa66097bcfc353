// Per-target SIMD twin of engine/bsdf/blend.h (Mitsuba `blendbsdf`), included by bsdf8-inl.h.
// Oracle: BlendEval / BlendPdf / BlendSample. The children run on their own 8-wide kernels
// (the rows regrouped by child tag, as ShadeHitsWith groups hits); the blend itself only picks
// a child per row and mixes the children's numbers, in plain loops in the oracle's order. So
// the contract is the children's: bit-identical where theirs is, else theirs carried through
// the mixture (a few ulp; tests/simd/wavefront/blend8_test.cpp).

#if defined(PTLAB_SIMD_BLEND8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_BLEND8_INL_H_
#undef PTLAB_SIMD_BLEND8_INL_H_
#else
#define PTLAB_SIMD_BLEND8_INL_H_
#endif

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "engine/bsdf/blend.h"
#include "engine/wavefront/bsdf.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

inline void ShadeBatchKernel(const MaterialTables& m, MaterialTag tag,
                             const uint32_t* material_index, size_t n, const ShadeInputs& in,
                             const ShadeOutputs& out);

/// The children's f and pdf at (wo, w) for refs[0, n): ShadeHitsWith over this target's
/// kernels, evaluation only.
inline void BlendChildrenEval(const MaterialTables& m, const MaterialRef* refs, size_t n,
                              DirectionArrays wo, DirectionArrays w, float* fr, float* fg,
                              float* fb, float* pdf, ShadeScratch* scratch,
                              const ShadeInputs::Textures& texture) {
  ShadeInputs in;
  in.wo = wo, in.wl = w;
  in.texture = texture;  // mask: textured children
  ShadeOutputs out;
  out.f = {fr, fg, fb};
  out.pdf_l = pdf;
  ShadeHitsWith([](const MaterialTables& mt, MaterialTag t, const uint32_t* index, size_t count,
                   const ShadeInputs& bin,
                   const ShadeOutputs& bout) { ShadeBatchKernel(mt, t, index, count, bin, bout); },
                m, refs, n, in, out, scratch);
}

/// mask: TexturedUnitFloat of rows material_index[0, n) into out[0, n): the constant column,
/// TexturedFloat8 for the textured rows, clipped to [0, 1] as the oracle clips (NaN → 1). A
/// blend's weight, a mask's opacity.
inline void TexturedUnitFloatRows8(const AlignedVector<float>& constant,
                                   const AlignedVector<uint32_t>& texture,
                                   const ShadeInputs::Textures& tex, const uint32_t* material_index,
                                   size_t n, float* out) {
  const bool textured = tex.textures != nullptr && !texture.empty();
  ShadeIo io;
  io.index = material_index;
  if (textured) io.entry = tex.entry;
  io.out[kFR] = out;
  ForEachBlock(io, n, [&constant, &texture, &tex, textured](const ShadeIo& b, size_t i) HWY_ATTR {
    const D8 d;
    V8 v = Gather(d, constant, b.index, i);
    if (textured) TexturedFloat8(d, tex, texture, b, i, &v);
    const V8 one = hn::Set(d, 1.0f);
    Store(d, hn::IfThenElse(hn::Lt(v, one), hn::IfThenElseZero(hn::Gt(v, hn::Zero(d)), v), one),
          b.out[kFR], i);
  });
}

/// Calls vec(i) for i = 0, N, 2N, … while a whole vector of N = Lanes(D8) rows fits, then
/// scalar(i) for each row of the rest (the two compute the same IEEE operations).
template <class Vec, class Scalar>
HWY_INLINE void ForEachRowVector(size_t n, const Vec& vec, const Scalar& scalar) {
  const size_t lanes = hn::Lanes(D8());
  size_t i = 0;
  for (; i + lanes <= n; i += lanes) vec(i);
  for (; i < n; ++i) scalar(i);
}

/// The mixture (1 − w) f₀ + w f₁ and (1 − w) p₀ + w p₁ of BlendEvalPdf, in its order.
inline void BlendMix(size_t n, const float* weight, float* const f0[4], float* const f1[4],
                     float* fr, float* fg, float* fb, float* pdf) {
  ForEachRowVector(
      n,
      [&](size_t i) HWY_ATTR {
        const D8 d;
        const V8 wt = Load(d, weight, i), wf = hn::Sub(hn::Set(d, 1.0f), wt);
        const auto mixed = [&](int c) HWY_ATTR {
          return hn::Add(hn::Mul(Load(d, f0[c], i), wf), hn::Mul(Load(d, f1[c], i), wt));
        };
        Store(d, mixed(0), fr, i), Store(d, mixed(1), fg, i), Store(d, mixed(2), fb, i);
        Store(d, hn::Add(hn::Mul(wf, Load(d, f0[3], i)), hn::Mul(wt, Load(d, f1[3], i))), pdf, i);
      },
      [&](size_t i) {
        const float wt = weight[i], wf = 1.0f - wt;
        fr[i] = f0[0][i] * wf + f1[0][i] * wt;
        fg[i] = f0[1][i] * wf + f1[1][i] * wt;
        fb[i] = f0[2][i] * wf + f1[2][i] * wt;
        pdf[i] = wf * f0[3][i] + wt * f1[3][i];
      });
}

/// BlendSample's ending for rows whose picked child sampled (out.pdf > 0): a delta sample's pdf
/// times the pick's probability, a non-delta sample the mixture's pdf `mixed[3]` and weight
/// mixed[0..2] |wi.z| / pdf; a row that fails gets no sample. Rows without a sample are kept.
inline void BlendFinishSamples(size_t n, const float* weight, const float* is_second,
                               const float* const mixed[4], float* delta, const ShadeOutputs& out) {
  ForEachRowVector(
      n,
      [&](size_t i) HWY_ATTR {
        const D8 d;
        const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
        const V8 child_pdf = Load(d, out.pdf, i);
        const M8 sampled = hn::Gt(child_pdf, zero);
        if (hn::AllFalse(d, sampled)) return;
        const M8 is_delta = hn::Ne(Load(d, delta, i), zero);
        const V8 wt = Load(d, weight, i);
        const V8 pick = hn::IfThenElse(hn::Ne(Load(d, is_second, i), zero), wt, hn::Sub(one, wt));
        const V8 delta_pdf = hn::Mul(child_pdf, pick);
        const V8 pdf = Load(d, mixed[3], i);
        const V8 s = hn::Div(hn::Abs(Load(d, out.wi.z, i)), pdf);
        const V8 wr = hn::Mul(Load(d, mixed[0], i), s), wg = hn::Mul(Load(d, mixed[1], i), s),
                 wb = hn::Mul(Load(d, mixed[2], i), s);
        const M8 ok_mixed =
            hn::And(hn::And(hn::Gt(pdf, zero), hn::IsFinite(pdf)), AllFinite3(d, wr, wg, wb));
        const M8 ok =
            hn::Or(hn::And(is_delta, hn::Gt(delta_pdf, zero)), hn::AndNot(is_delta, ok_mixed));
        const M8 keep = hn::And(sampled, ok), drop = hn::AndNot(ok, sampled);
        const M8 mixture = hn::AndNot(is_delta, keep);
        const auto put = [&](M8 m, V8 v, float* col)
                             HWY_ATTR { Store(d, hn::IfThenElse(m, v, Load(d, col, i)), col, i); };
        put(sampled, hn::IfThenElseZero(keep, hn::IfThenElse(is_delta, delta_pdf, pdf)), out.pdf);
        put(mixture, wr, out.weight.r), put(mixture, wg, out.weight.g);
        put(mixture, wb, out.weight.b);
        put(drop, zero, out.weight.r), put(drop, zero, out.weight.g), put(drop, zero, out.weight.b);
        put(drop, zero, out.wi.x), put(drop, zero, out.wi.y), put(drop, zero, out.wi.z);
        put(drop, one, out.eta), put(drop, zero, delta);
      },
      [&](size_t i) {
        if (!(out.pdf[i] > 0)) return;  // the child had no sample
        bool ok;
        if (delta[i] != 0) {
          out.pdf[i] *= is_second[i] != 0 ? weight[i] : 1.0f - weight[i];
          ok = out.pdf[i] > 0;
        } else {
          const float pdf = mixed[3][i];
          const float s = std::fabs(out.wi.z[i]) / pdf;
          const float wr = mixed[0][i] * s, wg = mixed[1][i] * s, wb = mixed[2][i] * s;
          ok = pdf > 0 && std::isfinite(pdf) && std::isfinite(wr) && std::isfinite(wg) &&
               std::isfinite(wb);
          if (ok)
            out.pdf[i] = pdf, out.weight.r[i] = wr, out.weight.g[i] = wg, out.weight.b[i] = wb;
        }
        if (!ok) {
          out.wi.x[i] = out.wi.y[i] = out.wi.z[i] = 0.0f;
          out.weight.r[i] = out.weight.g[i] = out.weight.b[i] = out.pdf[i] = 0.0f;
          out.eta[i] = 1.0f;
          delta[i] = 0.0f;
        }
      });
}

/// col[i] = from[i] for the rows with pick[i] != 0.
inline void BlendTakeRows(size_t n, const float* pick, const float* from, float* col) {
  ForEachRowVector(
      n,
      [&](size_t i) HWY_ATTR {
        const D8 d;
        const M8 m = hn::Ne(Load(d, pick, i), hn::Zero(d));
        Store(d, hn::IfThenElse(m, Load(d, from, i), Load(d, col, i)), col, i);
      },
      [&](size_t i) {
        if (pick[i] != 0) col[i] = from[i];
      });
}

/// BlendEval / BlendPdf / BlendSample for rows of BlendTable.
///
/// When every row's first child has one tag and every second child one tag (a scene's blend
/// rows usually share their children's kinds), the children's kernels run on the rows as they
/// are, each on its child's index column: no regrouping by tag, no copies. Sampling then runs
/// each picked child's kernel over every row (the rows that picked the other child are computed
/// and dropped) rather than on a regrouped copy of its rows; each row's numbers are the ones its
/// child's kernel gives it either way (a kernel's lanes depend on their own inputs only), so the
/// results are those of the regrouping path, which other batches take
/// (Shade8.BlendOfUniformChildKindsEqualsRowsInAMixedBatch checks it bit for bit).
inline void ShadeBlendRows(const MaterialTables& m, const uint32_t* material_index, size_t n,
                           const ShadeInputs& in, const ShadeOutputs& out) {
  const BlendTable& t = m.blend;
  const bool eval = in.wl.x != nullptr, sample = in.u_lobe != nullptr;
  // Working storage reused across calls, one set per nesting level (a blend child of a blend
  // runs while its parent's arrays are in use).
  struct Storage {
    ShadeScratch scratch;
    std::vector<MaterialRef> first, second, picked;
    std::vector<uint32_t> index0, index1;
    std::vector<float> weight, c, u_child, is_second, delta, mixed, other;
  };
  thread_local std::vector<std::unique_ptr<Storage>> pool;
  thread_local size_t depth = 0;
  if (pool.size() <= depth) pool.push_back(std::make_unique<Storage>());
  Storage& st = *pool[depth];
  struct DepthGuard {
    size_t& d;
    explicit DepthGuard(size_t& v) : d(v) { ++d; }
    ~DepthGuard() { --d; }
  } guard(depth);
  ShadeScratch& scratch = st.scratch;
  std::vector<MaterialRef>& first = st.first;
  std::vector<MaterialRef>& second = st.second;
  std::vector<float>& weight = st.weight;
  first.resize(n), second.resize(n), weight.resize(n);
  st.index0.resize(n), st.index1.resize(n);
  // The children's refs and table rows; one tag each over the batch (valid tags only) takes
  // the direct path.
  const uint32_t tag0 = n > 0 ? t.First(material_index[0]).bits >> 28 : 0;
  const uint32_t tag1 = n > 0 ? t.Second(material_index[0]).bits >> 28 : 0;
  uint32_t other_tags = 0;
  ForEachRowVector(
      n,
      [&](size_t i) HWY_ATTR {
        const hn::RebindToUnsigned<D8> du;
        const hn::RebindToSigned<D8> di;
        const auto row = hn::LoadU(di, reinterpret_cast<const int32_t*>(material_index + i));
        const auto a = hn::BitCast(
            du, hn::GatherIndex(di, reinterpret_cast<const int32_t*>(t.first.data()), row));
        const auto b = hn::BitCast(
            du, hn::GatherIndex(di, reinterpret_cast<const int32_t*>(t.second.data()), row));
        hn::StoreU(a, du, reinterpret_cast<uint32_t*>(first.data() + i));
        hn::StoreU(b, du, reinterpret_cast<uint32_t*>(second.data() + i));
        const auto low = hn::Set(du, 0x0fffffffu);
        hn::StoreU(hn::And(a, low), du, st.index0.data() + i);
        hn::StoreU(hn::And(b, low), du, st.index1.data() + i);
        const auto differ = hn::Or(hn::Xor(hn::ShiftRight<28>(a), hn::Set(du, tag0)),
                                   hn::Xor(hn::ShiftRight<28>(b), hn::Set(du, tag1)));
        if (!hn::AllTrue(du, hn::Eq(differ, hn::Zero(du)))) other_tags = 1;
      },
      [&](size_t i) {
        const uint32_t row = material_index[i];
        first[i] = t.First(row), second[i] = t.Second(row);
        st.index0[i] = first[i].index(), st.index1[i] = second[i].index();
        other_tags |= ((first[i].bits >> 28) ^ tag0) | ((second[i].bits >> 28) ^ tag1);
      });
  const bool uniform = n > 0 && other_tags == 0 && tag0 < uint32_t(kMaterialTagCount) &&
                       tag1 < uint32_t(kMaterialTagCount);
  const MaterialTag kind0 = static_cast<MaterialTag>(tag0), kind1 = static_cast<MaterialTag>(tag1);
  TexturedUnitFloatRows8(t.weight, t.weight_texture, in.texture, material_index, n,
                         weight.data());  // mask: BlendWeight
  // Columns: f rgb and pdf of the first child, then of the second.
  std::vector<float>& c = st.c;
  c.resize(8 * n);
  float* const f0[4] = {c.data(), c.data() + n, c.data() + 2 * n, c.data() + 3 * n};
  float* const f1[4] = {c.data() + 4 * n, c.data() + 5 * n, c.data() + 6 * n, c.data() + 7 * n};
  // f and pdf of one child of every row at (wo, w).
  const auto children_eval = [&](bool second_child, DirectionArrays w, float* const f[4]) {
    if (!uniform) {
      return BlendChildrenEval(m, (second_child ? second : first).data(), n, in.wo, w, f[0], f[1],
                               f[2], f[3], &scratch, in.texture);
    }
    ShadeInputs child_in;
    child_in.wo = in.wo, child_in.wl = w;
    child_in.texture = in.texture;  // mask: textured children
    ShadeOutputs child_out;
    child_out.f = {f[0], f[1], f[2]};
    child_out.pdf_l = f[3];
    ShadeBatchKernel(m, second_child ? kind1 : kind0, (second_child ? st.index1 : st.index0).data(),
                     n, child_in, child_out);
  };
  const auto mix = [&](DirectionArrays w, float* fr, float* fg, float* fb, float* pdf) {
    children_eval(false, w, f0), children_eval(true, w, f1);
    BlendMix(n, weight.data(), f0, f1, fr, fg, fb, pdf);
  };
  // Uniform children that evaluate and sample: each child's evaluation at wl runs in the same
  // kernel call as its sampling (four child passes instead of six; a lane's numbers are its own
  // either way, so the bits are those of separate calls).
  const bool fused = uniform && eval && sample;
  if (eval && !fused) mix(in.wl, out.f.r, out.f.g, out.f.b, out.pdf_l);
  if (!sample) return;
  // The pick, then each row's child sampled with its own lobe number.
  std::vector<MaterialRef>& picked = st.picked;
  std::vector<float>& u_child = st.u_child;
  std::vector<float>& is_second = st.is_second;
  std::vector<float>& delta = st.delta;
  picked.resize(n), u_child.resize(n), is_second.resize(n), delta.resize(n);
  // BlendPicksSecond, 8 rows at a time (the same IEEE operations).
  size_t seconds = 0;
  ForEachRowVector(
      n,
      [&](size_t i) HWY_ATTR {
        const D8 d;
        const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f), below_one = hn::Set(d, 0x1.fffffep-1f);
        const V8 w = Load(d, weight.data(), i), u = Load(d, in.u_lobe, i);
        const M8 s = hn::Lt(u, w);
        const V8 v_second = hn::Div(u, w);
        const V8 v_first = hn::Div(hn::Sub(u, w), hn::Sub(one, w));
        const V8 c_second = hn::IfThenElse(hn::Lt(v_second, below_one), v_second, below_one);
        const V8 c_first =
            hn::IfThenElse(hn::Lt(v_first, below_one),
                           hn::IfThenElseZero(hn::Gt(v_first, zero), v_first), below_one);
        Store(d, hn::IfThenElse(s, c_second, c_first), u_child.data(), i);
        Store(d, hn::IfThenElseZero(s, one), is_second.data(), i);
        seconds += hn::CountTrue(d, s);
      },
      [&](size_t i) {
        const bool s = BlendPicksSecond(weight[i], in.u_lobe[i], &u_child[i]);
        is_second[i] = s ? 1.0f : 0.0f;
        seconds += s;
      });
  if (!uniform)
    for (size_t i = 0; i < n; ++i) picked[i] = is_second[i] != 0 ? second[i] : first[i];
  ShadeInputs child_in;
  child_in.wo = in.wo, child_in.u_lobe = u_child.data(), child_in.u_x = in.u_x,
  child_in.u_y = in.u_y;
  child_in.texture = in.texture;  // mask: textured children
  ShadeOutputs child_out = out;
  child_out.f = {}, child_out.pdf_l = nullptr;
  child_out.delta = delta.data();
  // With `fused`, a sampling child also writes its f and pdf at wl into its columns.
  const auto with_eval = [&](ShadeOutputs o, float* const f[4]) {
    if (fused) o.f = {f[0], f[1], f[2]}, o.pdf_l = f[3];
    return o;
  };
  ShadeInputs fused_in = child_in;
  if (fused) fused_in.wl = in.wl;
  if (!uniform) {
    ShadeHitsWith(
        [](const MaterialTables& mt, MaterialTag tg, const uint32_t* index, size_t count,
           const ShadeInputs& bin,
           const ShadeOutputs& bout) { ShadeBatchKernel(mt, tg, index, count, bin, bout); },
        m, picked.data(), n, child_in, child_out, &scratch);
  } else if (seconds == 0 || seconds == n) {
    const bool second_child = seconds == n;
    ShadeBatchKernel(m, second_child ? kind1 : kind0, (second_child ? st.index1 : st.index0).data(),
                     n, fused_in, with_eval(child_out, second_child ? f1 : f0));
    if (fused) children_eval(!second_child, in.wl, second_child ? f0 : f1);
  } else {
    // The first child into the outputs, the second into `other`, then its picked rows moved.
    ShadeBatchKernel(m, kind0, st.index0.data(), n, fused_in, with_eval(child_out, f0));
    std::vector<float>& other = st.other;
    other.resize(9 * n);
    float* col[9];
    for (int k = 0; k < 9; ++k) col[k] = other.data() + k * n;
    ShadeOutputs second_out;
    second_out.wi = {col[0], col[1], col[2]};
    second_out.weight = {col[3], col[4], col[5]};
    second_out.pdf = col[6], second_out.eta = col[7], second_out.delta = col[8];
    ShadeBatchKernel(m, kind1, st.index1.data(), n, fused_in, with_eval(second_out, f1));
    float* const dst[9] = {out.wi.x,     out.wi.y, out.wi.z, out.weight.r, out.weight.g,
                           out.weight.b, out.pdf,  out.eta,  delta.data()};
    for (int k = 0; k < 9; ++k) BlendTakeRows(n, is_second.data(), col[k], dst[k]);
  }
  if (fused) BlendMix(n, weight.data(), f0, f1, out.f.r, out.f.g, out.f.b, out.pdf_l);
  // Non-delta samples: the mixture's f and pdf at the sampled direction.
  std::vector<float>& mixed = st.mixed;
  mixed.resize(4 * n);
  float* const mixed_cols[4] = {mixed.data(), mixed.data() + n, mixed.data() + 2 * n,
                                mixed.data() + 3 * n};
  mix({out.wi.x, out.wi.y, out.wi.z}, mixed_cols[0], mixed_cols[1], mixed_cols[2], mixed_cols[3]);
  BlendFinishSamples(n, weight.data(), is_second.data(), mixed_cols, delta.data(), out);
  if (out.delta != nullptr) std::copy(delta.begin(), delta.end(), out.delta);
}

/// ShadeBlendRows over chunks of kBlendChunk rows: a chunk's 40-odd columns (inputs, the
/// children's numbers, the outputs) stay in the core's caches between the passes over them.
/// Every row's outputs depend on its own inputs only, so chunking changes no result.
inline constexpr size_t kBlendChunk = 256;
inline HWY_NOINLINE void ShadeBlend(const MaterialTables& m, const uint32_t* material_index,
                                    size_t n, const ShadeInputs& in, const ShadeOutputs& out) {
  const auto at = [](auto* p, size_t i) { return p != nullptr ? p + i : p; };
  for (size_t i = 0; i < n; i += kBlendChunk) {
    ShadeInputs ci = in;
    ci.wo = {at(in.wo.x, i), at(in.wo.y, i), at(in.wo.z, i)};
    ci.wl = {at(in.wl.x, i), at(in.wl.y, i), at(in.wl.z, i)};
    ci.u_lobe = at(in.u_lobe, i), ci.u_x = at(in.u_x, i), ci.u_y = at(in.u_y, i);
    ci.texture.entry = at(in.texture.entry, i);
    ShadeOutputs co;
    co.f = {at(out.f.r, i), at(out.f.g, i), at(out.f.b, i)};
    co.pdf_l = at(out.pdf_l, i);
    co.wi = {at(out.wi.x, i), at(out.wi.y, i), at(out.wi.z, i)};
    co.weight = {at(out.weight.r, i), at(out.weight.g, i), at(out.weight.b, i)};
    co.pdf = at(out.pdf, i), co.eta = at(out.eta, i), co.delta = at(out.delta, i);
    ShadeBlendRows(m, material_index + i, std::min(kBlendChunk, n - i), ci, co);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_BLEND8_INL_H_
