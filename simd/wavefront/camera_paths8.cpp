// Vectorized camera paths: per-target instantiation and dispatch of
// simd/wavefront/camera_paths8-inl.h.
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/wavefront/camera_paths8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/wavefront/camera_paths8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

void StartCameraPathsTarget(SamplerType type, uint64_t seed, uint64_t width, size_t n,
                            const CameraPathInputs& in, const CameraPathOutputs& out) {
  StartCameraPathsKernel(type, seed, width, n, in, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/wavefront/camera_paths8.h"

namespace ptlab::simd {

HWY_EXPORT(StartCameraPathsTarget);

void StartCameraPaths(SamplerType type, uint64_t seed, uint64_t width, size_t n,
                      const CameraPathInputs& in, const CameraPathOutputs& out) {
  if (n == 0) return;
  HWY_DYNAMIC_DISPATCH(StartCameraPathsTarget)(type, seed, width, n, in, out);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
