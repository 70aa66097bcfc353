// Per-target texture lookup of simd/texture/texture8.h (re-included once per Highway target):
// EvalTexture's operations in its order, eight lanes per vector, each lane its own texture row.

#if defined(PTLAB_SIMD_TEXTURE8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TEXTURE8_INL_H_
#undef PTLAB_SIMD_TEXTURE8_INL_H_
#else
#define PTLAB_SIMD_TEXTURE8_INL_H_
#endif

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "engine/bvh/sphere_intersect.h"
#include "engine/scene/texture_tables.h"
#include "engine/texture/texture.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

namespace texture8 {

using DT = hn::CappedTag<float, 8>;
using DTI = hn::RebindToSigned<DT>;
using DTU = hn::RebindToUnsigned<DT>;
using VT = hn::Vec<DT>;
using VTI = hn::Vec<DTI>;
using MT = hn::Mask<DT>;

/// a·b rounded to float before any add (the OR with +0.0 is opaque to FMA contraction), so
/// every target rounds as the scalar oracle (compiled without FMA) does.
HWY_INLINE VT RMul(DT d, VT a, VT b) { return hn::Or(hn::Mul(a, b), hn::Zero(d)); }

/// ClampTexel: to ±kMaxTexelCoordinate, NaN to the low end.
HWY_INLINE VT ClampTexel(DT d, VT x) {
  const VT hi = hn::Set(d, kMaxTexelCoordinate), lo = hn::Set(d, -kMaxTexelCoordinate);
  return hn::IfThenElse(hn::Ge(x, lo), hn::Min(x, hi), lo);
}

/// i mod n ∈ [0, n) for n > 0 and |i| ≤ 2^24 + 1: the quotient through float (off by at most
/// one there), then corrected.
HWY_INLINE VTI Mod(DT d, VTI i, VTI n) {
  const DTI di;
  const VTI q = hn::ConvertTo(di, hn::Floor(hn::Div(hn::ConvertTo(d, i), hn::ConvertTo(d, n))));
  VTI r = hn::Sub(i, hn::Mul(q, n));
  for (int k = 0; k < 2; ++k) {
    r = hn::IfThenElse(hn::Lt(r, hn::Zero(di)), hn::Add(r, n), r);
    r = hn::IfThenElse(hn::Lt(r, n), r, hn::Sub(r, n));
  }
  return r;
}

/// WrapTexel per lane: wrap holds each lane's TextureWrap.
HWY_INLINE VTI WrapTexel(DT d, VTI i, VTI size, VTI wrap) {
  const DTI di;
  const VTI one = hn::Set(di, 1);
  const VTI clamp = hn::Min(hn::Max(i, hn::Zero(di)), hn::Sub(size, one));
  const VTI repeat = Mod(d, i, size);
  const VTI two = hn::Add(size, size);
  const VTI m = Mod(d, i, two);
  const VTI mirror = hn::IfThenElse(hn::Lt(m, size), m, hn::Sub(hn::Sub(two, one), m));
  return hn::IfThenElse(hn::Eq(wrap, hn::Set(di, int32_t(TextureWrap::kClamp))), clamp,
                        hn::IfThenElse(hn::Eq(wrap, hn::Set(di, int32_t(TextureWrap::kMirror))),
                                       mirror, repeat));
}

HWY_INLINE VT GatherF(DT d, const AlignedVector<float>& column, VTI idx) {
  return hn::GatherIndex(d, column.data(), idx);
}
HWY_INLINE VTI GatherI(const AlignedVector<uint32_t>& column, VTI idx) {
  const DTI di;
  return hn::GatherIndex(di, reinterpret_cast<const int32_t*>(column.data()), idx);
}

}  // namespace texture8

/// EvalTexture for the lanes of `active` (texture ids `id`, surface coordinates u, v, world
/// position p, primitive prim); other lanes get 0. Bit-identical to the oracle lane by lane.
HWY_INLINE void EvalTexture8(const TextureTable& t, hn::Vec<texture8::DTI> id, texture8::VT u,
                             texture8::VT v, texture8::VT px, texture8::VT py, texture8::VT pz,
                             hn::Vec<texture8::DTI> prim, texture8::MT active, texture8::VT* r,
                             texture8::VT* g, texture8::VT* b) {
  using namespace texture8;
  const DT d;
  const DTI di;
  const DTU du;
  const size_t lanes = hn::Lanes(d);
  const VT zero = hn::Zero(d), one = hn::Set(d, 1.0f), half = hn::Set(d, 0.5f);
  *r = *g = *b = zero;
  if (t.empty()) return;
  const auto active_i = hn::RebindMask(di, active);
  const VTI row = hn::IfThenElseZero(active_i, id);
  // The rows' one-byte columns, lane by lane.
  HWY_ALIGN int32_t rows[8], kinds[8], filters[8], wraps[8];
  hn::Store(row, di, rows);
  for (size_t j = 0; j < lanes; ++j)
    kinds[j] = t.kind[rows[j]], filters[j] = t.filter[rows[j]], wraps[j] = t.wrap[rows[j]];
  const VTI kind = hn::Load(di, kinds);
  const auto is = [&](TextureKind k) {
    return hn::And(active, hn::RebindMask(d, hn::Eq(kind, hn::Set(di, int32_t(k)))));
  };
  const MT bitmap = is(TextureKind::kBitmap), checker = is(TextureKind::kCheckerboard);
  const MT face = is(TextureKind::kFaceAttribute), vertex = is(TextureKind::kVertexAttribute);
  VT out_r = zero, out_g = zero, out_b = zero;
  *r = out_r, *g = out_g, *b = out_b;
  // No data at all: only mesh_attribute rows that no mesh bound, which are 0 everywhere.
  if (t.data.empty()) return;
  const VTI offset = GatherI(t.offset, row);
  // to_uv of the bitmap and checkerboard lanes.
  VT su = zero, sv = zero;
  if (!hn::AllFalse(d, hn::Or(bitmap, checker))) {
    su = hn::Add(hn::Add(RMul(d, GatherF(d, t.m00, row), u), RMul(d, GatherF(d, t.m01, row), v)),
                 GatherF(d, t.m02, row));
    sv = hn::Add(hn::Add(RMul(d, GatherF(d, t.m10, row), u), RMul(d, GatherF(d, t.m11, row), v)),
                 GatherF(d, t.m12, row));
  }
  if (!hn::AllFalse(d, bitmap)) {
    const VTI w = GatherI(t.width, row), h = GatherI(t.height, row);
    const VT wf = hn::ConvertTo(d, w), hf = hn::ConvertTo(d, h);
    const VTI wrap = hn::Load(di, wraps);
    const auto nearest =
        hn::Eq(hn::Load(di, filters), hn::Set(di, int32_t(TextureFilter::kNearest)));
    const VT x = ClampTexel(d, hn::Sub(RMul(d, su, wf), hn::IfThenZeroElse(hn::RebindMask(d, nearest), half)));
    const VT y = ClampTexel(d, hn::Sub(RMul(d, sv, hf), hn::IfThenZeroElse(hn::RebindMask(d, nearest), half)));
    const VT x0 = hn::Floor(x), y0 = hn::Floor(y);
    const VTI ix = hn::ConvertTo(di, x0), iy = hn::ConvertTo(di, y0);
    const VTI one_i = hn::Set(di, 1);
    const VTI xa = WrapTexel(d, ix, w, wrap), xb = WrapTexel(d, hn::Add(ix, one_i), w, wrap);
    const VTI ya = WrapTexel(d, iy, h, wrap), yb = WrapTexel(d, hn::Add(iy, one_i), h, wrap);
    const VTI three = hn::Set(di, 3);
    const auto texel = [&](VTI xi, VTI yi) {
      return hn::Add(offset, hn::Mul(hn::Add(hn::Mul(yi, w), xi), three));
    };
    // Only the bitmap lanes' indices (another kind's width and height are not a texel grid).
    const auto bitmap_i = hn::RebindMask(di, bitmap);
    const VTI i00 = hn::IfThenElseZero(bitmap_i, texel(xa, ya));
    const VTI i10 = hn::IfThenElseZero(bitmap_i, texel(xb, ya));
    const VTI i01 = hn::IfThenElseZero(bitmap_i, texel(xa, yb));
    const VTI i11 = hn::IfThenElseZero(bitmap_i, texel(xb, yb));
    const VT fx = hn::Sub(x, x0), fy = hn::Sub(y, y0);
    const VT gx = hn::Sub(one, fx), gy = hn::Sub(one, fy);
    const MT near_f = hn::RebindMask(d, nearest);
    VT c[3];
    for (int k = 0; k < 3; ++k) {
      const VTI kk = hn::Set(di, k);
      const VT a00 = hn::GatherIndex(d, t.data.data(), hn::Add(i00, kk));
      const VT a10 = hn::GatherIndex(d, t.data.data(), hn::Add(i10, kk));
      const VT a01 = hn::GatherIndex(d, t.data.data(), hn::Add(i01, kk));
      const VT a11 = hn::GatherIndex(d, t.data.data(), hn::Add(i11, kk));
      const VT bl = hn::Add(RMul(d, hn::Add(RMul(d, a00, gx), RMul(d, a10, fx)), gy),
                            RMul(d, hn::Add(RMul(d, a01, gx), RMul(d, a11, fx)), fy));
      c[k] = hn::IfThenElse(near_f, a00, bl);
    }
    out_r = hn::IfThenElse(bitmap, c[0], out_r);
    out_g = hn::IfThenElse(bitmap, c[1], out_g);
    out_b = hn::IfThenElse(bitmap, c[2], out_b);
  }
  if (!hn::AllFalse(d, checker)) {
    const VT cu = ClampTexel(d, su), cv = ClampTexel(d, sv);
    const MT mu = hn::Gt(hn::Sub(cu, hn::Floor(cu)), half);
    const MT mv = hn::Gt(hn::Sub(cv, hn::Floor(cv)), half);
    // color0 where mu == mv.
    const MT same = hn::Not(hn::Xor(mu, mv));
    const VTI at = hn::IfThenElseZero(
        hn::RebindMask(di, checker),
        hn::Add(offset, hn::IfThenZeroElse(hn::RebindMask(di, same), hn::Set(di, 3))));
    out_r = hn::IfThenElse(checker, hn::GatherIndex(d, t.data.data(), at), out_r);
    out_g = hn::IfThenElse(checker, hn::GatherIndex(d, t.data.data(), hn::Add(at, hn::Set(di, 1))),
                           out_g);
    out_b = hn::IfThenElse(checker, hn::GatherIndex(d, t.data.data(), hn::Add(at, hn::Set(di, 2))),
                           out_b);
  }
  if (!hn::AllFalse(d, hn::Or(face, vertex))) {
    // The row's triangle: prim − first < count as unsigned (a sphere hit, bit 31, never is).
    const VTI first = GatherI(t.width, row), count = GatherI(t.height, row);
    const VTI tri = hn::Sub(prim, first);
    const auto in_range = hn::RebindMask(d, hn::Lt(hn::BitCast(du, tri), hn::BitCast(du, count)));
    const auto not_sphere = hn::RebindMask(
        d, hn::Eq(hn::And(prim, hn::Set(di, int32_t(kSphereHitBit))), hn::Zero(di)));
    const MT inside = hn::And(in_range, not_sphere);
    const VTI tri_ok = hn::IfThenElseZero(hn::RebindMask(di, inside), tri);
    const MT face_ok = hn::And(face, inside), vertex_ok = hn::And(vertex, inside);
    if (!hn::AllFalse(d, face_ok)) {
      const VTI at = hn::Add(offset, hn::Mul(tri_ok, hn::Set(di, 3)));
      const VTI at_ok = hn::IfThenElseZero(hn::RebindMask(di, face_ok), at);
      for (int k = 0; k < 3; ++k) {
        const VT c = hn::GatherIndex(d, t.data.data(), hn::Add(at_ok, hn::Set(di, k)));
        VT& o = k == 0 ? out_r : (k == 1 ? out_g : out_b);
        o = hn::IfThenElse(face_ok, c, o);
      }
    }
    if (!hn::AllFalse(d, vertex_ok)) {
      const VTI at = hn::IfThenElseZero(
          hn::RebindMask(di, vertex_ok),
          hn::Add(offset, hn::Mul(tri_ok, hn::Set(di, int32_t(kVertexAttributeFloats)))));
      const auto f = [&](int k) {
        return hn::GatherIndex(d, t.data.data(), hn::Add(at, hn::Set(di, k)));
      };
      const VT dx = hn::Sub(px, f(0)), dy = hn::Sub(py, f(1)), dz = hn::Sub(pz, f(2));
      for (int k = 0; k < 3; ++k) {
        const int a = 3 + 4 * k;
        const VT c = hn::Add(
            f(a), hn::Add(hn::Add(RMul(d, f(a + 1), dx), RMul(d, f(a + 2), dy)), RMul(d, f(a + 3), dz)));
        VT& o = k == 0 ? out_r : (k == 1 ? out_g : out_b);
        o = hn::IfThenElse(vertex_ok, c, o);
      }
    }
  }
  *r = out_r, *g = out_g, *b = out_b;
}

/// simd::EvalTextureBatch: EvalTexture8 over n rows, a partial last vector on padded copies.
inline void EvalTextureBatchKernel(const TextureTable& t, const uint32_t* id,
                                   const TexturePointArrays& at, size_t n, float* r, float* g,
                                   float* b) {
  using namespace texture8;
  const DT d;
  const DTI di;
  const size_t lanes = hn::Lanes(d);
  const auto block = [&](const uint32_t* ids, const float* u, const float* v, const float* x,
                         const float* y, const float* z, const uint32_t* prim, float* ro,
                         float* go, float* bo) HWY_ATTR {
    const VTI idv = hn::LoadU(di, reinterpret_cast<const int32_t*>(ids));
    const MT active = hn::RebindMask(d, hn::Ne(idv, hn::Set(di, int32_t(kNoTexture))));
    VT vr, vg, vb;
    EvalTexture8(t, idv, hn::LoadU(d, u), hn::LoadU(d, v), hn::LoadU(d, x), hn::LoadU(d, y),
                 hn::LoadU(d, z), hn::LoadU(di, reinterpret_cast<const int32_t*>(prim)), active,
                 &vr, &vg, &vb);
    hn::StoreU(vr, d, ro), hn::StoreU(vg, d, go), hn::StoreU(vb, d, bo);
  };
  size_t i = 0;
  for (; i + lanes <= n; i += lanes)
    block(id + i, at.u + i, at.v + i, at.p_x + i, at.p_y + i, at.p_z + i, at.prim + i, r + i,
          g + i, b + i);
  if (i == n) return;
  HWY_ALIGN uint32_t tid[8], tprim[8];
  HWY_ALIGN float tu[8], tv[8], tx[8], ty[8], tz[8], tr[8], tg[8], tb[8];
  for (size_t j = 0; j < 8; ++j) {
    const size_t s = i + std::min(j, n - i - 1);
    tid[j] = id[s], tprim[j] = at.prim[s];
    tu[j] = at.u[s], tv[j] = at.v[s], tx[j] = at.p_x[s], ty[j] = at.p_y[s], tz[j] = at.p_z[s];
  }
  block(tid, tu, tv, tx, ty, tz, tprim, tr, tg, tb);
  for (size_t j = 0; i + j < n; ++j) r[i + j] = tr[j], g[i + j] = tg[j], b[i + j] = tb[j];
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TEXTURE8_INL_H_
