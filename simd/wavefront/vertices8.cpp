// Vectorized vertex decisions: per-target instantiation and dispatch of
// simd/wavefront/vertices8-inl.h.
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/wavefront/vertices8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/wavefront/vertices8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

void DecideVerticesTarget(const Scene& scene, const VertexBatchRules& rules, size_t n,
                          const VertexBatchInputs& in, const VertexBatchPaths& paths,
                          VertexBatchOutputs* out) {
  DecideVerticesKernel(scene, rules, n, in, paths, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/wavefront/vertices8.h"

namespace ptlab::simd {

HWY_EXPORT(DecideVerticesTarget);

void DecideVertices(const Scene& scene, const VertexBatchRules& rules, size_t n,
                    const VertexBatchInputs& in, const VertexBatchPaths& paths,
                    VertexBatchOutputs* out) {
  if (n == 0) return;
  HWY_DYNAMIC_DISPATCH(DecideVerticesTarget)(scene, rules, n, in, paths, out);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
