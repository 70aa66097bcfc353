// Pcg32's jump-ahead (Pcg32JumpOf) against stepping, through Pcg32::FromState.
#include "engine/core/rng.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace ptlab {
namespace {

// The state k steps on, by stepping: read back through FromState, which draws from it.
TEST(Pcg32, JumpOfIsSteppingKTimes) {
  Pcg32 seeds(17, 4);
  for (int trial = 0; trial < 1000; ++trial) {
    const uint64_t state = (uint64_t(seeds.NextUint()) << 32) | seeds.NextUint();
    const uint64_t inc = ((uint64_t(seeds.NextUint()) << 32) | seeds.NextUint()) | 1u;
    Pcg32 stepped = Pcg32::FromState(state, inc);
    for (uint32_t k = 0; k <= 9; ++k) {
      const Pcg32Jump jump = Pcg32JumpOf(k);
      const Pcg32 jumped = Pcg32::FromState(state * jump.mul + inc * jump.add, inc);
      ASSERT_TRUE(jumped == stepped) << "state " << state << ", " << k << " steps";
      stepped.NextUint();
    }
  }
  static_assert(Pcg32JumpOf(0).mul == 1 && Pcg32JumpOf(0).add == 0);
  static_assert(Pcg32JumpOf(1).mul == kPcg32Multiplier && Pcg32JumpOf(1).add == 1);
}

}  // namespace
}  // namespace ptlab
