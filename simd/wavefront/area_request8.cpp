// Vectorized finish of area-light emitter samples: per-target instantiation and dispatch of
// simd/wavefront/area_request8-inl.h.
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/wavefront/area_request8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/wavefront/area_request8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

void AreaEmitterRequestBatchTarget(const Scene& scene, MaterialTag tag, bool mis, size_t n,
                                   const AreaRequestInputs& in, const AreaRequestOutputs& out) {
  AreaEmitterRequestBatchKernel(scene, tag, mis, n, in, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/wavefront/area_request8.h"

namespace ptlab::simd {

HWY_EXPORT(AreaEmitterRequestBatchTarget);

void AreaEmitterRequestBatch(const Scene& scene, MaterialTag tag, bool mis, size_t n,
                             const AreaRequestInputs& in, const AreaRequestOutputs& out) {
  if (n == 0) return;
  HWY_DYNAMIC_DISPATCH(AreaEmitterRequestBatchTarget)(scene, tag, mis, n, in, out);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
