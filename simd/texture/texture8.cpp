// Vectorized texture lookup: per-target instantiation and dispatch of simd/texture/texture8-inl.h.
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/texture/texture8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/texture/texture8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

void EvalTextureBatchTarget(const TextureTable& t, const uint32_t* id,
                            const TexturePointArrays& at, size_t n, float* r, float* g,
                            float* b) {
  EvalTextureBatchKernel(t, id, at, n, r, g, b);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/texture/texture8.h"

namespace ptlab::simd {

HWY_EXPORT(EvalTextureBatchTarget);

void EvalTextureBatch(const TextureTable& t, const uint32_t* id, const TexturePointArrays& at,
                      size_t n, float* r, float* g, float* b) {
  if (n == 0) return;
  HWY_DYNAMIC_DISPATCH(EvalTextureBatchTarget)(t, id, at, n, r, g, b);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
