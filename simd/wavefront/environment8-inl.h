// Per-target kernel of simd/wavefront/environment8.h (re-included once per Highway target):
// SampleEnvironment's importance sampling, eight rows per vector.

#if defined(PTLAB_SIMD_ENVIRONMENT8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_ENVIRONMENT8_INL_H_
#undef PTLAB_SIMD_ENVIRONMENT8_INL_H_
#else
#define PTLAB_SIMD_ENVIRONMENT8_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include "engine/wavefront/environment.h"
#include "engine/light/environment_map.h"
#include "hwy/contrib/math/math-inl.h"
#include "hwy/highway.h"
#include "simd/distribution8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

/// Lookup (environment_map.cpp) at (u, v) ∈ [0, 1]² of the w × h map whose texels (r, g, b,
/// pad: kEnvironmentTexel floats) start at `texels`: the bilinear interpolation of the pixel
/// points (row coordinate v · v_scale + v_offset: EnvironmentRowCoordinate), wrapping in u and
/// clamping in v, the scalar code's float operations in its order.
/// For u in [0, 1] the column ⌊u w − ½⌋ lies in [−1, w − 1], so the wrap is one conditional
/// add. A lane's three channels of a pixel share a cache line: the first gather brings it in.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void EnvironmentLookup8(D d, const float* texels, int w, int h, float v_scale,
                                   float v_offset, V u, V v, V* out_r, V* out_g, V* out_b) {
  const hn::RebindToSigned<D> di;
  const V one = hn::Set(d, 1.0f), half = hn::Set(d, 0.5f);
  const V x = hn::Sub(hn::Mul(u, hn::Set(d, float(w))), half);
  const V y = hn::Add(hn::Mul(v, hn::Set(d, v_scale)), hn::Set(d, v_offset));
  const V fx = hn::Floor(x), fy = hn::Floor(y);
  const V tx = hn::Sub(x, fx), ty = hn::Sub(y, fy);
  const auto zero_i = hn::Zero(di), one_i = hn::Set(di, 1), w_i = hn::Set(di, w);
  const auto ix = hn::ConvertTo(di, fx), iy = hn::ConvertTo(di, fy);
  const auto x0 = hn::IfThenElse(hn::Lt(ix, zero_i), hn::Add(ix, w_i), ix);
  const auto x1 = hn::IfThenElseZero(hn::Ne(hn::Add(x0, one_i), w_i), hn::Add(x0, one_i));
  const auto last_row = hn::Set(di, h - 1);
  const auto y0 = hn::Min(hn::Max(iy, zero_i), last_row);
  const auto y1 = hn::Min(hn::Max(hn::Add(iy, one_i), zero_i), last_row);
  static_assert(kEnvironmentTexel == 4);
  const auto texel = [&](auto row, auto column) {
    return hn::ShiftLeft<2>(hn::Add(hn::Mul(row, w_i), column));
  };
  const auto k00 = texel(y0, x0), k10 = texel(y0, x1), k01 = texel(y1, x0), k11 = texel(y1, x1);
  const V sx = hn::Sub(one, tx), sy = hn::Sub(one, ty);
  // (1 − ty)((1 − tx) c00 + tx c10) + ty((1 − tx) c01 + tx c11), per channel.
  const auto channel = [&](const float* c) {
    const V top =
        hn::Add(hn::Mul(sx, hn::GatherIndex(d, c, k00)), hn::Mul(tx, hn::GatherIndex(d, c, k10)));
    const V bottom =
        hn::Add(hn::Mul(sx, hn::GatherIndex(d, c, k01)), hn::Mul(tx, hn::GatherIndex(d, c, k11)));
    return hn::Add(hn::Mul(sy, top), hn::Mul(ty, bottom));
  };
  *out_r = channel(texels), *out_g = channel(texels + 1), *out_b = channel(texels + 2);
}

/// Whether the texels of map `map` can be addressed by int32 gathers.
inline bool TexelsFitInt32(const EnvironmentMapTable& table, uint32_t map) {
  return int64_t(table.width[map]) * int64_t(table.height[map]) * int64_t(kEnvironmentTexel) <
         (int64_t(1) << 31);
}

HWY_INLINE void SampleEnvironmentBatchKernel(const EnvironmentMapTable& table, uint32_t map,
                                             size_t n, const EnvironmentBatchInputs& in,
                                             const EnvironmentBatchOutputs& out) {
  const hn::CappedTag<float, 8> d;
  const hn::RebindToSigned<decltype(d)> di;
  const size_t lanes = hn::Lanes(d);
  const Distribution2DView dist = EnvironmentDistribution(table, map);
  size_t i = 0;
  // Importance rows of a map with mass (the scalar code samples the rest, and the tail); the
  // conditional CDFs and the texels are indexed by int32 gathers.
  const bool vector = table.sampling[map] == EnvironmentSampling::kImportance && dist.NonEmpty() &&
                      int64_t(dist.nv) * (int64_t(dist.nu) + 1) < (int64_t(1) << 31) &&
                      TexelsFitInt32(table, map);
  if (vector) {
    const float* texels = table.texels.data() + size_t(table.pixel_offset[map]) * kEnvironmentTexel;
    float v_scale, v_offset;
    EnvironmentRowCoordinate(table, map, &v_scale, &v_offset);
    const Frame& f = table.to_world[map];
    const auto zero = hn::Zero(d), half = hn::Set(d, 0.5f), one = hn::Set(d, 1.0f);
    const auto pi = hn::Set(d, kPi), two_pi = hn::Set(d, 2 * kPi);
    const auto stride = hn::Set(di, dist.nu + 1);
    for (; i + lanes <= n; i += lanes) {
      // SampleDistribution2D: the row from the marginal with u.y, the column from its
      // conditional with u.x; the cell's density (Distribution2DCellPdf).
      hn::Vec<decltype(d)> y, pdf_y, x, pdf_x;
      hn::Vec<decltype(di)> row, column;
      SamplePiecewiseConstant8(d, dist.marginal_cdf, dist.marginal_guide, hn::Zero(di), dist.nv,
                               hn::LoadU(d, in.u_y + i), &y, &row, &pdf_y);
      const auto row_at = hn::Mul(row, stride);
      SamplePiecewiseConstant8(d, dist.conditional_cdf, dist.conditional_guide, row_at, dist.nu,
                               hn::LoadU(d, in.u_x + i), &x, &column, &pdf_x);
      const auto pdf_uv = hn::Mul(pdf_y, pdf_x);
      // A row without mass gives no sample (it is never picked: the marginal skips it).
      const auto valid = hn::Gt(
          hn::GatherIndex(d, dist.conditional_cdf, hn::Add(row_at, hn::Set(di, dist.nu))), zero);
      // Off the pole (v = 0 has infinite density), then SinCosTheta and the direction.
      const auto v = hn::Max(y, hn::Set(d, 0x1p-24f));
      const auto south = hn::Gt(v, half);
      const auto from_pole = hn::Mul(pi, hn::IfThenElse(south, hn::Sub(one, v), v));
      const auto sin_theta = hn::Sin(d, from_pole);
      const auto cos_from_pole = hn::Cos(d, from_pole);
      const auto cos_theta = hn::IfThenElse(south, hn::Neg(cos_from_pole), cos_from_pole);
      const auto phi = hn::Mul(two_pi, x);
      const auto dx = hn::Mul(sin_theta, hn::Sin(d, phi));
      const auto dz = hn::Mul(hn::Neg(sin_theta), hn::Cos(d, phi));
      // Frame::ToWorld: s d.x + t d.y + n d.z.
      const auto world = [&](float s, float t, float nn) {
        return hn::Add(hn::Add(hn::Mul(hn::Set(d, s), dx), hn::Mul(hn::Set(d, t), cos_theta)),
                       hn::Mul(hn::Set(d, nn), dz));
      };
      hn::Vec<decltype(d)> r, g, b;
      EnvironmentLookup8(d, texels, table.width[map], table.height[map], v_scale, v_offset, x, v,
                         &r, &g, &b);
      const auto pdf = hn::Div(pdf_uv, hn::Mul(hn::Set(d, kEnvironmentTwoPiSquared), sin_theta));
      hn::StoreU(hn::IfThenElseZero(valid, world(f.s.x, f.t.x, f.n.x)), d, out.wi_x + i);
      hn::StoreU(hn::IfThenElseZero(valid, world(f.s.y, f.t.y, f.n.y)), d, out.wi_y + i);
      hn::StoreU(hn::IfThenElseZero(valid, world(f.s.z, f.t.z, f.n.z)), d, out.wi_z + i);
      hn::StoreU(hn::IfThenElseZero(valid, r), d, out.r + i);
      hn::StoreU(hn::IfThenElseZero(valid, g), d, out.g + i);
      hn::StoreU(hn::IfThenElseZero(valid, b), d, out.b + i);
      hn::StoreU(hn::IfThenElseZero(valid, pdf), d, out.pdf + i);
    }
  }
  for (; i < n; ++i) SetEnvironmentRow(out, i, SampleEnvironmentRow(table, map, in, i));
}

/// atan2(y, x) from hwy's Atan on [0, 1] (the smaller magnitude over the larger), moved to
/// its quadrant: atan2's signs (CopySign of y, so atan2(±0, x < 0) = ±π) and ±0 for (±0, +0).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V Atan2(D d, V y, V x) {
  const V ax = hn::Abs(x), ay = hn::Abs(y), zero = hn::Zero(d);
  const auto steep = hn::Gt(ay, ax);
  const V big = hn::IfThenElse(steep, ay, ax), small = hn::IfThenElse(steep, ax, ay);
  const V ratio = hn::IfThenZeroElse(hn::Eq(big, zero), hn::Div(small, big));
  V a = hn::Atan(d, ratio);
  a = hn::IfThenElse(steep, hn::Sub(hn::Set(d, 0.5f * kPi), a), a);
  // x with its sign bit set (−0 included: atan2(0, −0) = π) reflects a about π/2.
  const hn::RebindToSigned<D> di;
  const auto x_negative = hn::RebindMask(d, hn::Lt(hn::BitCast(di, x), hn::Zero(di)));
  a = hn::IfThenElse(x_negative, hn::Sub(hn::Set(d, kPi), a), a);
  return hn::CopySign(a, y);
}

HWY_INLINE void EvalEnvironmentBatchKernel(const EnvironmentMapTable& table, uint32_t map, size_t n,
                                           const EnvironmentEvalInputs& in,
                                           const EnvironmentEvalOutputs& out) {
  const hn::CappedTag<float, 8> d;
  const size_t lanes = hn::Lanes(d);
  const int w = table.width[map], h = table.height[map], nv = EnvironmentCellRows(table, map);
  float v_scale, v_offset;
  EnvironmentRowCoordinate(table, map, &v_scale, &v_offset);
  const bool importance = table.sampling[map] == EnvironmentSampling::kImportance;
  const Distribution2DView dist = EnvironmentDistribution(table, map);
  size_t i = 0;
  // The conditional CDFs and the texels are indexed by int32 gathers.
  if ((!importance || int64_t(nv) * (int64_t(w) + 1) < (int64_t(1) << 31)) &&
      TexelsFitInt32(table, map)) {
    const hn::RebindToSigned<decltype(d)> di;
    const float* texels = table.texels.data() + size_t(table.pixel_offset[map]) * kEnvironmentTexel;
    const Frame& f = table.to_world[map];
    const auto zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    const auto uniform_pdf = hn::Set(d, table.luminance_integral[map] > 0 ? kInv4Pi : 0.0f);
    for (; i + lanes <= n; i += lanes) {
      const auto wx = hn::LoadU(d, in.w_x + i), wy = hn::LoadU(d, in.w_y + i),
                 wz = hn::LoadU(d, in.w_z + i);
      // Frame::ToLocal: the dot products with s, t, n.
      const auto local = [&](const Vec3f& axis) {
        return hn::Add(hn::Add(hn::Mul(wx, hn::Set(d, axis.x)), hn::Mul(wy, hn::Set(d, axis.y))),
                       hn::Mul(wz, hn::Set(d, axis.z)));
      };
      const auto lx = local(f.s), ly = local(f.t), lz = local(f.n);
      // EnvironmentDirectionToUv.
      auto phi = Atan2(d, lx, hn::Neg(lz));
      phi = hn::IfThenElse(hn::Lt(phi, zero), hn::Add(phi, hn::Set(d, 2 * kPi)), phi);
      const auto r = hn::Sqrt(hn::Add(hn::Mul(lx, lx), hn::Mul(lz, lz)));
      const auto theta = Atan2(d, r, ly);
      const auto u = hn::Min(hn::Max(hn::Mul(phi, hn::Set(d, kInv2Pi)), zero), one);
      const auto v = hn::Min(hn::Max(hn::Mul(theta, hn::Set(d, kInvPi)), zero), one);
      hn::Vec<decltype(d)> cr, cg, cb;
      EnvironmentLookup8(d, texels, w, h, v_scale, v_offset, u, v, &cr, &cg, &cb);
      // A direction that is not finite sees black (Lookup's test of x and y).
      const auto finite = hn::And(hn::IsFinite(u), hn::IsFinite(v));
      hn::StoreU(hn::IfThenElseZero(finite, cr), d, out.r + i);
      hn::StoreU(hn::IfThenElseZero(finite, cg), d, out.g + i);
      hn::StoreU(hn::IfThenElseZero(finite, cb), d, out.b + i);
      if (!out.pdf) continue;
      if (!importance) {
        hn::StoreU(uniform_pdf, d, out.pdf + i);
        continue;
      }
      // EnvironmentPdf: the cell's density (Distribution2DPdf at (u, v)) over 2π² sinθ, with
      // sinθ = r / |d|; 0 on the axis (r = 0).
      const auto column = PiecewiseConstantBin8(d, u, float(w));
      const auto row = PiecewiseConstantBin8(d, v, float(nv));
      const auto m0 = hn::GatherIndex(d, dist.marginal_cdf, row);
      const auto m1 = hn::GatherIndex(d, dist.marginal_cdf, hn::Add(row, hn::Set(di, 1)));
      const auto at = hn::Add(hn::Mul(row, hn::Set(di, w + 1)), column);
      const auto c0 = hn::GatherIndex(d, dist.conditional_cdf, at);
      const auto c1 = hn::GatherIndex(d, dist.conditional_cdf, hn::Add(at, hn::Set(di, 1)));
      const auto pdf_uv = hn::Mul(hn::Mul(hn::Set(d, float(nv)), hn::Sub(m1, m0)),
                                  hn::Mul(hn::Set(d, float(w)), hn::Sub(c1, c0)));
      const auto sin_theta = hn::Div(r, hn::Sqrt(hn::Add(hn::Mul(r, r), hn::Mul(ly, ly))));
      const auto pdf = hn::Div(pdf_uv, hn::Mul(hn::Set(d, kEnvironmentTwoPiSquared), sin_theta));
      hn::StoreU(hn::IfThenElseZero(hn::And(hn::Gt(r, zero), finite), pdf), d, out.pdf + i);
    }
  }
  if (i < n) {
    const EnvironmentEvalInputs tail{in.w_x + i, in.w_y + i, in.w_z + i};
    const EnvironmentEvalOutputs rest{out.r + i, out.g + i, out.b + i,
                                      out.pdf ? out.pdf + i : nullptr};
    ptlab::EvalEnvironmentBatch(table, map, n - i, tail, rest);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_ENVIRONMENT8_INL_H_
