// Per-target helper (re-included once per Highway target): the selected lanes of a vector
// stored in order, as CompressBlendedStore does, with a plain store when every lane is
// selected (the common case of the stages' row compaction, and a few cycles cheaper per column).

#if defined(PTLAB_SIMD_STORE_SELECTED_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_STORE_SELECTED_INL_H_
#undef PTLAB_SIMD_STORE_SELECTED_INL_H_
#else
#define PTLAB_SIMD_STORE_SELECTED_INL_H_
#endif

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

/// The lanes of v that m selects, in lane order, at p (exactly CountTrue(m) elements written);
/// `all`: every lane of m is set (the caller's AllTrue, shared by its columns).
template <class D>
HWY_INLINE void StoreSelected(D d, hn::Vec<D> v, hn::Mask<D> m, bool all, hn::TFromD<D>* p) {
  if (all) {
    hn::StoreU(v, d, p);
  } else {
    hn::CompressBlendedStore(v, m, d, p);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_STORE_SELECTED_INL_H_
