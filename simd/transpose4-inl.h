// Per-target helper (re-included once per Highway target): four vectors of floats as quads of
// rows, the 4x4 transpose within each 128-bit block (simd/interaction8, simd/continue8).

#if defined(PTLAB_SIMD_TRANSPOSE4_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TRANSPOSE4_INL_H_
#undef PTLAB_SIMD_TRANSPOSE4_INL_H_
#else
#define PTLAB_SIMD_TRANSPOSE4_INL_H_
#endif

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// Lane j of (f0, f1, f2, f3) as a quad: lanes j, j + 1, j + 2, j + 3 of a 128-bit block give
// that block of r0, r1, r2, r3, so on 8-lane vectors r0 holds the quads of lanes 0 and 4, r1
// those of 1 and 5, and so on. Not on HWY_SCALAR (one lane, no blocks).
#if HWY_TARGET != HWY_SCALAR
template <class D, class V = hn::Vec<D>>
HWY_INLINE void TransposeQuads(D d, V f0, V f1, V f2, V f3, V* r0, V* r1, V* r2, V* r3) {
  const hn::Repartition<double, D> dd;
  const auto lo01 = hn::BitCast(dd, hn::InterleaveLower(d, f0, f1));
  const auto lo23 = hn::BitCast(dd, hn::InterleaveLower(d, f2, f3));
  const auto hi01 = hn::BitCast(dd, hn::InterleaveUpper(d, f0, f1));
  const auto hi23 = hn::BitCast(dd, hn::InterleaveUpper(d, f2, f3));
  *r0 = hn::BitCast(d, hn::InterleaveLower(dd, lo01, lo23));
  *r1 = hn::BitCast(d, hn::InterleaveUpper(dd, lo01, lo23));
  *r2 = hn::BitCast(d, hn::InterleaveLower(dd, hi01, hi23));
  *r3 = hn::BitCast(d, hn::InterleaveUpper(dd, hi01, hi23));
}
#endif

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TRANSPOSE4_INL_H_
