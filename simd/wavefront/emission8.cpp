// Vectorized area-light emission of the shading stage: per-target instantiation and dispatch
// of simd/wavefront/emission8-inl.h.
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/wavefront/emission8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/wavefront/emission8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

void AddAreaEmissionsTarget(const Scene& scene, const EmissionBatchRules& rules, size_t n,
                            const EmissionBatchInputs& in, const EmissionBatchPaths& paths) {
  AddAreaEmissionsKernel(scene, rules, n, in, paths);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/wavefront/emission8.h"

namespace ptlab::simd {

HWY_EXPORT(AddAreaEmissionsTarget);

void AddAreaEmissions(const Scene& scene, const EmissionBatchRules& rules, size_t n,
                      const EmissionBatchInputs& in, const EmissionBatchPaths& paths) {
  if (n == 0) return;
  HWY_DYNAMIC_DISPATCH(AddAreaEmissionsTarget)(scene, rules, n, in, paths);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
