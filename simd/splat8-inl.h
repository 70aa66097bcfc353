// Per-target kernel of simd/splat8.h (re-included once per Highway target): the operations of
// FilmBlock::Splat, a sample's x and y taps in one vector and a footprint row per vector.

#if defined(PTLAB_SIMD_SPLAT8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_SPLAT8_INL_H_
#undef PTLAB_SIMD_SPLAT8_INL_H_
#else
#define PTLAB_SIMD_SPLAT8_INL_H_
#endif

#include <algorithm>
#include <cstddef>

#include "engine/render/film.h"
#include "engine/render/filter.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

/// Adds one sample into `block`: FilmBlock::Splat's operations, each pixel's (r, g, b, w)
/// accumulators as one 4-lane vector, the taps from scalar PixelFilter::Eval. The path of wide
/// filters and 128-bit targets.
HWY_INLINE void SplatOne(const PixelFilter& filter, float sx, float sy, const float* rgb1,
                         FilmBlock* block) {
  const hn::CappedTag<float, 4> d;
  if (hn::Lanes(d) != 4) {
    // A target with fewer than four lanes: FilmBlock::Splat itself.
    block->Splat(filter, sx, sy, Color3f{rgb1[0], rgb1[1], rgb1[2]});
    return;
  }
  const SplatFootprint f = block->Footprint(filter.radius(), sx, sy);
  const int nx = std::min(kMaxFilterTaps, f.ix1 - f.ix0 + 1);
  if (nx <= 0) return;
  float wx[kMaxFilterTaps];
  for (int i = 0; i < nx; ++i) wx[i] = filter.Eval(float(f.ix0 + i) + 0.5f - sx);
  const auto radiance = hn::LoadU(d, rgb1);
  for (int j = f.iy0; j <= f.iy1; ++j) {
    const float wy = filter.Eval(float(j) + 0.5f - sy);
    if (wy == 0.0f) continue;
    float* row = block->PixelSums(f.ix0, j);
    for (int i = 0; i < nx; ++i) {
      // w · (r, g, b, 1): w · 1 = w is FilmBlock::Splat's weight sum, bit for bit.
      const auto w = hn::Set(d, wx[i] * wy);
      hn::StoreU(hn::Add(hn::LoadU(d, row + 4 * i), hn::Mul(w, radiance)), d, row + 4 * i);
    }
  }
}

// HWY_SCALAR has one lane and lacks the ops below; it takes SplatOne's path.
#if HWY_TARGET != HWY_SCALAR
/// The separable path's constants on this target: a sample's x and y taps share one 8-lane
/// weight vector (x offsets in lanes 0-3, y offsets in lanes 4-7: two 8-lane gathers per
/// sample, half the cost of 16 lanes), and a row of the block's accumulators is read
/// Lanes(D) / 4 pixels per vector (4 on AVX3, 2 on AVX2). D has 8 or 16 lanes.
template <class D>
struct SeparableSplat {
  using DT = hn::CappedTag<float, 8>;
  using DI = hn::RebindToSigned<D>;
  using DTI = hn::RebindToSigned<DT>;
  static constexpr size_t kHalf = 4;  // taps per axis in the weight vector
  D d;
  DI di;
  DT dt;
  DTI dti;
  hn::Mask<DT> x_lanes = hn::FirstN(dt, kHalf);
  hn::Vec<DTI> tap = hn::And(hn::Iota(dti, 0), hn::Set(dti, int32_t(kHalf - 1)));  // lane % 4
  // Lane k of a row vector is pixel (first + k / 4) of the row: the lane of its tap weight.
  hn::Vec<DI> spread0 = hn::ShiftRight<2>(hn::Iota(di, 0));
  hn::Vec<DI> spread1 = hn::Add(spread0, hn::Set(di, int32_t(hn::Lanes(d) / 4)));
  // (r, g, b, 1) per pixel: which lanes take r, g and b.
  hn::Mask<D> r_lanes, g_lanes, b_lanes;

  SeparableSplat() {
    const hn::Vec<DI> channel = hn::And(hn::Iota(di, 0), hn::Set(di, 3));
    r_lanes = hn::RebindMask(d, hn::Eq(channel, hn::Zero(di)));
    g_lanes = hn::RebindMask(d, hn::Eq(channel, hn::Set(di, 1)));
    b_lanes = hn::RebindMask(d, hn::Eq(channel, hn::Set(di, 2)));
  }

  /// The 8 tap weights as a row vector (lanes 8-15 zero on AVX3).
  hn::Vec<D> Widen(hn::Vec<DT> w) const {
    if constexpr (hn::MaxLanes(D()) == 2 * hn::MaxLanes(DT())) {
      return hn::ZeroExtendVector(d, w);
    } else {
      return w;
    }
  }
};

/// PixelFilter::Eval at every lane of `x`, the same float operations lane by lane (the table
/// reads as gathers). Lanes out of the table's range read index 0 and are zeroed.
template <class D>
HWY_INLINE hn::Vec<D> EvalFilter(D d, const PixelFilter& filter, hn::Vec<D> x) {
  const hn::RebindToSigned<D> di;
  const auto ax = hn::Abs(x);
  const auto inside = hn::Le(ax, hn::Set(d, filter.radius()));  // false for NaN, as Eval's !(<=)
  const auto t = hn::Mul(ax, hn::Set(d, filter.lookup_scale()));
  const auto i =
      hn::Max(hn::Min(hn::ConvertTo(di, t), hn::Set(di, kFilterTableSize - 1)), hn::Zero(di));
  const auto frac = hn::Sub(t, hn::ConvertTo(d, i));
  const auto lo = hn::GatherIndex(d, filter.table(), i);
  const auto hi = hn::GatherIndex(d, filter.table() + 1, i);
  return hn::IfThenElseZero(inside, hn::Add(lo, hn::Mul(frac, hn::Sub(hi, lo))));
}

/// Adds c to the first `floats` accumulators at `sums` (all of a vector's lanes or fewer: the
/// rest of memory untouched). Add(sum, c) as FilmBlock::Splat's `sum += w * L`.
template <class D>
HWY_INLINE void AccumulateRow(D d, hn::Vec<D> c, size_t floats, float* sums) {
  if (floats == hn::Lanes(d)) {
    hn::StoreU(hn::Add(hn::LoadU(d, sums), c), d, sums);
  } else {
    const auto m = hn::FirstN(d, floats);
    hn::BlendedStore(hn::Add(hn::MaskedLoad(m, d, sums), c), m, d, sums);
  }
}

/// One sample through the separable path when its taps fit half a vector per axis: the x and y
/// weights from one EvalFilter, then per row of the footprint its pixels' (r, g, b, w) as whole
/// vectors, weight wx·wy·(r, g, b, 1) with FilmBlock::Splat's operations per lane. Returns
/// false (nothing done) when the taps do not fit.
template <class D>
HWY_INLINE bool SplatSeparable(const SeparableSplat<D>& k, const PixelFilter& filter, float sx,
                               float sy, float r, float g, float b, FilmBlock* block) {
  const D d = k.d;
  const SplatFootprint f = block->Footprint(filter.radius(), sx, sy);
  const int nx = f.ix1 - f.ix0 + 1, ny = f.iy1 - f.iy0 + 1;
  if (nx <= 0 || ny <= 0) return true;  // no pixel of the block: FilmBlock::Splat adds nothing
  if (size_t(nx) > k.kHalf || size_t(ny) > k.kHalf) return false;
  // Offsets float(i) + 0.5f - s per tap, as FilmBlock::Splat computes them.
  const auto first = hn::IfThenElse(hn::RebindMask(k.dti, k.x_lanes), hn::Set(k.dti, f.ix0),
                                    hn::Set(k.dti, f.iy0));
  const auto s = hn::IfThenElse(k.x_lanes, hn::Set(k.dt, sx), hn::Set(k.dt, sy));
  const auto x =
      hn::Sub(hn::Add(hn::ConvertTo(k.dt, hn::Add(first, k.tap)), hn::Set(k.dt, 0.5f)), s);
  const auto weights = EvalFilter(k.dt, filter, x);
  HWY_ALIGN float w[hn::MaxLanes(k.dt)];
  hn::Store(weights, k.dt, w);
  // wx per accumulator lane, for the first and second vector of a row.
  const auto wide = k.Widen(weights);
  const auto wx0 = hn::TableLookupLanes(wide, hn::IndicesFromVec(d, k.spread0));
  const auto radiance =
      hn::IfThenElse(k.r_lanes, hn::Set(d, r),
                     hn::IfThenElse(k.g_lanes, hn::Set(d, g),
                                    hn::IfThenElse(k.b_lanes, hn::Set(d, b), hn::Set(d, 1.0f))));
  const size_t floats = size_t(nx) * 4, lanes = hn::Lanes(d);
  for (int j = 0; j < ny; ++j) {
    const float wy = w[k.kHalf + size_t(j)];
    if (wy == 0.0f) continue;
    float* row = block->PixelSums(f.ix0, f.iy0 + j);
    const auto wyv = hn::Set(d, wy);
    AccumulateRow(d, hn::Mul(hn::Mul(wx0, wyv), radiance), std::min(floats, lanes), row);
    if (floats > lanes) {  // 8-lane targets: pixels 2 and 3
      const auto wx1 = hn::TableLookupLanes(wide, hn::IndicesFromVec(d, k.spread1));
      AccumulateRow(d, hn::Mul(hn::Mul(wx1, wyv), radiance), floats - lanes, row + lanes);
    }
  }
  return true;
}

#endif  // HWY_TARGET != HWY_SCALAR

/// D: the row tag, CappedTag<float, 16>; a template so that targets with fewer than 8 lanes do
/// not instantiate the separable path.
template <class D>
HWY_INLINE void SplatSamplesWithTag(D, const PixelFilter& filter, const FilmSamples& samples,
                                    FilmBlock* block) {
  if constexpr (hn::MaxLanes(D()) < 8) {
    // 128-bit targets: a row vector holds one pixel, the per-pixel path is as good.
    for (size_t i = 0; i < samples.n; ++i) {
      const float rgb1[4] = {samples.r[i], samples.g[i], samples.b[i], 1.0f};
      SplatOne(filter, samples.sx[i], samples.sy[i], rgb1, block);
    }
  } else {
#if HWY_TARGET != HWY_SCALAR
    const SeparableSplat<D> k;
    for (size_t i = 0; i < samples.n; ++i) {
      const float sx = samples.sx[i], sy = samples.sy[i];
      if (SplatSeparable(k, filter, sx, sy, samples.r[i], samples.g[i], samples.b[i], block)) {
        continue;
      }
      const float rgb1[4] = {samples.r[i], samples.g[i], samples.b[i], 1.0f};
      SplatOne(filter, sx, sy, rgb1, block);  // more than 4 taps on an axis
    }
#endif
  }
}

HWY_INLINE void SplatSamplesKernel(const PixelFilter& filter, const FilmSamples& samples,
                                   FilmBlock* block) {
  SplatSamplesWithTag(hn::CappedTag<float, 16>(), filter, samples, block);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_SPLAT8_INL_H_
