// Highway dynamic dispatch of simd/dispatched_target: the target name, compiled per target.
// clang-format off
#include "simd/targets.h"  // first: the target policy
// clang-format on

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/dispatched_target.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

const char* DispatchedTargetNameTarget() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/dispatched_target.h"

namespace ptlab::simd {

HWY_EXPORT(DispatchedTargetNameTarget);

const char* DispatchedTargetName() { return HWY_DYNAMIC_DISPATCH(DispatchedTargetNameTarget)(); }

}  // namespace ptlab::simd
#endif  // HWY_ONCE
