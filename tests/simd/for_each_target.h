// Runs a test body once per compiled Highway target this CPU supports, with dispatch pinned to
// it (shared by the SIMD-vs-oracle tests).
#pragma once

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "hwy/targets.h"

namespace ptlab::test {

/// fn(target_name) per target; target_name_of_kernels() (simd::DispatchedTargetName) must report
/// the pinned target (a check that simd/ kernels really dispatch to it: every simd/*.cpp is
/// compiled for the same targets, simd/targets.h).
template <class NameFn, class Fn>
void ForEachTarget(NameFn&& target_name_of_kernels, Fn&& fn) {
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  for (int64_t t : targets) {
    hwy::SetSupportedTargetsForTest(t);
    SCOPED_TRACE(hwy::TargetName(t));
    ASSERT_STREQ(target_name_of_kernels(), hwy::TargetName(t));
    fn(hwy::TargetName(t));
  }
  hwy::SetSupportedTargetsForTest(0);
}

}  // namespace ptlab::test
