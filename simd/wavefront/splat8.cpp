// Vectorized film splatting: per-target instantiation and dispatch of simd/wavefront/splat8-inl.h.
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/wavefront/splat8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/wavefront/splat8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

void SplatSamplesTarget(const PixelFilter& filter, const FilmSamples& samples, FilmBlock* block) {
  SplatSamplesKernel(filter, samples, block);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/wavefront/splat8.h"

namespace ptlab::simd {

HWY_EXPORT(SplatSamplesTarget);

void SplatSamples(const PixelFilter& filter, const FilmSamples& samples, FilmBlock* block) {
  if (samples.n == 0) return;
  HWY_DYNAMIC_DISPATCH(SplatSamplesTarget)(filter, samples, block);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
