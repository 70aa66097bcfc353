// Per-target lane types of the wavefront kernels (re-included once per Highway target): the
// 8-wide float tag every shading-side kernel uses, its vector and mask, and the finiteness test
// of an RGB triple. Shared by the shading stage (bsdf8-inl.h) and the stages that call it
// through its dispatched entry point (area_request8-inl.h).

#if defined(PTLAB_SIMD_LANES8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_LANES8_INL_H_
#undef PTLAB_SIMD_LANES8_INL_H_
#else
#define PTLAB_SIMD_LANES8_INL_H_
#endif

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

/// Eight float lanes: one vector on AVX2/AVX-512, two iterations of four on SSE4.
using D8 = hn::CappedTag<float, 8>;
using V8 = hn::Vec<D8>;
using M8 = hn::Mask<D8>;

/// Lanes whose three values are all finite.
HWY_INLINE M8 AllFinite3(D8, V8 a, V8 b, V8 c) {
  return hn::And(hn::IsFinite(a), hn::And(hn::IsFinite(b), hn::IsFinite(c)));
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_LANES8_INL_H_
