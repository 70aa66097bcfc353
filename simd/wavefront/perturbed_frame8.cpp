// normal: per-target instantiation and dispatch of simd/wavefront/perturbed_frame8-inl.h's
// frame batch (the shade step's use of it is in bsdf8.cpp).
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/wavefront/perturbed_frame8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/wavefront/bsdf8-inl.h"  // perturbed_frame8-inl.h and the kernels it wraps

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

void PerturbedFrameBatchTarget(const MaterialTables& m, MaterialTag tag,
                               const uint32_t* material_index, size_t n, const ShadeInputs& in,
                               float* const frame[9]) {
  PerturbedFrameBatchKernel(m, tag, material_index, n, in, frame);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/wavefront/perturbed_frame8.h"

namespace ptlab::simd {

HWY_EXPORT(PerturbedFrameBatchTarget);

void PerturbedFrameBatch(const MaterialTables& m, MaterialTag tag, const uint32_t* material_index,
                         size_t n, const ShadeInputs& in, float* const frame[9]) {
  if (n == 0) return;
  HWY_DYNAMIC_DISPATCH(PerturbedFrameBatchTarget)(m, tag, material_index, n, in, frame);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
