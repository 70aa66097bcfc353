// Guide-table CDF inversion returns exactly what a binary search over the whole CDF returns.
#include "engine/sampling/guide_table.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/rng.h"

namespace ptlab {
namespace {

uint32_t Reference(const std::vector<float>& cdf, float u) {
  return uint32_t(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin());
}

// A normalised CDF of n weights; every `zero_every`-th weight is 0 (degenerate triangles give
// repeated CDF values), and the weights span six orders of magnitude.
std::vector<float> RandomCdf(Pcg32& rng, uint32_t n, uint32_t zero_every) {
  std::vector<double> w(n);
  double total = 0;
  for (uint32_t i = 0; i < n; ++i) {
    w[i] = (zero_every > 0 && i % zero_every == 0) ? 0.0 : std::pow(10.0, 6.0 * rng.NextFloat());
    total += w[i];
  }
  std::vector<float> cdf(n);
  double run = 0;
  for (uint32_t i = 0; i < n; ++i) cdf[i] = float((run += w[i]) / total);
  cdf[n - 1] = 1.0f;
  return cdf;
}

std::vector<float> HardUs(const std::vector<float>& cdf) {
  std::vector<float> us = {0.0f, std::nextafter(1.0f, 0.0f), 0.5f, 1e-30f};
  const uint32_t n = uint32_t(cdf.size());
  for (uint32_t b = 0; b <= n; ++b) {  // bucket edges and their neighbours
    const float e = float(b) / float(n);
    for (float v : {e, std::nextafter(e, 0.0f), std::nextafter(e, 2.0f)})
      if (v >= 0.0f && v < 1.0f) us.push_back(v);
  }
  for (const float c : cdf) {  // the CDF values themselves and their neighbours
    for (float v : {c, std::nextafter(c, 0.0f), std::nextafter(c, 2.0f)})
      if (v >= 0.0f && v < 1.0f) us.push_back(v);
  }
  return us;
}

TEST(GuideTable, EqualsBinarySearchOnRandomAndHardInputs) {
  Pcg32 rng(5, 9);
  long checked = 0;
  for (uint32_t n : {1u, 2u, 3u, 7u, 16u, 17u, 64u, 1000u, 4099u}) {
    for (uint32_t zero_every : {0u, 1u + n / 3, 2u}) {
      if (zero_every == 1 && n > 1) continue;
      std::vector<float> cdf = RandomCdf(rng, n, zero_every);
      std::vector<uint32_t> guide(n + 1);
      BuildGuideTable(cdf.data(), n, guide.data());
      std::vector<float> us = HardUs(cdf);
      for (int i = 0; i < 20000; ++i) us.push_back(rng.NextFloat());
      for (const float u : us) {
        ASSERT_EQ(GuidedUpperBound(cdf.data(), n, guide.data(), u), Reference(cdf, u))
            << "n " << n << " u " << u;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 100000);
}

// A guide built for other values (the CDF edited afterwards, as a test may do) or filled with
// garbage only costs speed: the verified search still returns the binary search's answer.
TEST(GuideTable, StaleOrGarbageGuideStillExact) {
  Pcg32 rng(8, 1);
  const uint32_t n = 500;
  const std::vector<float> built_for = RandomCdf(rng, n, 0);
  const std::vector<float> cdf = RandomCdf(rng, n, 7);
  std::vector<uint32_t> guide(n + 1);
  BuildGuideTable(built_for.data(), n, guide.data());
  std::vector<uint32_t> garbage(n + 1);
  for (uint32_t& g : garbage) g = rng.NextUint();
  for (int i = 0; i < 50000; ++i) {
    const float u = rng.NextFloat();
    ASSERT_EQ(GuidedUpperBound(cdf.data(), n, guide.data(), u), Reference(cdf, u));
    ASSERT_EQ(GuidedUpperBound(cdf.data(), n, garbage.data(), u), Reference(cdf, u));
  }
}

TEST(GuideTable, GuideBracketsEveryBucket) {
  Pcg32 rng(2, 2);
  const std::vector<float> cdf = RandomCdf(rng, 300, 5);
  std::vector<uint32_t> guide(301);
  BuildGuideTable(cdf.data(), 300, guide.data());
  EXPECT_TRUE(std::is_sorted(guide.begin(), guide.end()));
  EXPECT_EQ(guide[300], 300u);  // nothing exceeds 1
}

}  // namespace
}  // namespace ptlab
