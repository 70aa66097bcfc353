// Per-target SIMD twin of engine/bsdf/mask.h (Mitsuba `mask`), included by bsdf8-inl.h.
// Oracle: MaskEval / MaskPdf / MaskSample. The opacity is gathered (TexturedFloat8 for textured
// rows) 8-wide; the nested materials run on their own 8-wide kernels (ShadeHitsWith, as the
// blend's children do); the mask only scales their numbers and writes the pass-through rows,
// in plain loops with the oracle's operations. Contract: the nested material's, and
// bit-identical for the opacity, the pick and the pass-through (tests/simd/wavefront/
// mask8_test.cpp).

#if defined(PTLAB_SIMD_MASK8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_MASK8_INL_H_
#undef PTLAB_SIMD_MASK8_INL_H_
#else
#define PTLAB_SIMD_MASK8_INL_H_
#endif

#include <memory>
#include <vector>

#include "engine/bsdf/mask.h"
#include "engine/wavefront/bsdf.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

inline void ShadeBatchKernel(const MaterialTables& m, MaterialTag tag,
                             const uint32_t* material_index, size_t n, const ShadeInputs& in,
                             const ShadeOutputs& out);

/// MaskEval / MaskPdf / MaskSample for rows of MaskTable.
inline HWY_NOINLINE void ShadeMask(const MaterialTables& m, const uint32_t* material_index,
                                   size_t n, const ShadeInputs& in, const ShadeOutputs& out) {
  const MaskTable& t = m.mask;
  const bool eval = in.wl.x != nullptr, sample = in.u_lobe != nullptr;
  // Working storage reused across calls, one set per nesting level (as ShadeBlend's).
  struct Storage {
    ShadeScratch scratch;
    std::vector<MaterialRef> nested, picked;
    std::vector<float> opacity, u_nested, delta;
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
  st.nested.resize(n), st.opacity.resize(n);
  for (size_t i = 0; i < n; ++i) st.nested[i] = t.Nested(material_index[i]);
  // MaskOpacity (TexturedUnitFloatRows8: blend8-inl.h).
  TexturedUnitFloatRows8(t.opacity, t.opacity_texture, in.texture, material_index, n,
                         st.opacity.data());
  const float* opacity = st.opacity.data();
  const auto run = [&](const MaterialRef* refs, const ShadeInputs& cin, const ShadeOutputs& cout) {
    ShadeHitsWith(
        [](const MaterialTables& mt, MaterialTag tg, const uint32_t* index, size_t count,
           const ShadeInputs& bin,
           const ShadeOutputs& bout) { ShadeBatchKernel(mt, tg, index, count, bin, bout); },
        m, refs, n, cin, cout, &st.scratch);
  };
  if (eval) {
    ShadeInputs cin;
    cin.wo = in.wo, cin.wl = in.wl, cin.texture = in.texture;
    ShadeOutputs cout;
    cout.f = out.f, cout.pdf_l = out.pdf_l;
    run(st.nested.data(), cin, cout);
    for (size_t i = 0; i < n; ++i) {
      const float o = opacity[i];
      out.f.r[i] = out.f.r[i] * o, out.f.g[i] = out.f.g[i] * o, out.f.b[i] = out.f.b[i] * o;
      out.pdf_l[i] = out.pdf_l[i] * o;
    }
  }
  if (!sample) return;
  // The pick: pass-through rows get no nested sample (MaterialRef::None() rows are zeroed).
  st.picked.resize(n), st.u_nested.resize(n), st.delta.resize(n);
  for (size_t i = 0; i < n; ++i) {
    st.u_nested[i] = 0.0f;
    st.picked[i] = MaskPicksNested(opacity[i], in.u_lobe[i], &st.u_nested[i]) ? st.nested[i]
                                                                              : MaterialRef::None();
  }
  ShadeInputs cin;
  cin.wo = in.wo, cin.u_lobe = st.u_nested.data(), cin.u_x = in.u_x, cin.u_y = in.u_y;
  cin.texture = in.texture;
  ShadeOutputs cout = out;
  cout.f = {}, cout.pdf_l = nullptr;
  cout.delta = st.delta.data();
  run(st.picked.data(), cin, cout);
  for (size_t i = 0; i < n; ++i) {
    if (st.picked[i].valid()) {
      if (!(out.pdf[i] > 0)) {  // the nested material had no sample
        st.delta[i] = 0.0f;
        continue;
      }
      out.pdf[i] *= opacity[i];
      if (out.pdf[i] > 0) continue;
      out.wi.x[i] = out.wi.y[i] = out.wi.z[i] = 0.0f;
      out.weight.r[i] = out.weight.g[i] = out.weight.b[i] = out.pdf[i] = 0.0f;
      out.eta[i] = 1.0f;
      st.delta[i] = 0.0f;
      continue;
    }
    out.wi.x[i] = -in.wo.x[i], out.wi.y[i] = -in.wo.y[i], out.wi.z[i] = -in.wo.z[i];
    out.weight.r[i] = out.weight.g[i] = out.weight.b[i] = 1.0f;
    out.pdf[i] = 1.0f - opacity[i];
    out.eta[i] = 1.0f;
    st.delta[i] = 1.0f;  // Mitsuba's null lobe is a delta lobe
  }
  if (out.delta != nullptr)
    for (size_t i = 0; i < n; ++i) out.delta[i] = st.delta[i];
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_MASK8_INL_H_
