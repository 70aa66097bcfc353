// normal: per-target twin of engine/bsdf/perturbed_frame.h (Mitsuba's normalmap / bumpmap),
// included by bsdf8-inl.h. PerturbedFrame8 builds the perturbed frames of eight rows with the
// oracle's float operations in its order (products rounded before each add, as the oracle is
// compiled without FMA contraction): bit-identical to PerturbedFrame. ShadePerturbed runs a
// tag's rows through it: wo and wl into the frames, the tag's kernel (two-sided aware) on the
// copies, then the side rule, the cosine ratio and the shadowing term, as the oracle's
// Perturbed* calls do.

#if defined(PTLAB_SIMD_PERTURBED_FRAME8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_PERTURBED_FRAME8_INL_H_
#undef PTLAB_SIMD_PERTURBED_FRAME8_INL_H_
#else
#define PTLAB_SIMD_PERTURBED_FRAME8_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include "engine/bsdf/perturbed_frame.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/render/interaction.h"
#include "engine/wavefront/bsdf.h"
#include "hwy/highway.h"
#include "simd/texture/texture8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

namespace perturbed8 {

using D = hn::CappedTag<float, 8>;
using DI = hn::RebindToSigned<D>;
using V = hn::Vec<D>;
using VI = hn::Vec<DI>;
using M = hn::Mask<D>;

struct V3 {
  V x, y, z;
};

/// a·b rounded before any add (opaque to contraction, as texture8's RMul).
HWY_INLINE V Mul(V a, V b) { return hn::Or(hn::Mul(a, b), hn::Zero(D())); }
HWY_INLINE V Dot(const V3& a, const V3& b) {
  return hn::Add(hn::Add(Mul(a.x, b.x), Mul(a.y, b.y)), Mul(a.z, b.z));
}
HWY_INLINE V3 Scale(const V3& a, V s) { return {Mul(a.x, s), Mul(a.y, s), Mul(a.z, s)}; }
HWY_INLINE V3 Sub(const V3& a, const V3& b) {
  return {hn::Sub(a.x, b.x), hn::Sub(a.y, b.y), hn::Sub(a.z, b.z)};
}
HWY_INLINE V3 Add(const V3& a, const V3& b) {
  return {hn::Add(a.x, b.x), hn::Add(a.y, b.y), hn::Add(a.z, b.z)};
}
HWY_INLINE V3 Cross(const V3& a, const V3& b) {
  return {hn::Sub(Mul(a.y, b.z), Mul(a.z, b.y)), hn::Sub(Mul(a.z, b.x), Mul(a.x, b.z)),
          hn::Sub(Mul(a.x, b.y), Mul(a.y, b.x))};
}
HWY_INLINE V3 Select(M m, const V3& a, const V3& b) {
  return {hn::IfThenElse(m, a.x, b.x), hn::IfThenElse(m, a.y, b.y), hn::IfThenElse(m, a.z, b.z)};
}
HWY_INLINE V3 Splat(float x, float y, float z) {
  const D d;
  return {hn::Set(d, x), hn::Set(d, y), hn::Set(d, z)};
}
HWY_INLINE M Finite(V x) { return hn::IsFinite(x); }
HWY_INLINE M Finite3(const V3& v) {
  return hn::And(hn::And(Finite(v.x), Finite(v.y)), Finite(v.z));
}

/// Frame::ToLocal / ToWorld with frame vectors s, t, n.
struct F3 {
  V3 s, t, n;
};
HWY_INLINE V3 ToLocal(const F3& f, const V3& v) { return {Dot(v, f.s), Dot(v, f.t), Dot(v, f.n)}; }
HWY_INLINE V3 ToWorld(const F3& f, const V3& v) {
  return {hn::Add(hn::Add(Mul(f.s.x, v.x), Mul(f.t.x, v.y)), Mul(f.n.x, v.z)),
          hn::Add(hn::Add(Mul(f.s.y, v.x), Mul(f.t.y, v.y)), Mul(f.n.y, v.z)),
          hn::Add(hn::Add(Mul(f.s.z, v.x), Mul(f.t.z, v.y)), Mul(f.n.z, v.z))};
}

/// Frame(n): Duff et al.'s basis, the oracle's operations.
HWY_INLINE F3 DuffFrame(const V3& n) {
  const D d;
  const V one = hn::Set(d, 1.0f);
  const V sign = hn::CopySign(one, n.z);
  const V a = hn::Div(hn::Set(d, -1.0f), hn::Add(sign, n.z));
  const V b = Mul(Mul(n.x, n.y), a);
  F3 f;
  f.n = n;
  f.s = {hn::Add(one, Mul(Mul(Mul(sign, n.x), n.x), a)), Mul(sign, b), hn::Neg(Mul(sign, n.x))};
  f.t = {b, hn::Add(sign, Mul(Mul(n.y, n.y), a)), hn::Neg(n.y)};
  return f;
}

/// NormalizedOr: v / |v| (as v · (1 / sqrt(|v|²))), or fallback where |v|² < 1e-30 or not finite.
HWY_INLINE V3 NormalizedOr(const V3& v, const V3& fallback) {
  const D d;
  const V len2 = Dot(v, v);
  const M ok = hn::And(hn::Ge(len2, hn::Set(d, 1e-30f)), Finite(len2));
  const V inv = hn::Div(hn::Set(d, 1.0f), hn::Sqrt(len2));
  return Select(ok, Scale(v, inv), fallback);
}

/// TanTheta2 of the oracle: max(0, 1 − z²) / z² (std::max(0, x) for finite x).
HWY_INLINE V TanTheta2(V z) {
  const D d;
  const V z2 = Mul(z, z);
  return hn::Div(hn::Max(hn::Zero(d), hn::Sub(hn::Set(d, 1.0f), z2)), z2);
}

/// ShadowTerminator(n, w) of engine/bsdf/perturbed_frame.h.
HWY_INLINE V ShadowTerminator(V nz, V wz) {
  const D d;
  const V one = hn::Set(d, 1.0f);
  const V alpha2 = hn::Min(Mul(hn::Set(d, 0.125f), TanTheta2(nz)), one);
  const V g =
      hn::Div(hn::Set(d, 2.0f), hn::Add(one, hn::Sqrt(hn::Add(one, Mul(alpha2, TanTheta2(wz))))));
  const V shadowed = hn::IfThenZeroElse(hn::Not(Finite(g)), g);
  return hn::IfThenElse(hn::Gt(alpha2, hn::Zero(d)), shadowed, one);
}

/// EvalTextureGradient for the lanes of `active` (bilinear bitmap rows; others 0), the oracle's
/// operations: the four texels' luminances, the bilinear derivative, the chain rule.
HWY_INLINE void TextureGradient8(const TextureTable& t, VI id, V u, V v, M active, V* gu, V* gv) {
  using namespace texture8;
  const D d;
  const DI di;
  const size_t lanes = hn::Lanes(d);
  *gu = *gv = hn::Zero(d);
  HWY_ALIGN int32_t rows[8], ok[8];
  const VI row = hn::IfThenElseZero(hn::RebindMask(di, active), id);
  hn::Store(row, di, rows);
  HWY_ALIGN int32_t act[8];
  hn::Store(hn::VecFromMask(di, hn::RebindMask(di, active)), di, act);
  for (size_t j = 0; j < lanes; ++j)
    ok[j] = act[j] != 0 && t.Kind(rows[j]) == TextureKind::kBitmap &&
                    TextureFilter(t.filter[rows[j]]) == TextureFilter::kBilinear
                ? -1
                : 0;
  const M bilinear = hn::RebindMask(d, hn::Ne(hn::Load(di, ok), hn::Zero(di)));
  if (hn::AllFalse(d, bilinear)) return;
  HWY_ALIGN int32_t wraps[8];
  for (size_t j = 0; j < lanes; ++j) wraps[j] = t.wrap[rows[j]];
  const V m00 = GatherF(d, t.m00, row), m01 = GatherF(d, t.m01, row), m10 = GatherF(d, t.m10, row),
          m11 = GatherF(d, t.m11, row);
  const V su = hn::Add(hn::Add(Mul(m00, u), Mul(m01, v)), GatherF(d, t.m02, row));
  const V sv = hn::Add(hn::Add(Mul(m10, u), Mul(m11, v)), GatherF(d, t.m12, row));
  const VI wi = GatherI(t.width, row), hi = GatherI(t.height, row);
  const V w = hn::ConvertTo(d, wi), h = hn::ConvertTo(d, hi);
  const V half = hn::Set(d, 0.5f), one = hn::Set(d, 1.0f);
  const V x = ClampTexel(d, hn::Sub(Mul(su, w), half)),
          y = ClampTexel(d, hn::Sub(Mul(sv, h), half));
  const V x0 = hn::Floor(x), y0 = hn::Floor(y);
  const V fx = hn::Sub(x, x0), fy = hn::Sub(y, y0);
  const VI ix = hn::ConvertTo(di, x0), iy = hn::ConvertTo(di, y0);
  const VI wrap = hn::Load(di, wraps), one_i = hn::Set(di, 1);
  const VI xa = WrapTexel(d, ix, wi, wrap), xb = WrapTexel(d, hn::Add(ix, one_i), wi, wrap);
  const VI ya = WrapTexel(d, iy, hi, wrap), yb = WrapTexel(d, hn::Add(iy, one_i), hi, wrap);
  const VI offset = GatherI(t.offset, row);
  const VI three = hn::Set(di, 3);
  const auto lum = [&](VI tx, VI ty) {
    const VI at = hn::Add(offset, hn::Mul(hn::Add(hn::Mul(ty, wi), tx), three));
    const VI at_bilinear = hn::IfThenElseZero(hn::RebindMask(di, bilinear), at);
    const V r = hn::GatherIndex(d, t.data.data(), at_bilinear);
    const V g = hn::GatherIndex(d, t.data.data(), hn::Add(at_bilinear, one_i));
    const V b = hn::GatherIndex(d, t.data.data(), hn::Add(at_bilinear, hn::Set(di, 2)));
    return hn::Add(hn::Add(Mul(hn::Set(d, 0.212671f), r), Mul(hn::Set(d, 0.715160f), g)),
                   Mul(hn::Set(d, 0.072169f), b));
  };
  const V f00 = lum(xa, ya), f10 = lum(xb, ya), f01 = lum(xa, yb), f11 = lum(xb, yb);
  const V df_dx = hn::Add(Mul(hn::Sub(one, fy), hn::Sub(f10, f00)), Mul(fy, hn::Sub(f11, f01)));
  const V df_dy = hn::Add(Mul(hn::Sub(one, fx), hn::Sub(f01, f00)), Mul(fx, hn::Sub(f11, f10)));
  const V gx = Mul(df_dx, w), gy = Mul(df_dy, h);
  *gu = hn::IfThenElseZero(bilinear, hn::Add(Mul(gx, m00), Mul(gy, m10)));
  *gv = hn::IfThenElseZero(bilinear, hn::Add(Mul(gx, m01), Mul(gy, m11)));
}

}  // namespace perturbed8

/// PerturbedFrame of rows [i, i + Lanes): perturbation ids pid (−1: not perturbed: the
/// identity frame), the rows' shading points its[entry[row]], viewer directions wo (local).
HWY_INLINE perturbed8::F3 PerturbedFrame8(const MaterialTables& m, const ShadeInputs::Textures& tex,
                                          const int32_t* pid, const uint32_t* entry,
                                          const perturbed8::V3& wo) {
  using namespace perturbed8;
  const D d;
  const DI di;
  const size_t lanes = hn::Lanes(d);
  const ShadingPerturbations& p = m.perturbation;
  const VI id = hn::LoadU(di, pid);
  const M perturbed = hn::RebindMask(d, hn::Gt(id, hn::Set(di, -1)));
  F3 identity{Splat(1, 0, 0), Splat(0, 1, 0), Splat(0, 0, 1)};
  if (hn::AllFalse(d, perturbed)) return identity;
  // The shading points' fields (SurfaceInteraction as 4-byte words): frame, ng, uv, p, prim.
  constexpr int32_t kWords = int32_t(sizeof(SurfaceInteraction) / 4);
  constexpr int32_t kP = int32_t(offsetof(SurfaceInteraction, p) / 4),
                    kNg = int32_t(offsetof(SurfaceInteraction, ng) / 4),
                    kFrame = int32_t(offsetof(SurfaceInteraction, frame) / 4),
                    kUv = int32_t(offsetof(SurfaceInteraction, uv) / 4),
                    kPrim = int32_t(offsetof(SurfaceInteraction, prim) / 4);
  HWY_ALIGN int32_t entries[8];
  for (size_t j = 0; j < lanes; ++j)
    entries[j] = pid[j] >= 0 ? int32_t(entry[j]) : int32_t(entry[0]);
  // Lanes that are not perturbed read a perturbed lane's entry (any valid row).
  int32_t any = 0;
  for (size_t j = 0; j < lanes; ++j)
    if (pid[j] >= 0) any = int32_t(entry[j]);
  for (size_t j = 0; j < lanes; ++j)
    if (pid[j] < 0) entries[j] = any;
  const VI base = hn::Mul(hn::Load(di, entries), hn::Set(di, kWords));
  const float* its = reinterpret_cast<const float*>(tex.its);
  const auto at = [&](int32_t word) {
    return hn::GatherIndex(d, its, hn::Add(base, hn::Set(di, word)));
  };
  F3 frame;
  frame.s = {at(kFrame), at(kFrame + 1), at(kFrame + 2)};
  frame.t = {at(kFrame + 3), at(kFrame + 4), at(kFrame + 5)};
  frame.n = {at(kFrame + 6), at(kFrame + 7), at(kFrame + 8)};
  const V3 ng{at(kNg), at(kNg + 1), at(kNg + 2)};
  const V u = at(kUv), v = at(kUv + 1);
  const VI prim = hn::GatherIndex(di, reinterpret_cast<const int32_t*>(tex.its),
                                  hn::Add(base, hn::Set(di, kPrim)));
  // LocalTangentsAt: the triangle's columns, or the basis around ng.
  HWY_ALIGN int32_t prims[8], has_row[8];
  hn::Store(prim, di, prims);
  for (size_t j = 0; j < lanes; ++j)
    has_row[j] = !IsSphereHit(uint32_t(prims[j])) && uint32_t(prims[j]) < p.dp_du_x.size() ? -1 : 0;
  const M tri = hn::And(perturbed, hn::RebindMask(d, hn::Ne(hn::Load(di, has_row), hn::Zero(di))));
  const VI row = hn::IfThenElseZero(hn::RebindMask(di, tri), prim);
  const F3 basis = DuffFrame(ng);
  V3 du = basis.s, dv = basis.t;
  if (!hn::AllFalse(d, tri)) {
    const auto g = [&](const AlignedVector<float>& c) { return hn::GatherIndex(d, c.data(), row); };
    du = Select(tri, V3{g(p.dp_du_x), g(p.dp_du_y), g(p.dp_du_z)}, du);
    dv = Select(tri, V3{g(p.dp_dv_x), g(p.dp_dv_y), g(p.dp_dv_z)}, dv);
  }
  du = ToLocal(frame, du), dv = ToLocal(frame, dv);
  const V3 ngl = ToLocal(frame, ng);
  // Kind and texture per lane.
  HWY_ALIGN int32_t kinds[8], textures[8], ids[8];
  HWY_ALIGN float scales[8];
  hn::Store(id, di, ids);
  for (size_t j = 0; j < lanes; ++j) {
    const size_t k = ids[j] >= 0 ? size_t(ids[j]) : 0;
    kinds[j] = ids[j] >= 0 ? int32_t(p.kind[k]) : -1;
    textures[j] = ids[j] >= 0 ? int32_t(p.texture[k]) : 0;
    scales[j] = ids[j] >= 0 ? p.scale[k] : 0.0f;
  }
  const VI kind = hn::Load(di, kinds), texture = hn::Load(di, textures);
  const M normal =
      hn::RebindMask(d, hn::Eq(kind, hn::Set(di, int32_t(PerturbationKind::kNormalMap))));
  const M bump = hn::RebindMask(d, hn::Eq(kind, hn::Set(di, int32_t(PerturbationKind::kBumpMap))));
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f), two = hn::Set(d, 2.0f);
  V3 n = Splat(0, 0, 0), s_hint = Splat(0, 0, 0);
  if (!hn::AllFalse(d, normal)) {
    const V3 s0 = NormalizedOr({du.x, du.y, zero}, Splat(1, 0, 0));
    const V3 t0{hn::Neg(s0.y), s0.x, zero};
    const V px = at(kP), py = at(kP + 1), pz = at(kP + 2);
    V cr, cg, cb;
    EvalTexture8(*tex.textures, texture, u, v, px, py, pz, prim, normal, &cr, &cg, &cb);
    const V3 nm{hn::Sub(Mul(two, cr), one), hn::Sub(Mul(two, cg), one), hn::Sub(Mul(two, cb), one)};
    const V3 nn = Add(Add(Scale(s0, nm.x), Scale(t0, nm.y)), V3{zero, zero, nm.z});
    n = Select(normal, nn, n);
    s_hint = Select(normal, s0, s_hint);
  }
  if (!hn::AllFalse(d, bump)) {
    V gu, gv;
    perturbed8::TextureGradient8(*tex.textures, texture, u, v, bump, &gu, &gv);
    const V scale = hn::Load(d, scales);
    const V3 dup{du.x, du.y, Mul(scale, gu)}, dvp{dv.x, dv.y, Mul(scale, gv)};
    V3 nb = Cross(dup, dvp);
    const M below = hn::Lt(Dot(ngl, nb), zero);
    nb = Select(below, V3{hn::Neg(nb.x), hn::Neg(nb.y), hn::Neg(nb.z)}, nb);
    n = Select(bump, nb, n);
    s_hint = Select(bump, du, s_hint);
  }
  n = NormalizedOr(Select(Finite3(n), n, Splat(0, 0, 0)), Splat(0, 0, 1));
  const M flip = hn::Le(Mul(wo.z, Dot(wo, n)), zero);
  n = {hn::IfThenElse(flip, hn::Neg(n.x), n.x), hn::IfThenElse(flip, hn::Neg(n.y), n.y), n.z};
  // FrameAlong(n, s_hint).
  s_hint = Select(Finite3(s_hint), s_hint, Splat(1, 0, 0));
  const V3 s = NormalizedOr(Sub(s_hint, Scale(n, Dot(n, s_hint))), Splat(0, 0, 0));
  const M s_zero = hn::And(hn::And(hn::Eq(s.x, zero), hn::Eq(s.y, zero)), hn::Eq(s.z, zero));
  const F3 duff = DuffFrame(n);
  F3 out;
  out.n = n;
  out.s = Select(s_zero, duff.s, s);
  out.t = Select(s_zero, duff.t, Cross(n, s));
  return {Select(perturbed, out.s, identity.s), Select(perturbed, out.t, identity.t),
          Select(perturbed, out.n, identity.n)};
}

/// The rows' perturbation ids (−1 where the row is not perturbed).
inline void PerturbationIds(const ShadingPerturbations& p, MaterialTag tag, const uint32_t* index,
                            size_t n, int32_t* pid) {
  for (size_t j = 0; j < n; ++j) pid[j] = int32_t(p.Of(MaterialRef::Make(tag, index[j])));
}

/// simd::PerturbedFrameBatch (plain API in simd/wavefront/perturbed_frame8.h).
inline void PerturbedFrameBatchKernel(const MaterialTables& m, MaterialTag tag,
                                      const uint32_t* material_index, size_t n,
                                      const ShadeInputs& in, float* const frame[9]) {
  using namespace perturbed8;
  const D d;
  const size_t lanes = hn::Lanes(d);
  HWY_ALIGN int32_t pid[8];
  HWY_ALIGN uint32_t entry[8];
  HWY_ALIGN float wx[8], wy[8], wz[8];
  for (size_t i = 0; i < n; i += lanes) {
    const size_t c = n - i < lanes ? n - i : lanes;
    for (size_t j = 0; j < lanes; ++j) {
      const size_t r = i + (j < c ? j : 0);
      pid[j] = j < c ? int32_t(m.perturbation.Of(MaterialRef::Make(tag, material_index[r]))) : -1;
      entry[j] = in.texture.entry[r];
      wx[j] = in.wo.x[r], wy[j] = in.wo.y[r], wz[j] = in.wo.z[r];
    }
    const F3 f = PerturbedFrame8(m, in.texture, pid, entry,
                                 V3{hn::Load(d, wx), hn::Load(d, wy), hn::Load(d, wz)});
    const V cols[9] = {f.s.x, f.s.y, f.s.z, f.t.x, f.t.y, f.t.z, f.n.x, f.n.y, f.n.z};
    HWY_ALIGN float tmp[8];
    for (int k = 0; k < 9; ++k) {
      hn::Store(cols[k], d, tmp);
      for (size_t j = 0; j < c; ++j) frame[k][i + j] = tmp[j];
    }
  }
}

inline void ShadeBatchKernelInFrame(const MaterialTables& m, MaterialTag tag,
                                    const uint32_t* material_index, size_t n, const ShadeInputs& in,
                                    const ShadeOutputs& out);

/// The shade step of a tag some of whose rows are perturbed, in chunks of kChunk rows on stack
/// copies of wo and wl in the rows' perturbed frames (rows that are not perturbed keep theirs).
inline HWY_NOINLINE void ShadePerturbed(const MaterialTables& m, MaterialTag tag,
                                        const uint32_t* material_index, size_t n,
                                        const ShadeInputs& in, const ShadeOutputs& out) {
  using namespace perturbed8;
  PTLAB_CHECK(in.texture.textures != nullptr);
  constexpr size_t kChunk = 256;
  const D d;
  const size_t lanes = hn::Lanes(d);
  HWY_ALIGN int32_t pid[kChunk + 8];
  HWY_ALIGN uint32_t entry[kChunk + 8];
  HWY_ALIGN float wo[3][kChunk + 8], wl[3][kChunk + 8], fr[9][kChunk + 8], lscale[kChunk + 8];
  HWY_ALIGN float src_o[3][kChunk + 8], src_l[3][kChunk + 8];
  const bool eval = in.wl.x != nullptr, sample = in.u_lobe != nullptr;
  const V zero = hn::Zero(d);
  for (size_t at = 0; at < n; at += kChunk) {
    const size_t c = n - at < kChunk ? n - at : kChunk;
    const size_t padded = (c + lanes - 1) / lanes * lanes;
    const uint32_t* index = material_index + at;
    PerturbationIds(m.perturbation, tag, index, c, pid);
    for (size_t j = 0; j < padded; ++j) {
      const size_t r = at + (j < c ? j : 0);
      if (j >= c) pid[j] = -1;
      entry[j] = in.texture.entry[r];
      src_o[0][j] = in.wo.x[r], src_o[1][j] = in.wo.y[r], src_o[2][j] = in.wo.z[r];
      if (eval) src_l[0][j] = in.wl.x[r], src_l[1][j] = in.wl.y[r], src_l[2][j] = in.wl.z[r];
    }
    for (size_t j = 0; j < padded; j += lanes) {
      const M perturbed = hn::RebindMask(d, hn::Gt(hn::Load(DI(), pid + j), hn::Set(DI(), -1)));
      const V3 o{hn::Load(d, src_o[0] + j), hn::Load(d, src_o[1] + j), hn::Load(d, src_o[2] + j)};
      const F3 f = PerturbedFrame8(m, in.texture, pid + j, entry + j, o);
      const V cols[9] = {f.s.x, f.s.y, f.s.z, f.t.x, f.t.y, f.t.z, f.n.x, f.n.y, f.n.z};
      for (int k = 0; k < 9; ++k) hn::Store(cols[k], d, fr[k] + j);
      const V3 op = Select(perturbed, ToLocal(f, o), o);
      hn::Store(op.x, d, wo[0] + j), hn::Store(op.y, d, wo[1] + j), hn::Store(op.z, d, wo[2] + j);
      if (!eval) continue;
      const V3 l{hn::Load(d, src_l[0] + j), hn::Load(d, src_l[1] + j), hn::Load(d, src_l[2] + j)};
      const V3 lp = Select(perturbed, ToLocal(f, l), l);
      hn::Store(lp.x, d, wl[0] + j), hn::Store(lp.y, d, wl[1] + j), hn::Store(lp.z, d, wl[2] + j);
      // The side rule and |cos θi'| / |cos θi| · shadowing (−1: no direction of the row, f = 0
      // and pdf = 0; −2: a ratio that is not finite, f = 0).
      const M side = hn::Gt(Mul(l.z, lp.z), zero);
      const V ratio = Mul(hn::Div(hn::Abs(lp.z), hn::Abs(l.z)), ShadowTerminator(f.n.z, l.z));
      const V s = hn::IfThenElse(side, hn::IfThenElse(Finite(ratio), ratio, hn::Set(d, -2.0f)),
                                 hn::Set(d, -1.0f));
      hn::Store(hn::IfThenElse(perturbed, s, hn::Set(d, 1.0f)), d, lscale + j);
    }
    ShadeInputs cin;
    cin.wo = {wo[0], wo[1], wo[2]};
    if (eval) cin.wl = {wl[0], wl[1], wl[2]};
    if (sample) cin.u_lobe = in.u_lobe + at, cin.u_x = in.u_x + at, cin.u_y = in.u_y + at;
    cin.texture = in.texture;
    cin.texture.entry = in.texture.entry + at;
    ShadeOutputs cout;
    if (eval) {
      cout.f = {out.f.r + at, out.f.g + at, out.f.b + at};
      cout.pdf_l = out.pdf_l + at;
    }
    if (sample) {
      cout.wi = {out.wi.x + at, out.wi.y + at, out.wi.z + at};
      cout.weight = {out.weight.r + at, out.weight.g + at, out.weight.b + at};
      cout.pdf = out.pdf + at, cout.eta = out.eta + at;
      if (out.delta != nullptr) cout.delta = out.delta + at;
    }
    ShadeBatchKernelInFrame(m, tag, index, c, cin, cout);
    // Back from the frames, row by row (the oracle's scalar operations).
    for (size_t j = 0; j < c; ++j) {
      if (pid[j] < 0) continue;
      if (eval) {
        const float s = lscale[j];
        if (s < 0) {
          cout.f.r[j] = cout.f.g[j] = cout.f.b[j] = 0.0f;
          if (s == -1.0f) cout.pdf_l[j] = 0.0f;
        } else {
          cout.f.r[j] *= s, cout.f.g[j] *= s, cout.f.b[j] *= s;
        }
      }
      if (!sample || !(cout.pdf[j] > 0)) continue;
      const Frame f = [&] {
        Frame x;
        x.s = {fr[0][j], fr[1][j], fr[2][j]}, x.t = {fr[3][j], fr[4][j], fr[5][j]};
        x.n = {fr[6][j], fr[7][j], fr[8][j]};
        return x;
      }();
      const Vec3f wi_p{cout.wi.x[j], cout.wi.y[j], cout.wi.z[j]};
      const Vec3f wi = f.ToWorld(wi_p);
      if (!(wi_p.z * wi.z > 0)) {
        cout.wi.x[j] = cout.wi.y[j] = cout.wi.z[j] = 0.0f;
        cout.weight.r[j] = cout.weight.g[j] = cout.weight.b[j] = 0.0f;
        cout.pdf[j] = 0.0f, cout.eta[j] = 1.0f;
        if (cout.delta != nullptr) cout.delta[j] = 0.0f;
        continue;
      }
      const float g = ptlab::ShadowTerminator(f.n, wi);
      cout.wi.x[j] = wi.x, cout.wi.y[j] = wi.y, cout.wi.z[j] = wi.z;
      cout.weight.r[j] *= g, cout.weight.g[j] *= g, cout.weight.b[j] *= g;
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_PERTURBED_FRAME8_INL_H_
