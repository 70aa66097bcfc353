// Vectorized emitter sampling: per-target instantiation and dispatch of simd/wavefront/area_light8-inl.h.
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/wavefront/area_light8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/wavefront/area_light8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

void SampleAreaLightBatchTarget(const Scene& scene, const TriangleRows& tri_rows,
                                TriangleSampling mode, size_t n, const AreaLightBatchInputs& in,
                                const AreaLightBatchOutputs& out) {
  SampleAreaLightBatchKernel(scene, tri_rows, mode, n, in, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/wavefront/area_light8.h"

namespace ptlab::simd {

HWY_EXPORT(SampleAreaLightBatchTarget);

void SampleAreaLightBatch(const Scene& scene, const TriangleRows& tri_rows, TriangleSampling mode,
                          size_t n, const AreaLightBatchInputs& in,
                          const AreaLightBatchOutputs& out) {
  if (n == 0) return;
  HWY_DYNAMIC_DISPATCH(SampleAreaLightBatchTarget)(scene, tri_rows, mode, n, in, out);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
