// Vectorized environment-map sampling: per-target instantiation and dispatch of
// simd/wavefront/environment8-inl.h.
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/wavefront/environment8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/wavefront/environment8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

void SampleEnvironmentBatchTarget(const EnvironmentMapTable& table, uint32_t map, size_t n,
                                  const EnvironmentBatchInputs& in,
                                  const EnvironmentBatchOutputs& out) {
  SampleEnvironmentBatchKernel(table, map, n, in, out);
}
void EvalEnvironmentBatchTarget(const EnvironmentMapTable& table, uint32_t map, size_t n,
                                const EnvironmentEvalInputs& in,
                                const EnvironmentEvalOutputs& out) {
  EvalEnvironmentBatchKernel(table, map, n, in, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/wavefront/environment8.h"

namespace ptlab::simd {

HWY_EXPORT(SampleEnvironmentBatchTarget);
HWY_EXPORT(EvalEnvironmentBatchTarget);

void SampleEnvironmentBatch(const EnvironmentMapTable& table, uint32_t map, size_t n,
                            const EnvironmentBatchInputs& in, const EnvironmentBatchOutputs& out) {
  if (n == 0) return;
  HWY_DYNAMIC_DISPATCH(SampleEnvironmentBatchTarget)(table, map, n, in, out);
}

void EvalEnvironmentBatch(const EnvironmentMapTable& table, uint32_t map, size_t n,
                          const EnvironmentEvalInputs& in, const EnvironmentEvalOutputs& out) {
  if (n == 0) return;
  HWY_DYNAMIC_DISPATCH(EvalEnvironmentBatchTarget)(table, map, n, in, out);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
