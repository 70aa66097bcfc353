// PTLAB_TARGET pins the dispatch to one compiled target; a bad name is an error naming the
// accepted ones.
#include "simd/targets.h"  // first: the same compiled target set as simd/

#include "simd/target_select.h"

#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "hwy/targets.h"
#include "simd/dispatched_target.h"

namespace ptlab {
namespace {

TEST(TargetSelect, PinsEveryCompiledTargetAndRejectsOthers) {
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  for (int64_t t : targets) {
    std::string name = hwy::TargetName(t);
    for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
    ASSERT_EQ(setenv("PTLAB_TARGET", name.c_str(), 1), 0);
    const Status s = simd::SelectTargetFromEnvironment();
    EXPECT_TRUE(s.ok()) << s.message();
    // The kernels dispatch there now (the traversal's dispatch is one of them).
    EXPECT_STREQ(simd::DispatchedTargetName(), hwy::TargetName(t));
  }
  ASSERT_EQ(setenv("PTLAB_TARGET", "AVX9000", 1), 0);
  const Status bad = simd::SelectTargetFromEnvironment();
  EXPECT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find("AVX9000"), std::string::npos) << bad.message();
  EXPECT_NE(bad.message().find(hwy::TargetName(targets.front())), std::string::npos)
      << bad.message();
  ASSERT_EQ(unsetenv("PTLAB_TARGET"), 0);
  EXPECT_TRUE(simd::SelectTargetFromEnvironment().ok());
  hwy::SetSupportedTargetsForTest(0);
}

}  // namespace
}  // namespace ptlab
