// Vectorized sampler entry points: per-target instantiation and dispatch of simd/wavefront/sobol8-inl.h.
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/wavefront/sobol8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/wavefront/sobol8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

void Sobol2DTarget(const uint32_t* pixel_seed, const uint32_t* index, uint32_t dim, size_t n,
                   float* x, float* y) {
  SobolKernel<true>(pixel_seed, index, dim, n, x, y);
}
void Sobol1DTarget(const uint32_t* pixel_seed, const uint32_t* index, uint32_t dim, size_t n,
                   float* x) {
  SobolKernel<false>(pixel_seed, index, dim, n, x, nullptr);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/wavefront/sobol8.h"

namespace ptlab::simd {

HWY_EXPORT(Sobol2DTarget);
HWY_EXPORT(Sobol1DTarget);

void ScrambledSobol2DBatch(const uint32_t* pixel_seed, const uint32_t* index, uint32_t dim,
                           size_t n, float* x, float* y) {
  HWY_DYNAMIC_DISPATCH(Sobol2DTarget)(pixel_seed, index, dim, n, x, y);
}

void ScrambledSobol1DBatch(const uint32_t* pixel_seed, const uint32_t* index, uint32_t dim,
                           size_t n, float* x) {
  HWY_DYNAMIC_DISPATCH(Sobol1DTarget)(pixel_seed, index, dim, n, x);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
