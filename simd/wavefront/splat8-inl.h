// Per-target kernel of simd/wavefront/splat8.h (re-included once per Highway target): the
// operations of FilmBlock::Splat, a sample's x and y taps in one vector and a footprint row per
// vector.

#if defined(PTLAB_SIMD_SPLAT8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_SPLAT8_INL_H_
#undef PTLAB_SIMD_SPLAT8_INL_H_
#else
#define PTLAB_SIMD_SPLAT8_INL_H_
#endif

#include <algorithm>
#include <cstddef>

#include "engine/render/filter.h"
#include "engine/wavefront/splat.h"
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

/// Sample `row` alone, through SplatOne: the samples outside whole groups of eight, those with
/// more than 4 taps on an axis and groups SplatGroup leaves to the per-sample path.
HWY_INLINE void SplatSample(const PixelFilter& filter, const FilmSamples& samples, size_t row,
                            FilmBlock* block) {
  const float rgb1[4] = {samples.r[row], samples.g[row], samples.b[row], 1.0f};
  SplatOne(filter, samples.sx[row], samples.sy[row], rgb1, block);
}

// HWY_SCALAR has one lane and lacks the ops below; it takes SplatOne's path.
#if HWY_TARGET != HWY_SCALAR
/// The separable path: at most kSplatTaps taps per axis, evaluated for kSplatGroup samples at
/// a time (one tap of eight samples per vector); a row of the block's accumulators is read
/// Lanes(D) / 4 pixels per vector (4 on AVX3, 2 on AVX2; D has 8 or 16 lanes).
constexpr size_t kSplatTaps = 4, kSplatGroup = 8;

/// PixelFilter::Eval at every lane of `x`, the same float operations lane by lane (the table
/// reads as gathers). Lanes out of the table's range read index 0 and are zeroed.
template <class D>
HWY_INLINE hn::Vec<D> EvalFilter(D d, const PixelFilter& filter, hn::Vec<D> x) {
  const hn::RebindToSigned<D> di;
  const auto ax = hn::Abs(x);
  const auto inside = hn::Le(ax, hn::Set(d, filter.radius()));  // false for NaN, as Eval's !(<=)
  const auto t = hn::Mul(ax, hn::Set(d, filter.lookup_scale()));
  const auto i =
      hn::Max(hn::Min(hn::ConvertTo(di, t), hn::Set(di, filter.last_index())), hn::Zero(di));
  const auto frac = hn::Sub(t, hn::ConvertTo(d, i));
  const auto lo = hn::GatherIndex(d, filter.table(), i);
  const auto hi = hn::GatherIndex(d, filter.next(), i);
  return hn::IfThenElseZero(inside, hn::Add(lo, hn::Mul(frac, hn::Sub(hi, lo))));
}

/// Adds c to the first `floats` accumulators at `sums` (a multiple of 4, all of a vector's
/// lanes or fewer: the rest of memory untouched). Add(sum, c) as FilmBlock::Splat's
/// `sum += w * L`. Whole loads and stores of 16, 8 or 4 floats, never masked ones: the box
/// filter's samples of one pixel come in a row, each adding to the accumulators the one before
/// stored, and a masked store does not forward to the next load (the CPU waits for it to
/// reach the cache).
template <class D>
HWY_INLINE void AccumulateRow(D d, hn::Vec<D> c, size_t floats, float* sums) {
  if (floats == hn::Lanes(d)) {
    hn::StoreU(hn::Add(hn::LoadU(d, sums), c), d, sums);
    return;
  }
  if constexpr (hn::MaxLanes(D()) > 4) {
    const hn::Half<D> dh;
    const size_t half = hn::Lanes(dh);
    const auto lo = hn::LowerHalf(dh, c);
    if (floats < half) return AccumulateRow(dh, lo, floats, sums);
    hn::StoreU(hn::Add(hn::LoadU(dh, sums), lo), dh, sums);
    if (floats > half) AccumulateRow(dh, hn::UpperHalf(dh, c), floats - half, sums + half);
  } else {
    const auto m = hn::FirstN(d, floats);
    hn::BlendedStore(hn::Add(hn::MaskedLoad(m, d, sums), c), m, d, sums);
  }
}

/// Adds the footprint rows of one sample, its footprint and taps given in SplatGroup's layout:
/// x weights wx[0], wx[kSplatGroup], ..., y weights likewise (nx, ny ≤ kSplatTaps), r, g, b its
/// radiance. Each row is one or two vectors of (r, g, b, w) accumulators, wx·wy·(r, g, b, 1)
/// with FilmBlock::Splat's operations per lane.
template <class D>
HWY_INLINE void AddFootprint(D d, int ix0, int iy0, int nx, int ny, const float* wx,
                             const float* wy, float r, float g, float b, FilmBlock* block) {
  constexpr size_t kPixels = hn::MaxLanes(D()) / 4, stride = kSplatGroup;
  // Lane l of a row vector is channel l % 4 of pixel l / 4 of the vector's pixels.
  const hn::RebindToSigned<D> di;
  const auto lane = hn::Iota(di, 0);
  const auto pixel_of_lane = hn::ShiftRight<2>(lane), channel = hn::And(lane, hn::Set(di, 3));
  // wx per accumulator lane: lane l holds pixel l / 4 of the row; of the second vector (8-lane
  // targets), pixel l / 4 + 2.
  auto wx0 = hn::Set(d, wx[0]), wx1 = wx0;
  for (size_t p = 1; p < kPixels; ++p) {
    const auto lanes = hn::RebindMask(d, hn::Eq(pixel_of_lane, hn::Set(di, int32_t(p))));
    wx0 = hn::IfThenElse(lanes, hn::Set(d, wx[p * stride]), wx0);
  }
  if constexpr (kPixels < kSplatTaps) {
    wx1 = hn::Set(d, wx[kPixels * stride]);
    for (size_t p = 1; p < kPixels; ++p) {
      const auto lanes = hn::RebindMask(d, hn::Eq(pixel_of_lane, hn::Set(di, int32_t(p))));
      wx1 = hn::IfThenElse(lanes, hn::Set(d, wx[(kPixels + p) * stride]), wx1);
    }
  }
  const auto is = [&](int c) { return hn::RebindMask(d, hn::Eq(channel, hn::Set(di, c))); };
  const auto radiance = hn::IfThenElse(
      is(0), hn::Set(d, r),
      hn::IfThenElse(is(1), hn::Set(d, g), hn::IfThenElse(is(2), hn::Set(d, b), hn::Set(d, 1.0f))));
  const size_t floats = size_t(nx) * 4, lanes = hn::Lanes(d);
  for (int j = 0; j < ny; ++j) {
    const float wy_j = wy[size_t(j) * stride];
    if (wy_j == 0.0f) continue;
    float* row = block->PixelSums(ix0, iy0 + j);
    const auto wyv = hn::Set(d, wy_j);
    AccumulateRow(d, hn::Mul(hn::Mul(wx0, wyv), radiance), std::min(floats, lanes), row);
    if (floats > lanes) {  // 8-lane targets: pixels 2 and 3
      AccumulateRow(d, hn::Mul(hn::Mul(wx1, wyv), radiance), floats - lanes, row + lanes);
    }
  }
}

/// Samples [i, i + 8) in order: their footprints and the 4 x and 4 y taps of all eight as
/// vectors over the samples (eight independent filter evaluations instead of one long chain
/// per sample: the per-sample path was latency-bound), then each sample's rows. The vector
/// footprint is FilmBlock::Footprint's operations; for positions of magnitude 2^24 or more
/// (or not finite) the group takes the per-sample path, where that equality is not argued.
template <class D>
HWY_INLINE void SplatGroup(D d, const PixelFilter& filter, const FilmSamples& samples, size_t i,
                           FilmBlock* block) {
  const hn::CappedTag<float, 8> dt;
  const hn::RebindToSigned<decltype(dt)> dti;
  constexpr size_t kGroup = kSplatGroup, kTaps = kSplatTaps;
  const auto sx = hn::LoadU(dt, samples.sx + i), sy = hn::LoadU(dt, samples.sy + i);
  const auto limit = hn::Set(dt, 16777216.0f);
  if (!hn::AllTrue(dt, hn::And(hn::Lt(hn::Abs(sx), limit), hn::Lt(hn::Abs(sy), limit)))) {
    for (size_t s = i; s < i + kGroup; ++s) SplatSample(filter, samples, s, block);
    return;
  }
  const auto half = hn::Set(dt, 0.5f), radius = hn::Set(dt, filter.radius());
  const auto cx = hn::Sub(sx, half), cy = hn::Sub(sy, half);
  const auto ix0 =
      hn::Max(hn::Set(dti, block->x0()), hn::ConvertTo(dti, hn::Ceil(hn::Sub(cx, radius))));
  const auto ix1 = hn::Min(hn::Set(dti, block->x0() + block->width() - 1),
                           hn::ConvertTo(dti, hn::Floor(hn::Add(cx, radius))));
  const auto iy0 =
      hn::Max(hn::Set(dti, block->y0()), hn::ConvertTo(dti, hn::Ceil(hn::Sub(cy, radius))));
  const auto iy1 = hn::Min(hn::Set(dti, block->y0() + block->height() - 1),
                           hn::ConvertTo(dti, hn::Floor(hn::Add(cy, radius))));
  HWY_ALIGN int32_t x0[kGroup], y0[kGroup], nx[kGroup], ny[kGroup];
  hn::Store(ix0, dti, x0), hn::Store(iy0, dti, y0);
  hn::Store(hn::Add(hn::Sub(ix1, ix0), hn::Set(dti, 1)), dti, nx);
  hn::Store(hn::Add(hn::Sub(iy1, iy0), hn::Set(dti, 1)), dti, ny);
  // All eight samples on one pixel (the box filter's samples come pixel by pixel): their
  // contributions added in order in a register, one load and one store of the pixel's
  // accumulators; the same operations as AddFootprint's, sample after sample.
  const auto one = hn::Set(dti, 1);
  const auto one_pixel =
      hn::And(hn::And(hn::Eq(hn::Load(dti, nx), one), hn::Eq(hn::Load(dti, ny), one)),
              hn::And(hn::Eq(ix0, hn::Set(dti, x0[0])), hn::Eq(iy0, hn::Set(dti, y0[0]))));
  if (hn::AllTrue(dti, one_pixel)) {
    // Their only taps: tap 0 on each axis.
    HWY_ALIGN float wx0[kGroup], wy0[kGroup];
    hn::Store(EvalFilter(dt, filter, hn::Sub(hn::Add(hn::ConvertTo(dt, ix0), half), sx)), dt, wx0);
    hn::Store(EvalFilter(dt, filter, hn::Sub(hn::Add(hn::ConvertTo(dt, iy0), half), sy)), dt, wy0);
    const hn::CappedTag<float, 4> d4;
    float* sums = block->PixelSums(x0[0], y0[0]);
    auto acc = hn::LoadU(d4, sums);
    for (size_t s = 0; s < kGroup; ++s) {
      if (wy0[s] == 0.0f) continue;
      const size_t row = i + s;
      const float rgb1[4] = {samples.r[row], samples.g[row], samples.b[row], 1.0f};
      const auto w = hn::Mul(hn::Set(d4, wx0[s]), hn::Set(d4, wy0[s]));
      acc = hn::Add(acc, hn::Mul(w, hn::LoadU(d4, rgb1)));
    }
    hn::StoreU(acc, d4, sums);
    return;
  }
  // Tap t of every sample: offset float(i0 + t) + 0.5f - s, as FilmBlock::Splat computes it.
  HWY_ALIGN float wx[kTaps][kGroup], wy[kTaps][kGroup];
  for (size_t t = 0; t < kTaps; ++t) {
    const auto tap = hn::Set(dti, int32_t(t));
    hn::Store(
        EvalFilter(dt, filter, hn::Sub(hn::Add(hn::ConvertTo(dt, hn::Add(ix0, tap)), half), sx)),
        dt, wx[t]);
    hn::Store(
        EvalFilter(dt, filter, hn::Sub(hn::Add(hn::ConvertTo(dt, hn::Add(iy0, tap)), half), sy)),
        dt, wy[t]);
  }
  for (size_t s = 0; s < kGroup; ++s) {
    if (nx[s] <= 0 || ny[s] <= 0) continue;  // no pixel of the block
    const size_t row = i + s;
    if (size_t(nx[s]) > kTaps || size_t(ny[s]) > kTaps) {
      SplatSample(filter, samples, row, block);
      continue;
    }
    AddFootprint(d, x0[s], y0[s], nx[s], ny[s], &wx[0][s], &wy[0][s], samples.r[row],
                 samples.g[row], samples.b[row], block);
  }
}

#endif  // HWY_TARGET != HWY_SCALAR

/// D: the row tag, CappedTag<float, 16>; a template so that targets with fewer than 8 lanes do
/// not instantiate the separable path.
template <class D>
HWY_INLINE void SplatSamplesWithTag(D, const PixelFilter& filter, const FilmSamples& samples,
                                    FilmBlock* block) {
  if constexpr (hn::MaxLanes(D()) < 8) {
    // 128-bit targets: a row vector holds one pixel, the per-pixel path is as good.
    for (size_t i = 0; i < samples.n; ++i) SplatSample(filter, samples, i, block);
  } else {
#if HWY_TARGET != HWY_SCALAR
    size_t i = 0;
    for (; i + kSplatGroup <= samples.n; i += kSplatGroup)
      SplatGroup(D(), filter, samples, i, block);
    for (; i < samples.n; ++i) SplatSample(filter, samples, i, block);
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
