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
  ShadeHitsWith(
      [](const MaterialTables& mt, MaterialTag t, const uint32_t* index, size_t count,
         const ShadeInputs& bin, const ShadeOutputs& bout) {
        ShadeBatchKernel(mt, t, index, count, bin, bout);
      },
      m, refs, n, in, out, scratch);
}

/// mask: TexturedUnitFloat of rows material_index[0, n) into out[0, n): the constant column,
/// TexturedFloat8 for the textured rows, clipped to [0, 1] as the oracle clips (NaN → 1). A
/// blend's weight, a mask's opacity.
inline void TexturedUnitFloatRows8(const AlignedVector<float>& constant,
                                   const AlignedVector<uint32_t>& texture,
                                   const ShadeInputs::Textures& tex,
                                   const uint32_t* material_index, size_t n, float* out) {
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

/// BlendEval / BlendPdf / BlendSample for rows of BlendTable.
inline void ShadeBlend(const MaterialTables& m, const uint32_t* material_index, size_t n,
                       const ShadeInputs& in, const ShadeOutputs& out) {
  const BlendTable& t = m.blend;
  const bool eval = in.wl.x != nullptr, sample = in.u_lobe != nullptr;
  // Working storage reused across calls, one set per nesting level (a blend child of a blend
  // runs while its parent's arrays are in use).
  struct Storage {
    ShadeScratch scratch;
    std::vector<MaterialRef> first, second, picked;
    std::vector<float> weight, c, u_child, is_second, delta, mixed;
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
  for (size_t i = 0; i < n; ++i) {
    const uint32_t row = material_index[i];
    first[i] = t.First(row), second[i] = t.Second(row);
  }
  TexturedUnitFloatRows8(t.weight, t.weight_texture, in.texture, material_index, n,
                         weight.data());  // mask: BlendWeight
  // Columns: f rgb and pdf of the first child, then of the second.
  std::vector<float>& c = st.c;
  c.resize(8 * n);
  float* const f0[4] = {c.data(), c.data() + n, c.data() + 2 * n, c.data() + 3 * n};
  float* const f1[4] = {c.data() + 4 * n, c.data() + 5 * n, c.data() + 6 * n, c.data() + 7 * n};
  const auto mix = [&](DirectionArrays w, float* fr, float* fg, float* fb, float* pdf) {
    BlendChildrenEval(m, first.data(), n, in.wo, w, f0[0], f0[1], f0[2], f0[3], &scratch,
                      in.texture);
    BlendChildrenEval(m, second.data(), n, in.wo, w, f1[0], f1[1], f1[2], f1[3], &scratch,
                      in.texture);
    for (size_t i = 0; i < n; ++i) {
      const float wt = weight[i], wf = 1.0f - wt;
      fr[i] = f0[0][i] * wf + f1[0][i] * wt;
      fg[i] = f0[1][i] * wf + f1[1][i] * wt;
      fb[i] = f0[2][i] * wf + f1[2][i] * wt;
      pdf[i] = wf * f0[3][i] + wt * f1[3][i];
    }
  };
  if (eval) mix(in.wl, out.f.r, out.f.g, out.f.b, out.pdf_l);
  if (!sample) return;
  // The pick, then each row's child sampled with its own lobe number.
  std::vector<MaterialRef>& picked = st.picked;
  std::vector<float>& u_child = st.u_child;
  std::vector<float>& is_second = st.is_second;
  std::vector<float>& delta = st.delta;
  picked.resize(n), u_child.resize(n), is_second.resize(n), delta.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const bool s = BlendPicksSecond(weight[i], in.u_lobe[i], &u_child[i]);
    picked[i] = s ? second[i] : first[i];
    is_second[i] = s ? 1.0f : 0.0f;
  }
  ShadeInputs child_in;
  child_in.wo = in.wo, child_in.u_lobe = u_child.data(), child_in.u_x = in.u_x,
  child_in.u_y = in.u_y;
  child_in.texture = in.texture;  // mask: textured children
  ShadeOutputs child_out = out;
  child_out.f = {}, child_out.pdf_l = nullptr;
  child_out.delta = delta.data();
  ShadeHitsWith(
      [](const MaterialTables& mt, MaterialTag tg, const uint32_t* index, size_t count,
         const ShadeInputs& bin, const ShadeOutputs& bout) {
        ShadeBatchKernel(mt, tg, index, count, bin, bout);
      },
      m, picked.data(), n, child_in, child_out, &scratch);
  // Non-delta samples: the mixture's f and pdf at the sampled direction.
  std::vector<float>& mixed = st.mixed;
  mixed.resize(4 * n);
  mix({out.wi.x, out.wi.y, out.wi.z}, mixed.data(), mixed.data() + n, mixed.data() + 2 * n,
      mixed.data() + 3 * n);
  for (size_t i = 0; i < n; ++i) {
    if (!(out.pdf[i] > 0)) continue;  // the child had no sample
    bool ok;
    if (delta[i] != 0) {
      out.pdf[i] *= is_second[i] != 0 ? weight[i] : 1.0f - weight[i];
      ok = out.pdf[i] > 0;
    } else {
      const float pdf = mixed[3 * n + i];
      const float s = std::fabs(out.wi.z[i]) / pdf;
      const float wr = mixed[i] * s, wg = mixed[n + i] * s, wb = mixed[2 * n + i] * s;
      ok = pdf > 0 && std::isfinite(pdf) && std::isfinite(wr) && std::isfinite(wg) &&
           std::isfinite(wb);
      if (ok) out.pdf[i] = pdf, out.weight.r[i] = wr, out.weight.g[i] = wg, out.weight.b[i] = wb;
    }
    if (!ok) {
      out.wi.x[i] = out.wi.y[i] = out.wi.z[i] = 0.0f;
      out.weight.r[i] = out.weight.g[i] = out.weight.b[i] = out.pdf[i] = 0.0f;
      out.eta[i] = 1.0f;
      delta[i] = 0.0f;
    }
  }
  if (out.delta != nullptr)
    for (size_t i = 0; i < n; ++i) out.delta[i] = delta[i];
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_BLEND8_INL_H_
