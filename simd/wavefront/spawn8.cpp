// Vectorized spawn stage: per-target instantiation and dispatch of simd/wavefront/spawn8-inl.h.
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/wavefront/spawn8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/wavefront/spawn8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

void SpawnRayBatchTarget(const SurfaceInteraction* its, size_t n, const SpawnInputs& in,
                         RayPacket8* out) {
  SpawnRayBatchKernel(its, n, in, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/wavefront/spawn8.h"

namespace ptlab::simd {

HWY_EXPORT(SpawnRayBatchTarget);

void SpawnRayBatch(const SurfaceInteraction* its, size_t n, const SpawnInputs& in,
                   RayPacket8* out) {
  if (n == 0) return;
  HWY_DYNAMIC_DISPATCH(SpawnRayBatchTarget)(its, n, in, out);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
