// Per-target SIMD kernels of simd/wavefront/bsdf8.h (re-included once per Highway target).
// Each kernel mirrors its scalar oracle in engine/bsdf/ operation by operation, so that the two
// differ only by the rounding of transcendentals (hwy/contrib/math vs libm) and by FMA
// contraction outside the cancelling sums (those use RoundedMul below).

#if defined(PTLAB_SIMD_SHADE8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_SHADE8_INL_H_
#undef PTLAB_SIMD_SHADE8_INL_H_
#else
#define PTLAB_SIMD_SHADE8_INL_H_
#endif

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/bsdf/beckmann.h"
#include "engine/bsdf/bsdf.h"  // IsDeltaMaterial, MixesDeltaLobes
#include "engine/bsdf/fresnel.h"
#include "engine/scene/material_tables.h"
#include "engine/wavefront/bsdf.h"
#include "hwy/contrib/math/math-inl.h"
#include "hwy/highway.h"
#include "simd/texture/texture8-inl.h"
#include "simd/wavefront/lanes8-inl.h"  // D8, V8, M8, AllFinite3

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// ------------------------------------------------------------------------------ clamps

/// ClampBeckmannAlpha.
HWY_INLINE V8 ClampAlpha(D8 d, V8 alpha) {
  const V8 lo = hn::Set(d, kBeckmannMinAlpha);
  return hn::IfThenElse(hn::Gt(alpha, lo), hn::Min(alpha, hn::Set(d, kBeckmannMaxAlpha)), lo);
}
/// ClampSample.
HWY_INLINE V8 ClampUnit(D8 d, V8 u) {
  return hn::IfThenElseZero(hn::Gt(u, hn::Zero(d)), hn::Min(u, hn::Set(d, kOneMinusEpsilon)));
}
/// ClampCosine: |c| clamped to [0, 1], NaN → 1.
HWY_INLINE V8 ClampCos(D8 d, V8 c) {
  const V8 a = hn::Abs(c), one = hn::Set(d, 1.0f);
  return hn::IfThenElse(hn::Lt(a, one), a, one);
}
/// ClampRelativeIor.
HWY_INLINE V8 ClampRelIor(D8 d, V8 eta) {
  const V8 lo = hn::Set(d, kMinRelativeIor);
  return hn::IfThenElse(hn::Gt(eta, lo), hn::Min(eta, hn::Set(d, kMaxRelativeIor)), lo);
}
/// ClampConductorIor.
HWY_INLINE V8 ClampCondIor(D8 d, V8 v) {
  return hn::IfThenElseZero(hn::Gt(v, hn::Zero(d)), hn::Min(v, hn::Set(d, kMaxConductorIor)));
}
/// a·b rounded to float before any add: the bitwise OR with +0.0 is opaque to the compiler, so
/// it cannot contract the product and a following add/sub into one FMA. Used for the products
/// in sums that cancel (η² − sin²θ, wo·H, …), so that every target rounds them exactly as the
/// scalar oracle does (engine/ is compiled without FMA).
HWY_INLINE V8 RoundedMul(D8 d, V8 a, V8 b) { return hn::Or(hn::Mul(a, b), hn::Zero(d)); }

/// Dot product with RoundedMul terms, summed in the order of Dot() in engine/core/vec.h.
HWY_INLINE V8 RoundedDot(D8 d, V8 ax, V8 ay, V8 az, V8 bx, V8 by, V8 bz) {
  return hn::Add(hn::Add(RoundedMul(d, ax, bx), RoundedMul(d, ay, by)), RoundedMul(d, az, bz));
}

// ------------------------------------------------------------------------------ Fresnel

/// FresnelDielectric (fresnel.h); eta is clamped here. Returns F, sets *cos_t.
HWY_INLINE V8 FresnelDielectric(D8 d, V8 cos_i, V8 eta, V8* cos_t) {
  const V8 one = hn::Set(d, 1.0f);
  eta = ClampRelIor(d, eta);
  eta = hn::IfThenElse(hn::Lt(cos_i, hn::Zero(d)), hn::Div(one, eta), eta);
  const V8 c = ClampCos(d, cos_i);
  const V8 p = hn::Add(RoundedMul(d, hn::Sub(eta, one), hn::Add(eta, one)), RoundedMul(d, c, c));
  const M8 refracts = hn::Gt(p, hn::Zero(d));
  const V8 eta_ct = hn::Sqrt(hn::IfThenElseZero(refracts, p));
  const V8 ct_over_eta = hn::Div(eta_ct, hn::Mul(eta, eta));
  const V8 rs = hn::Div(hn::Sub(c, eta_ct), hn::Add(c, eta_ct));
  const V8 rp = hn::Div(hn::Sub(c, ct_over_eta), hn::Add(c, ct_over_eta));
  const V8 f = hn::Mul(hn::Set(d, 0.5f), hn::Add(hn::Mul(rs, rs), hn::Mul(rp, rp)));
  *cos_t = hn::IfThenElseZero(refracts, hn::Div(eta_ct, eta));
  return hn::IfThenElse(refracts, f, one);
}

/// FresnelSchlick (fresnel.h).
HWY_INLINE V8 FresnelSchlick(D8 d, V8 cos_i, V8 eta) {
  const V8 one = hn::Set(d, 1.0f);
  eta = ClampRelIor(d, eta);
  const V8 r = hn::Div(hn::Sub(eta, one), hn::Add(eta, one));
  const V8 r0 = hn::Mul(r, r);
  const V8 m = hn::Sub(one, ClampCos(d, cos_i));
  const V8 m2 = hn::Mul(m, m);
  return hn::Add(r0, hn::Mul(hn::Sub(one, r0), hn::Mul(hn::Mul(m2, m2), m)));
}

/// FresnelConductor (fresnel.h), one channel.
HWY_INLINE V8 FresnelConductor(D8 d, V8 cos_i, V8 eta, V8 k) {
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f), half = hn::Set(d, 0.5f);
  eta = ClampCondIor(d, eta);
  k = ClampCondIor(d, k);
  const V8 c = ClampCos(d, cos_i);
  const V8 s2 = RoundedMul(d, hn::Sub(one, c), hn::Add(one, c));
  const V8 t = hn::Sub(RoundedMul(d, hn::Sub(eta, k), hn::Add(eta, k)), s2);
  const V8 ek = hn::Mul(eta, k);
  const V8 abs_z = hn::Sqrt(hn::Add(hn::Mul(t, t), hn::Mul(hn::Set(d, 4.0f), hn::Mul(ek, ek))));
  // The oracle's non-cancelling root (a for t > 0, else b) and the quotient for the other.
  const M8 pos = hn::Gt(t, zero);
  const V8 root = hn::Sqrt(hn::Mul(half, hn::Add(abs_z, hn::Abs(t))));
  const V8 other = hn::Div(ek, hn::Max(root, hn::Set(d, 1e-20f)));
  const V8 a = hn::IfThenElse(pos, root, other);
  const V8 b = hn::IfThenElse(pos, other, root);
  const V8 b2 = hn::Mul(b, b);
  const V8 am = hn::Sub(a, c), ap = hn::Add(a, c);
  const V8 num_s = hn::Add(hn::Mul(am, am), b2), den_s = hn::Add(hn::Mul(ap, ap), b2);
  const V8 ac = RoundedMul(d, a, c), bc = hn::Mul(b, c);
  const V8 pm = hn::Sub(ac, s2), pp = hn::Add(ac, s2);
  const V8 bc2 = hn::Mul(bc, bc);
  const V8 num_p = hn::Add(hn::Mul(pm, pm), bc2), den_p = hn::Add(hn::Mul(pp, pp), bc2);
  // (Rs + Rp)/2 as the oracle's one quotient of terms + 1e-30.
  const V8 tiny = hn::Set(d, 1e-30f);
  const V8 ns = hn::Add(num_s, tiny), ds = hn::Add(den_s, tiny);
  const V8 np = hn::Add(num_p, tiny), dp = hn::Add(den_p, tiny);
  return hn::Div(hn::Mul(hn::Mul(half, ns), hn::Add(dp, np)), hn::Mul(ds, dp));
}

// ------------------------------------------------------------------------------ Beckmann

/// BeckmannD (beckmann.h) for the unnormalised half vector h; alpha already clamped.
HWY_INLINE V8 BeckmannD(D8 d, V8 alpha, V8 hx, V8 hy, V8 hz) {
  const V8 a2 = hn::Mul(alpha, alpha);
  // Rounded products: exp(−s2/(z2 α²)) amplifies an ulp of its argument up to ~100 times.
  const V8 s2 = hn::Add(RoundedMul(d, hx, hx), RoundedMul(d, hy, hy));
  const V8 z2 = RoundedMul(d, hz, hz);
  // hwy::Exp converts its argument to int before it range-checks it: −∞ (h.z = 0) and NaN
  // (h = 0) would be undefined behaviour on the EMU128 target (UBSan found it). Below −104
  // Exp is 0 anyway, which is what the oracle's exp gives there (NaN lanes end at 0 below).
  const V8 arg = hn::Div(hn::Neg(s2), hn::Mul(z2, a2)), low = hn::Set(d, -200.0f);
  const V8 e = hn::Exp(d, hn::IfThenElse(hn::Ge(arg, low), arg, low));
  const V8 cos2 = hn::Div(z2, hn::Add(s2, z2));
  const V8 dv = hn::Div(e, hn::Mul(hn::Mul(hn::Set(d, kPi), a2), hn::Mul(cos2, cos2)));
  const V8 zero = hn::Zero(d);
  return hn::IfThenElseZero(hn::And(hn::Gt(hz, zero), hn::Gt(e, zero)), dv);
}

/// BeckmannEvalPdf (beckmann.h) given dv = BeckmannD(alpha, h) of h = wo + wi (the sum as
/// BeckmannEvalPdf forms it). Returns D, sets *pdf.
HWY_INLINE V8 BeckmannEvalPdfOfD(D8 d, V8 dv, V8 ox, V8 oy, V8 oz, V8 iz, V8 hx, V8 hy, V8 hz,
                                 V8* pdf) {
  const V8 zero = hn::Zero(d);
  const V8 wo_h = RoundedDot(d, ox, oy, oz, hx, hy, hz);
  const V8 p = hn::Div(hn::Mul(dv, hz), hn::Mul(hn::Set(d, 4.0f), wo_h));
  const M8 ok = hn::And(hn::And(hn::And(hn::Gt(oz, zero), hn::Gt(iz, zero)), hn::Gt(wo_h, zero)),
                        hn::And(hn::Gt(dv, zero), hn::And(hn::IsFinite(dv), hn::IsFinite(p))));
  *pdf = hn::IfThenElseZero(ok, p);
  return hn::IfThenElseZero(ok, dv);
}

/// BeckmannEvalPdf (beckmann.h); alpha already clamped. Returns D, sets *pdf.
HWY_INLINE V8 BeckmannEvalPdf(D8 d, V8 alpha, V8 ox, V8 oy, V8 oz, V8 ix, V8 iy, V8 iz, V8* pdf) {
  const V8 hx = hn::Add(ox, ix), hy = hn::Add(oy, iy), hz = hn::Add(oz, iz);
  return BeckmannEvalPdfOfD(d, BeckmannD(d, alpha, hx, hy, hz), ox, oy, oz, iz, hx, hy, hz, pdf);
}

/// BeckmannG1 (beckmann.h); alpha already clamped, v.z > 0 assumed by the caller's mask.
HWY_INLINE V8 BeckmannG1(D8 d, V8 alpha, V8 vx, V8 vy, V8 vz) {
  const V8 b = hn::Div(vz, hn::Mul(alpha, hn::Sqrt(hn::Add(hn::Mul(vx, vx), hn::Mul(vy, vy)))));
  const V8 num = hn::Mul(b, hn::Add(hn::Set(d, 3.535f), hn::Mul(hn::Set(d, 2.181f), b)));
  const V8 den = hn::Add(hn::Set(d, 1.0f),
                         hn::Mul(b, hn::Add(hn::Set(d, 2.276f), hn::Mul(hn::Set(d, 2.577f), b))));
  return hn::IfThenElse(hn::Lt(b, hn::Set(d, 1.6f)), hn::Div(num, den), hn::Set(d, 1.0f));
}

/// BeckmannG1OverCos (beckmann.h); alpha already clamped.
HWY_INLINE V8 BeckmannG1OverCos(D8 d, V8 alpha, V8 vx, V8 vy, V8 vz) {
  const V8 as = hn::Mul(alpha, hn::Sqrt(hn::Add(hn::Mul(vx, vx), hn::Mul(vy, vy))));
  const V8 b = hn::Div(vz, as);
  const V8 num = hn::Add(hn::Set(d, 3.535f), hn::Mul(hn::Set(d, 2.181f), b));
  const V8 den = hn::Add(hn::Set(d, 1.0f),
                         hn::Mul(b, hn::Add(hn::Set(d, 2.276f), hn::Mul(hn::Set(d, 2.577f), b))));
  return hn::IfThenElse(hn::Lt(b, hn::Set(d, 1.6f)), hn::Div(num, hn::Mul(den, as)),
                        hn::Div(hn::Set(d, 1.0f), vz));
}

/// SampleBeckmannNormal (beckmann.h); alpha already clamped.
HWY_INLINE void SampleBeckmannNormal(D8 d, V8 alpha, V8 ux, V8 uy, V8* hx, V8* hy, V8* hz) {
  const V8 u1 = ClampUnit(d, ux), u2 = ClampUnit(d, uy);
  const V8 tan2 = hn::Mul(hn::Neg(hn::Mul(alpha, alpha)), hn::Log1p(d, hn::Neg(u1)));
  const V8 one = hn::Set(d, 1.0f);
  const V8 cos_t = hn::Div(one, hn::Sqrt(hn::Add(one, tan2)));
  const V8 sin_t = hn::Mul(hn::Sqrt(tan2), cos_t);
  const V8 phi = hn::Mul(hn::Set(d, 2.0f * kPi), u2);
  *hx = hn::Mul(sin_t, hn::Cos(d, phi));
  *hy = hn::Mul(sin_t, hn::Sin(d, phi));
  *hz = cos_t;
}

/// ReflectAbout (beckmann.h).
HWY_INLINE void Reflect(D8 d, V8 ox, V8 oy, V8 oz, V8 hx, V8 hy, V8 hz, V8* rx, V8* ry, V8* rz) {
  const V8 dot = hn::Add(hn::Add(hn::Mul(ox, hx), hn::Mul(oy, hy)), hn::Mul(oz, hz));
  const V8 dot2 = hn::Mul(hn::Set(d, 2.0f), dot);
  *rx = hn::Sub(hn::Mul(dot2, hx), ox);
  *ry = hn::Sub(hn::Mul(dot2, hy), oy);
  *rz = hn::Sub(hn::Mul(dot2, hz), oz);
}

/// SampleCosineHemisphere (engine/sampling/warp.h: Malley's method on the concentric disk).
HWY_INLINE void SampleCosineHemisphere(D8 d, V8 ux, V8 uy, V8* wx, V8* wy, V8* wz) {
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f), two = hn::Set(d, 2.0f);
  const V8 ox = hn::Sub(hn::Mul(two, ux), one), oy = hn::Sub(hn::Mul(two, uy), one);
  const M8 at_center = hn::And(hn::Eq(ox, zero), hn::Eq(oy, zero));
  const M8 x_major = hn::Gt(hn::Abs(ox), hn::Abs(oy));
  const V8 quarter_pi = hn::Set(d, kPi / 4);
  const V8 r = hn::IfThenElse(x_major, ox, oy);
  // At the centre θ is 0/0: zeroed, because hwy::Cos/Sin convert NaN to int (undefined on
  // EMU128; UBSan found it). Those lanes are 0 below either way.
  const V8 theta = hn::IfThenZeroElse(
      at_center,
      hn::IfThenElse(x_major, hn::Mul(quarter_pi, hn::Div(oy, ox)),
                     hn::Sub(hn::Set(d, kPi / 2), hn::Mul(quarter_pi, hn::Div(ox, oy)))));
  const V8 dx = hn::IfThenZeroElse(at_center, hn::Mul(r, hn::Cos(d, theta)));
  const V8 dy = hn::IfThenZeroElse(at_center, hn::Mul(r, hn::Sin(d, theta)));
  *wx = dx;
  *wy = dy;
  *wz = hn::Sqrt(hn::Max(zero, hn::Sub(hn::Sub(one, hn::Mul(dx, dx)), hn::Mul(dy, dy))));
}

// ------------------------------------------------------------------------------ batch driver

/// Plain pointers for one block of rows: `index` (may be null), kIn float inputs and kOut float
/// outputs (null entries are neither read nor written).
template <size_t kIn, size_t kOut>
struct BlockIo {
  const uint32_t* index = nullptr;
  const uint32_t* entry = nullptr;  // the shading step's ShadeInputs::texture.entry (or null)
  const float* in[kIn] = {};
  float* out[kOut] = {};
};

/// Calls block(io, i) for i = 0, N, 2N, … with N = Lanes(D8) ≤ 8; a partial last block runs
/// on padded copies (padding repeats the last row, so it is always a valid input).
template <size_t kIn, size_t kOut, class Block>
HWY_INLINE void ForEachBlock(const BlockIo<kIn, kOut>& io, size_t n, const Block& block) {
  const D8 d;
  const size_t lanes = hn::Lanes(d);
  size_t i = 0;
  for (; i + lanes <= n; i += lanes) block(io, i);
  if (i == n) return;
  const size_t rem = n - i;
  HWY_ALIGN uint32_t t_index[8], t_entry[8];
  HWY_ALIGN float t_in[kIn][8];
  HWY_ALIGN float t_out[kOut][8];
  BlockIo<kIn, kOut> t;
  for (size_t j = 0; j < 8; ++j) {
    const size_t src = i + std::min(j, rem - 1);
    if (io.index != nullptr) t_index[j] = io.index[src];
    if (io.entry != nullptr) t_entry[j] = io.entry[src];
    for (size_t c = 0; c < kIn; ++c)
      if (io.in[c] != nullptr) t_in[c][j] = io.in[c][src];
  }
  t.index = io.index != nullptr ? t_index : nullptr;
  t.entry = io.entry != nullptr ? t_entry : nullptr;
  for (size_t c = 0; c < kIn; ++c) t.in[c] = io.in[c] != nullptr ? t_in[c] : nullptr;
  for (size_t c = 0; c < kOut; ++c) t.out[c] = io.out[c] != nullptr ? t_out[c] : nullptr;
  block(t, 0);
  for (size_t c = 0; c < kOut; ++c) {
    if (io.out[c] == nullptr) continue;
    for (size_t j = 0; j < rem; ++j) io.out[c][i + j] = t_out[c][j];
  }
}

/// ForEachBlock over the rows grouped by a key of each row (0 .. kGroupKeys - 1, counting sort,
/// stable within a key): a kernel whose lanes branch on the key (AllTrue / AllFalse) then runs
/// one branch per block, not all of them for blocks that mix keys. The inputs are copied in the
/// grouped order and the outputs copied back; every lane's result depends on its own inputs
/// only, so each row's outputs are the ones ForEachBlock gives it. Batches whose blocks seldom
/// mix keys (at most one in four) go to ForEachBlock as they are.
inline constexpr uint32_t kGroupKeys = 4;
template <size_t kIn, size_t kOut, class Key, class Block>
HWY_NOINLINE void ForEachBlockGrouped(const BlockIo<kIn, kOut>& io, size_t n, const Key& key,
                                      const Block& block) {
  if (io.index == nullptr) return ForEachBlock(io, n, block);
  size_t mixed = 0, count[kGroupKeys] = {};
  thread_local std::vector<uint32_t> keys;
  keys.resize(n);
  // Counted in registers: `++count[key]` would be a load-add-store chain through memory when
  // consecutive rows share a key (the usual case), about five cycles a row.
  static_assert(kGroupKeys == 4);
  size_t c0 = 0, c1 = 0, c2 = 0;
  for (size_t r = 0; r < n; ++r) {
    const uint32_t k = keys[r] = key(r);
    c0 += k == 0, c1 += k == 1, c2 += k == 2;
  }
  count[0] = c0, count[1] = c1, count[2] = c2, count[3] = n - c0 - c1 - c2;
  if (n == 0 || count[keys[0]] == n) return ForEachBlock(io, n, block);  // one key: none mixes
  for (size_t i = 0; i < n; i += 8) {
    const size_t end = std::min(n, i + 8);
    for (size_t r = i + 1; r < end; ++r) {
      if (keys[r] != keys[i]) {
        ++mixed;
        break;
      }
    }
  }
  if (mixed * 4 <= (n + 7) / 8) return ForEachBlock(io, n, block);
  // order[g] = the row at grouped position g.
  thread_local std::vector<uint32_t> order, t_index, t_entry;
  thread_local std::vector<float> t_in, t_out;
  size_t start[kGroupKeys] = {};
  for (uint32_t k = 1; k < kGroupKeys; ++k) start[k] = start[k - 1] + count[k - 1];
  order.resize(n);
  for (size_t r = 0; r < n; ++r) order[start[keys[r]]++] = uint32_t(r);
  BlockIo<kIn, kOut> t;
  t_index.resize(n);
  for (size_t g = 0; g < n; ++g) t_index[g] = io.index[order[g]];
  t.index = t_index.data();
  if (io.entry != nullptr) {
    t_entry.resize(n);
    for (size_t g = 0; g < n; ++g) t_entry[g] = io.entry[order[g]];
    t.entry = t_entry.data();
  }
  t_in.resize(kIn * n), t_out.resize(kOut * n);
  for (size_t c = 0; c < kIn; ++c) {
    if (io.in[c] == nullptr) continue;
    float* col = t_in.data() + c * n;
    for (size_t g = 0; g < n; ++g) col[g] = io.in[c][order[g]];
    t.in[c] = col;
  }
  for (size_t c = 0; c < kOut; ++c)
    t.out[c] = io.out[c] != nullptr ? t_out.data() + c * n : nullptr;
  ForEachBlock(t, n, block);
  for (size_t c = 0; c < kOut; ++c) {
    if (io.out[c] == nullptr) continue;
    const float* col = t.out[c];
    for (size_t g = 0; g < n; ++g) io.out[c][order[g]] = col[g];
  }
}

HWY_INLINE V8 Load(D8 d, const float* p, size_t i) { return hn::LoadU(d, p + i); }
HWY_INLINE void Store(D8 d, V8 v, float* p, size_t i) { hn::StoreU(v, d, p + i); }

/// Gathers column[index[i + lane]].
HWY_INLINE V8 Gather(D8 d, const AlignedVector<float>& column, const uint32_t* index, size_t i) {
  const hn::RebindToSigned<D8> di;
  const auto idx = hn::LoadU(di, reinterpret_cast<const int32_t*>(index + i));
  return hn::GatherIndex(d, column.data(), idx);
}

// ------------------------------------------------------------------------------ shade step

// Column order of the shade step's BlockIo (see ShadeInputs / ShadeOutputs).
enum ShadeIn { kWoX, kWoY, kWoZ, kWlX, kWlY, kWlZ, kULobe, kUX, kUY, kShadeInCount };
// kDelta (matB): ShadeOutputs::delta, written only by the kernels of tags that MixesDeltaLobes.
enum ShadeOut {
  kFR,
  kFG,
  kFB,
  kPdfL,
  kWiX,
  kWiY,
  kWiZ,
  kWR,
  kWG,
  kWB,
  kPdf,
  kEta,
  kDelta,
  kShadeOutCount
};
using ShadeIo = BlockIo<kShadeInCount, kShadeOutCount>;

/// Column c of the shade step's inputs, rows [i, i + Lanes(d)).
HWY_INLINE V8 In(D8 d, const ShadeIo& b, ShadeIn c, size_t i) { return Load(d, b.in[c], i); }

HWY_INLINE void StoreEval(D8 d, const ShadeIo& b, size_t i, V8 fr, V8 fg, V8 fb, V8 pdf_l) {
  Store(d, fr, b.out[kFR], i), Store(d, fg, b.out[kFG], i), Store(d, fb, b.out[kFB], i);
  Store(d, pdf_l, b.out[kPdfL], i);
}

/// Stores a sample; rows outside `ok` get wi = 0, weight = 0, pdf = 0, eta = 1.
HWY_INLINE void StoreSample(D8 d, const ShadeIo& b, size_t i, M8 ok, V8 ix, V8 iy, V8 iz, V8 wr,
                            V8 wg, V8 wb, V8 pdf, V8 eta) {
  Store(d, hn::IfThenElseZero(ok, ix), b.out[kWiX], i);
  Store(d, hn::IfThenElseZero(ok, iy), b.out[kWiY], i);
  Store(d, hn::IfThenElseZero(ok, iz), b.out[kWiZ], i);
  Store(d, hn::IfThenElseZero(ok, wr), b.out[kWR], i);
  Store(d, hn::IfThenElseZero(ok, wg), b.out[kWG], i);
  Store(d, hn::IfThenElseZero(ok, wb), b.out[kWB], i);
  Store(d, hn::IfThenElseZero(ok, pdf), b.out[kPdf], i);
  Store(d, hn::IfThenElse(ok, eta, hn::Set(d, 1.0f)), b.out[kEta], i);
}

/// CosineHemispherePdf (warp.h) with the one-sided test of DiffusePdf.
HWY_INLINE V8 CosinePdf(D8 d, V8 oz, V8 iz) {
  const V8 zero = hn::Zero(d);
  return hn::IfThenElseZero(hn::And(hn::Gt(oz, zero), hn::Gt(iz, zero)),
                            hn::Mul(iz, hn::Set(d, kInvPi)));
}

/// DiffuseEval / DiffusePdf / DiffuseSample (engine/bsdf/diffuse.h).
/// A textured color parameter (TexturedColor, engine/texture/texture_site.h) of rows [i, i +
/// Lanes): the rows whose id in `texture` (a texture-id column, gathered by b.index) is not
/// kNoTexture get their texture at the shading point its[b.entry[row]] (uv, p, prim gathered),
/// each channel clamped to ≥ 0 as std::max(c, 0) does; the others keep (r, g, b).
/// mask: with `raw`, the channels are not clamped and *textured (when non-null) receives the
/// rows that have a texture (TexturedFloat8 takes the luminance of the raw colour, as the
/// oracle's TexturedFloat does).
HWY_INLINE void TexturedColor8(D8 d, const ShadeInputs::Textures& tex,
                               const AlignedVector<uint32_t>& texture, const ShadeIo& b, size_t i,
                               V8* r, V8* g, V8* b_out, bool raw = false, M8* textured = nullptr) {
  const hn::RebindToSigned<D8> di;
  const auto id = hn::GatherIndex(di, reinterpret_cast<const int32_t*>(texture.data()),
                                  hn::LoadU(di, reinterpret_cast<const int32_t*>(b.index + i)));
  const M8 has = hn::RebindMask(d, hn::Ne(id, hn::Set(di, int32_t(kNoTexture))));
  if (textured != nullptr) *textured = has;
  if (hn::AllFalse(d, has)) return;
  // The shading points' fields, SurfaceInteraction as 4-byte words.
  constexpr int32_t kWords = int32_t(sizeof(SurfaceInteraction) / 4);
  constexpr int32_t kP = int32_t(offsetof(SurfaceInteraction, p) / 4),
                    kUv = int32_t(offsetof(SurfaceInteraction, uv) / 4),
                    kPrim = int32_t(offsetof(SurfaceInteraction, prim) / 4);
  const auto base =
      hn::Mul(hn::LoadU(di, reinterpret_cast<const int32_t*>(b.entry + i)), hn::Set(di, kWords));
  const float* its = reinterpret_cast<const float*>(tex.its);
  const auto at = [&](int32_t word) { return hn::Add(base, hn::Set(di, word)); };
  const V8 u = hn::GatherIndex(d, its, at(kUv)), v = hn::GatherIndex(d, its, at(kUv + 1));
  const V8 px = hn::GatherIndex(d, its, at(kP)), py = hn::GatherIndex(d, its, at(kP + 1)),
           pz = hn::GatherIndex(d, its, at(kP + 2));
  const auto prim = hn::GatherIndex(di, reinterpret_cast<const int32_t*>(tex.its), at(kPrim));
  V8 tr, tg, tb;
  EvalTexture8(*tex.textures, id, u, v, px, py, pz, prim, has, &tr, &tg, &tb);
  const V8 zero = hn::Zero(d);
  if (raw) {
    *r = hn::IfThenElse(has, tr, *r), *g = hn::IfThenElse(has, tg, *g);
    *b_out = hn::IfThenElse(has, tb, *b_out);
    return;
  }
  *r = hn::IfThenElse(has, hn::IfThenZeroElse(hn::Lt(tr, zero), tr), *r);
  *g = hn::IfThenElse(has, hn::IfThenZeroElse(hn::Lt(tg, zero), tg), *g);
  *b_out = hn::IfThenElse(has, hn::IfThenZeroElse(hn::Lt(tb, zero), tb), *b_out);
}

/// A textured scalar parameter (TexturedFloat, engine/texture/texture_site.h): the rows with a
/// texture get the luminance of its color at their shading point, products rounded before the
/// sums as the oracle's Luminance is, clamped to ≥ 0; the others keep *value.
HWY_INLINE void TexturedFloat8(D8 d, const ShadeInputs::Textures& tex,
                               const AlignedVector<uint32_t>& texture, const ShadeIo& b, size_t i,
                               V8* value) {
  // mask: the luminance of the raw colour (channels may be < 0), as the oracle's TexturedFloat.
  V8 r = hn::Zero(d), g = r, bl = r;
  M8 has;
  TexturedColor8(d, tex, texture, b, i, &r, &g, &bl, /*raw=*/true, &has);
  const V8 lum =
      hn::Add(hn::Add(hn::Mul(hn::Set(d, 0.212671f), r), hn::Mul(hn::Set(d, 0.715160f), g)),
              hn::Mul(hn::Set(d, 0.072169f), bl));
  *value = hn::IfThenElse(has, hn::Max(lum, hn::Zero(d)), *value);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();
// The first models and the batch kernels of the Beckmann and Fresnel entry points, each in its
// own -inl file (they use the helpers above).
#include "simd/wavefront/beckmann_fresnel8-inl.h"
#include "simd/wavefront/conductor8-inl.h"
#include "simd/wavefront/dielectric8-inl.h"
#include "simd/wavefront/diffuse8-inl.h"
#include "simd/wavefront/mirror8-inl.h"
#include "simd/wavefront/rough_plastic8-inl.h"
// matB: the models in their own files (they use the helpers above).
#include "simd/wavefront/blend8-inl.h"
#include "simd/wavefront/perturbed_frame8-inl.h"  // normal
#include "simd/wavefront/plastic8-inl.h"
#include "simd/wavefront/thin_dielectric8-inl.h"
#include "simd/wavefront/two_sided8-inl.h"
// matA: the Mitsuba microfacet models, each in its own -inl file.
#include "simd/wavefront/rough_conductor8-inl.h"
#include "simd/wavefront/rough_dielectric8-inl.h"
// principled: principled and principledthin.
#include "simd/wavefront/principled8-inl.h"
// mask: Mitsuba's `mask`.
#include "simd/wavefront/mask8-inl.h"
HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

/// ShadeBatch for one tag, every row one-sided (ShadeBatchKernel applies the two-sided flags).
inline void ShadeBatchKernelOneSided(const MaterialTables& m, MaterialTag tag,
                                     const uint32_t* material_index, size_t n,
                                     const ShadeInputs& in, const ShadeOutputs& out) {
  const bool eval = in.wl.x != nullptr, sample = in.u_lobe != nullptr;
  ShadeIo io;
  io.index = material_index;
  if (in.texture.textures != nullptr) io.entry = in.texture.entry;
  io.in[kWoX] = in.wo.x, io.in[kWoY] = in.wo.y, io.in[kWoZ] = in.wo.z;
  if (eval) io.in[kWlX] = in.wl.x, io.in[kWlY] = in.wl.y, io.in[kWlZ] = in.wl.z;
  io.in[kULobe] = in.u_lobe, io.in[kUX] = in.u_x, io.in[kUY] = in.u_y;
  if (eval) {
    io.out[kFR] = out.f.r, io.out[kFG] = out.f.g, io.out[kFB] = out.f.b;
    io.out[kPdfL] = out.pdf_l;
  }
  if (sample) {
    io.out[kWiX] = out.wi.x, io.out[kWiY] = out.wi.y, io.out[kWiZ] = out.wi.z;
    io.out[kWR] = out.weight.r, io.out[kWG] = out.weight.g, io.out[kWB] = out.weight.b;
    io.out[kPdf] = out.pdf, io.out[kEta] = out.eta;
    // Only the kernels of tags that mix lobes write it (ForEachBlock's partial last block
    // copies back every column it is given; ShadeBatchKernel fills it for the others).
    if (MixesDeltaLobes(tag)) io.out[kDelta] = out.delta;
  }
  switch (tag) {
    case MaterialTag::kDiffuse:
      return ShadeDiffuse(m.diffuse, in.texture, io, n, eval, sample);
    case MaterialTag::kMirror:
      return ShadeMirror(m.mirror, io, n, eval, sample);
    case MaterialTag::kDielectric:
      return ShadeDielectric(m.dielectric, io, n, eval, sample);
    case MaterialTag::kConductor:
      if (m.conductor.microfacet())
        return ShadeRoughConductor(m.conductor, in.texture, io, n, eval, sample);  // mask: tex
      return ShadeConductor(m.conductor, io, n, eval, sample);
    case MaterialTag::kRoughDielectric:  // matA
      return ShadeRoughDielectric(m.rough_dielectric, in.texture, io, n, eval, sample);
    case MaterialTag::kRoughPlastic:
      return ShadeRoughPlastic(m.rough_plastic, io, n, eval, sample);
    // matB
    case MaterialTag::kPlastic:
      return ShadePlasticRows(m, material_index, n, in, out, io, eval, sample);
    case MaterialTag::kThinDielectric:
      return ShadeThinDielectric(m.thin_dielectric, io, n, eval, sample);
    case MaterialTag::kBlend:
      return ShadeBlend(m, material_index, n, in, out);
    case MaterialTag::kPrincipled:  // principled
      return ShadePrincipled(m.principled, in.texture, io, n, eval, sample);
    case MaterialTag::kPrincipledThin:
      return ShadePrincipledThin(m.principled_thin, in.texture, io, n, eval, sample);
    case MaterialTag::kMask:  // mask
      return ShadeMask(m, material_index, n, in, out);
  }
}

/// ShadeBatch for one tag: ShadeBatchKernelOneSided, with out.delta filled for the tags whose
/// lobes are all of one kind and the two-sided rows (TwoSidedFlags) mirrored (matB).
// normal: a tag some of whose rows a normal or bump map perturbs goes through ShadePerturbed
// (simd/wavefront/perturbed_frame8-inl.h), which runs ShadeBatchKernelInFrame on its copies.
inline void ShadeBatchKernel(const MaterialTables& m, MaterialTag tag,
                             const uint32_t* material_index, size_t n, const ShadeInputs& in,
                             const ShadeOutputs& out) {
  if (m.perturbation.Any(tag)) return ShadePerturbed(m, tag, material_index, n, in, out);
  ShadeBatchKernelInFrame(m, tag, material_index, n, in, out);
}

inline void ShadeBatchKernelInFrame(const MaterialTables& m, MaterialTag tag,
                                    const uint32_t* material_index, size_t n, const ShadeInputs& in,
                                    const ShadeOutputs& out) {
  if (in.u_lobe != nullptr && out.delta != nullptr && !MixesDeltaLobes(tag))
    std::fill(out.delta, out.delta + n, IsDeltaMaterial(tag) ? 1.0f : 0.0f);
  size_t flag_count = 0;
  const uint8_t* flags = m.two_sided.Column(tag, &flag_count);
  if (flags != nullptr) return ShadeTwoSided(m, tag, flags, flag_count, material_index, n, in, out);
  ShadeBatchKernelOneSided(m, tag, material_index, n, in, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_SHADE8_INL_H_
