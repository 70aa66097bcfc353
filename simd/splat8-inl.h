// Per-target kernel of simd/splat8.h (re-included once per Highway target): the operations of
// FilmBlock::Splat, four accumulators of a pixel per vector.

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
/// accumulators as one 4-lane vector. The filter's taps are table lookups (PixelFilter::Eval);
/// gathering them 8-wide was slower than these scalar loads (the taps are few, gathers slow).
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

HWY_INLINE void SplatSamplesKernel(const PixelFilter& filter, const FilmSamples& samples,
                                   FilmBlock* block) {
  for (size_t k = 0; k < samples.n; ++k) {
    const float rgb1[4] = {samples.r[k], samples.g[k], samples.b[k], 1.0f};
    SplatOne(filter, samples.sx[k], samples.sy[k], rgb1, block);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_SPLAT8_INL_H_
