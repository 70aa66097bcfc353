// The SIMD Sobol' sampler is bit-identical to its scalar oracle on every compiled Highway
// target, for random and adversarial seeds, indices and dimensions, and for any row count.
// clang-format off
#include "simd/targets.h"  // first: the target policy (must precede every hwy/ include)
// clang-format on
#include "simd/dispatched_target.h"
#include "simd/wavefront/sobol8.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "engine/core/rng.h"
#include "engine/wavefront/sobol.h"
#include "tests/simd/for_each_target.h"

namespace ptlab {
namespace {

template <class Fn>
void ForEachTarget(Fn&& fn) {
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) { fn(); });
}

TEST(Sobol8, BitIdenticalToTheOracleOnEveryTarget) {
  Pcg32 rng(17, 19);
  const size_t n = 1 << 17;  // 2^17 rows x 12 dimensions x (1-D + 2-D) > 10^6 values a target
  std::vector<uint32_t> seed(n), index(n);
  const uint32_t hard[] = {0u, 1u, 2u, 0x7fffffffu, 0x80000000u, 0xfffffffeu, 0xffffffffu,
                           0x55555555u, 0xaaaaaaaau, 0x00ff00ffu};
  for (size_t i = 0; i < n; ++i) {
    seed[i] = i < 100 ? hard[i % 10] : rng.NextUint();
    index[i] = i < 100 ? hard[(i / 10) % 10] : (i % 3 == 0 ? uint32_t(i) : rng.NextUint());
  }
  std::vector<float> ox(n), oy(n), sx(n), sy(n), s1(n), o1(n);
  ForEachTarget([&] {
    for (uint32_t dim : {0u, 1u, 2u, 3u, 7u, 31u, 100u, 1000u, 65535u, 0x9e3779b9u, 0xfffffffeu,
                         0xffffffffu}) {
      SCOPED_TRACE(dim);
      // Odd row counts exercise the tail that finishes a batch row by row.
      for (size_t rows : {n, size_t(1), size_t(7), size_t(13)}) {
        ScrambledSobol2DBatch(seed.data(), index.data(), dim, rows, ox.data(), oy.data());
        simd::ScrambledSobol2DBatch(seed.data(), index.data(), dim, rows, sx.data(), sy.data());
        ASSERT_EQ(std::memcmp(ox.data(), sx.data(), rows * sizeof(float)), 0);
        ASSERT_EQ(std::memcmp(oy.data(), sy.data(), rows * sizeof(float)), 0);
        ScrambledSobol1DBatch(seed.data(), index.data(), dim, rows, o1.data());
        simd::ScrambledSobol1DBatch(seed.data(), index.data(), dim, rows, s1.data());
        ASSERT_EQ(std::memcmp(o1.data(), s1.data(), rows * sizeof(float)), 0);
      }
    }
  });
  // Every value is a float in [0, 1).
  for (size_t i = 0; i < n; ++i) ASSERT_TRUE(sx[i] >= 0 && sx[i] < 1 && sy[i] >= 0 && sy[i] < 1);
}

}  // namespace
}  // namespace ptlab
