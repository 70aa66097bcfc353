// Vectorized distant-disk sampling: per-target instantiation and dispatch of
// simd/wavefront/distant_disk8-inl.h.
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/wavefront/distant_disk8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/wavefront/distant_disk8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

void SampleDistantDiskBatchTarget(const DistantDiskTable& table, uint32_t disk, size_t n,
                                  const EnvironmentBatchInputs& in,
                                  const EnvironmentBatchOutputs& out) {
  SampleDistantDiskBatchKernel(table, disk, n, in, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/wavefront/distant_disk8.h"

namespace ptlab::simd {

HWY_EXPORT(SampleDistantDiskBatchTarget);

void SampleDistantDiskBatch(const DistantDiskTable& table, uint32_t disk, size_t n,
                            const EnvironmentBatchInputs& in, const EnvironmentBatchOutputs& out) {
  if (n == 0) return;
  HWY_DYNAMIC_DISPATCH(SampleDistantDiskBatchTarget)(table, disk, n, in, out);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
