// Vectorized BSDF-stage finish: per-target instantiation and dispatch of simd/wavefront/continuation8-inl.h.
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/wavefront/continuation8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/wavefront/continuation8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

void ContinuePathsTarget(const ContinueBatchRules& rules, size_t n, const ContinueBatchInputs& in,
                         const ContinueBatchPaths& paths, ContinueBatchOutputs* out) {
  ContinuePathsKernel(rules, n, in, paths, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/wavefront/continuation8.h"

namespace ptlab::simd {

HWY_EXPORT(ContinuePathsTarget);

void ContinuePaths(const ContinueBatchRules& rules, size_t n, const ContinueBatchInputs& in,
                   const ContinueBatchPaths& paths, ContinueBatchOutputs* out) {
  if (n == 0) return;
  HWY_DYNAMIC_DISPATCH(ContinuePathsTarget)(rules, n, in, paths, out);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
