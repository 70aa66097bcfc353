// Vectorized shadow-row compaction: per-target kernel and dispatch.
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/wavefront/shadow_rows8.cpp"
#include "engine/wavefront/shadow_rows.h"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/store_selected-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

size_t CompactShadowRowsTarget(size_t n, const ShadowRowInputs& in, const ShadowRowOutputs& out) {
  const hn::CappedTag<float, 8> d;
  const hn::RebindToUnsigned<decltype(d)> du;
  const hn::Rebind<uint8_t, decltype(d)> d8;
  const size_t lanes = hn::Lanes(d);
  size_t c = 0, m = 0;
  for (; c + lanes <= n; c += lanes) {
    const auto traced_u = hn::Ne(hn::PromoteTo(du, hn::LoadU(d8, in.traced + c)), hn::Zero(du));
    if (hn::AllFalse(du, traced_u)) continue;
    const auto traced = hn::RebindMask(d, traced_u);
    const bool all = hn::AllTrue(du, traced_u);
    StoreSelected(du, hn::LoadU(du, in.request + c), traced_u, all, out.request + m);
    StoreSelected(d, hn::LoadU(d, in.o_x + c), traced, all, out.o_x + m);
    StoreSelected(d, hn::LoadU(d, in.o_y + c), traced, all, out.o_y + m);
    StoreSelected(d, hn::LoadU(d, in.o_z + c), traced, all, out.o_z + m);
    StoreSelected(d, hn::LoadU(d, in.d_x + c), traced, all, out.d_x + m);
    StoreSelected(d, hn::LoadU(d, in.d_y + c), traced, all, out.d_y + m);
    StoreSelected(d, hn::LoadU(d, in.d_z + c), traced, all, out.d_z + m);
    StoreSelected(d, hn::LoadU(d, in.r + c), traced, all, out.r + m);
    StoreSelected(d, hn::LoadU(d, in.g + c), traced, all, out.g + m);
    StoreSelected(d, hn::LoadU(d, in.b + c), traced, all, out.b + m);
    m += hn::CountTrue(du, traced_u);
  }
  // The rows after the last whole vector: the oracle.
  return m + ptlab::CompactShadowRows(n - c, in.From(c), out.From(m));
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/wavefront/shadow_rows8.h"

namespace ptlab::simd {

HWY_EXPORT(CompactShadowRowsTarget);

size_t CompactShadowRows(size_t n, const ShadowRowInputs& in, const ShadowRowOutputs& out) {
  if (n == 0) return 0;
  return HWY_DYNAMIC_DISPATCH(CompactShadowRowsTarget)(n, in, out);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
