// Per-target kernel of simd/environment8.h (re-included once per Highway target):
// SampleEnvironment's importance sampling, eight rows per vector.

#if defined(PTLAB_SIMD_ENVIRONMENT8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_ENVIRONMENT8_INL_H_
#undef PTLAB_SIMD_ENVIRONMENT8_INL_H_
#else
#define PTLAB_SIMD_ENVIRONMENT8_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include "engine/light/environment_batch.h"
#include "engine/light/environment_map.h"
#include "hwy/contrib/math/math-inl.h"
#include "hwy/highway.h"
#include "simd/distribution8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

/// Lookup (environment_map.cpp) at (u, v) ∈ [0, 1)² of the w × h map whose pixels start at
/// r, g, b: the bilinear interpolation of the pixel centres, wrapping in u and clamping in v,
/// the scalar code's float operations in its order. For u in [0, 1) the column ⌊u w − ½⌋ lies
/// in [−1, w − 1], so the wrap is one conditional add.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void EnvironmentLookup8(D d, const float* r, const float* g, const float* b, int w,
                                   int h, V u, V v, V* out_r, V* out_g, V* out_b) {
  const hn::RebindToSigned<D> di;
  const V one = hn::Set(d, 1.0f), half = hn::Set(d, 0.5f);
  const V x = hn::Sub(hn::Mul(u, hn::Set(d, float(w))), half);
  const V y = hn::Sub(hn::Mul(v, hn::Set(d, float(h))), half);
  const V fx = hn::Floor(x), fy = hn::Floor(y);
  const V tx = hn::Sub(x, fx), ty = hn::Sub(y, fy);
  const auto zero_i = hn::Zero(di), one_i = hn::Set(di, 1), w_i = hn::Set(di, w);
  const auto ix = hn::ConvertTo(di, fx), iy = hn::ConvertTo(di, fy);
  const auto x0 = hn::IfThenElse(hn::Lt(ix, zero_i), hn::Add(ix, w_i), ix);
  const auto x1 = hn::IfThenElseZero(hn::Ne(hn::Add(x0, one_i), w_i), hn::Add(x0, one_i));
  const auto last_row = hn::Set(di, h - 1);
  const auto y0 = hn::Min(hn::Max(iy, zero_i), last_row);
  const auto y1 = hn::Min(hn::Max(hn::Add(iy, one_i), zero_i), last_row);
  const auto k00 = hn::Add(hn::Mul(y0, w_i), x0), k10 = hn::Add(hn::Mul(y0, w_i), x1);
  const auto k01 = hn::Add(hn::Mul(y1, w_i), x0), k11 = hn::Add(hn::Mul(y1, w_i), x1);
  const V sx = hn::Sub(one, tx), sy = hn::Sub(one, ty);
  // (1 − ty)((1 − tx) c00 + tx c10) + ty((1 − tx) c01 + tx c11), per channel.
  const auto channel = [&](const float* c) {
    const V top =
        hn::Add(hn::Mul(sx, hn::GatherIndex(d, c, k00)), hn::Mul(tx, hn::GatherIndex(d, c, k10)));
    const V bottom =
        hn::Add(hn::Mul(sx, hn::GatherIndex(d, c, k01)), hn::Mul(tx, hn::GatherIndex(d, c, k11)));
    return hn::Add(hn::Mul(sy, top), hn::Mul(ty, bottom));
  };
  *out_r = channel(r), *out_g = channel(g), *out_b = channel(b);
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
  // conditional CDFs are indexed by int32 gathers.
  const bool vector = table.sampling[map] == EnvironmentSampling::kImportance && dist.NonEmpty() &&
                      int64_t(dist.nv) * (int64_t(dist.nu) + 1) < (int64_t(1) << 31);
  if (vector) {
    const uint32_t o = table.pixel_offset[map];
    const float *pr = table.r.data() + o, *pg = table.g.data() + o, *pb = table.b.data() + o;
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
      EnvironmentLookup8(d, pr, pg, pb, dist.nu, dist.nv, x, v, &r, &g, &b);
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

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_ENVIRONMENT8_INL_H_
