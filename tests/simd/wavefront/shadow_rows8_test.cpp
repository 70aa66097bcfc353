// simd::CompactShadowRows against its oracle ptlab::CompactShadowRows: the same count and
// bit-identical rows on every compiled target, for random rows (flags 0, 1 and other non-zero
// bytes; NaN, Inf and -0 among the values) at every traced fraction from none to all, batch
// sizes around whole vectors, and out's rows past the count untouched.
#include "simd/wavefront/shadow_rows8.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "engine/core/rng.h"
#include "engine/wavefront/shadow_rows.h"
#include "simd/dispatched_target.h"
#include "simd/targets.h"  // first: the same target policy as simd/
#include "tests/simd/for_each_target.h"

namespace ptlab {
namespace {

constexpr size_t kFloatColumns = 9;  // o, d, contribution

struct Rows {
  std::vector<uint8_t> traced;
  std::vector<uint32_t> request;
  std::vector<float> f[kFloatColumns];

  Rows(Pcg32& rng, size_t n, uint32_t traced_percent) {
    const float odd[] = {0.0f,
                         -0.0f,
                         std::numeric_limits<float>::infinity(),
                         std::numeric_limits<float>::quiet_NaN(),
                         1e-40f,
                         -3.5f};
    for (size_t c = 0; c < n; ++c) {
      const bool on = rng.NextUint() % 100 < traced_percent;
      traced.push_back(on ? uint8_t(1 + rng.NextUint() % 255) : 0);
      request.push_back(rng.NextUint());
      for (std::vector<float>& col : f)
        col.push_back(rng.NextUint() % 8 == 0 ? odd[rng.NextUint() % 6] : rng.NextFloat() * 4 - 2);
    }
  }
  ShadowRowInputs In() const {
    return {traced.data(), request.data(), f[0].data(), f[1].data(), f[2].data(), f[3].data(),
            f[4].data(),   f[5].data(),    f[6].data(), f[7].data(), f[8].data()};
  }
};

/// n rows of room and 3 more, garbage-filled.
struct Out {
  std::vector<uint32_t> request;
  std::vector<float> f[kFloatColumns];
  explicit Out(size_t n) : request(n + 3, 0xdeadbeefu) {
    for (std::vector<float>& col : f) col.assign(n + 3, -7.25f);
  }
  ShadowRowOutputs View() {
    return {request.data(), f[0].data(), f[1].data(), f[2].data(), f[3].data(),
            f[4].data(),    f[5].data(), f[6].data(), f[7].data(), f[8].data()};
  }
};

void ExpectSameAsOracle(const Rows& rows) {
  const size_t n = rows.traced.size();
  Out want(n), got(n);
  const size_t want_n = CompactShadowRows(n, rows.In(), want.View());
  const size_t got_n = simd::CompactShadowRows(n, rows.In(), got.View());
  ASSERT_EQ(want_n, got_n) << n << " rows";
  size_t traced = 0;
  for (const uint8_t t : rows.traced) traced += t != 0;
  ASSERT_EQ(want_n, traced);
  ASSERT_EQ(std::memcmp(want.request.data(), got.request.data(), (n + 3) * 4), 0) << n << " rows";
  for (size_t i = 0; i < kFloatColumns; ++i)
    ASSERT_EQ(std::memcmp(want.f[i].data(), got.f[i].data(), (n + 3) * 4), 0)
        << "column " << i << ", " << n << " rows";
}

TEST(ShadowRows8, MatchesOracle) {
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    Pcg32 rng(3, 17);
    for (const uint32_t percent : {0u, 1u, 30u, 50u, 90u, 100u}) {
      for (const size_t n : {0, 1, 3, 4, 5, 7, 8, 9, 15, 16, 17, 31, 64, 257, 4099}) {
        ExpectSameAsOracle(Rows(rng, n, percent));
        if (HasFatalFailure()) return;
      }
    }
  });
}

}  // namespace
}  // namespace ptlab
