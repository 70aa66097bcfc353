// The Sobol' sampler keeps the stratification its construction promises: the (0,2)-sequence in
// every decision's 2-D dimension (each aligned block of 2^m samples of a pixel is a (0,m,2)-net),
// 1-D strata in 1-D dimensions, progressive across passes, and the scrambles are permutations.
#include "engine/sampling/sobol.h"

#include <cstdint>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/rng.h"
#include "engine/sampling/sampler.h"

namespace ptlab {
namespace {

// True when the points form a (0,m,2)-net: every elementary interval of area 2^-m, of shape
// 2^-a x 2^-(m-a) for a = 0..m, holds exactly one of the 2^m points (coordinates as 32-bit
// fixed point, or floats in [0, 1) whose top m bits are the same).
bool IsZeroNet(const std::vector<Vec2f>& points, int m) {
  if (points.size() != (size_t(1) << m)) return false;
  for (int a = 0; a <= m; ++a) {
    std::vector<int> count(size_t(1) << m, 0);
    for (const Vec2f& p : points) {
      const uint64_t ix = uint64_t(double(p.x) * double(1u << a));
      const uint64_t iy = uint64_t(double(p.y) * double(1u << (m - a)));
      if (ix >= (1u << a) || iy >= (1u << (m - a))) return false;
      if (++count[size_t((ix << (m - a)) | iy)] != 1) return false;
    }
  }
  return true;
}

bool IsStratified1D(const std::vector<float>& xs, int m) {
  if (xs.size() != (size_t(1) << m)) return false;
  std::vector<int> count(size_t(1) << m, 0);
  for (float x : xs) {
    const uint64_t i = uint64_t(double(x) * double(1u << m));
    if (i >= (1u << m) || ++count[size_t(i)] != 1) return false;
  }
  return true;
}

TEST(Sobol, FirstPointsOfTheTwoDimensions) {
  // Natural (not Gray-code) order: x_i = xor of the direction numbers of i's set bits.
  const float x[8] = {0.0f, 0.5f, 0.25f, 0.75f, 0.125f, 0.625f, 0.375f, 0.875f};
  const float y[8] = {0.0f, 0.5f, 0.75f, 0.25f, 0.625f, 0.125f, 0.375f, 0.875f};
  for (uint32_t i = 0; i < 8; ++i) {
    EXPECT_EQ(FixedPointToFloat(SobolDimension0(i)), x[i]) << i;
    EXPECT_EQ(FixedPointToFloat(SobolDimension1(i)), y[i]) << i;
  }
}

TEST(Sobol, FastFormsEqualTheDefinitions) {
  // Every single index bit (each column of the generator matrix) and all of them at once.
  for (int bit = 0; bit < 32; ++bit)
    ASSERT_EQ(SobolDimension1Reversed(1u << bit), ReverseBits32(SobolDimension1(1u << bit))) << bit;
  ASSERT_EQ(SobolDimension1Reversed(~0u), ReverseBits32(SobolDimension1(~0u)));
  Pcg32 rng(8, 9);
  for (int k = 0; k < 100000; ++k) {
    const uint32_t index = k < 1000 ? uint32_t(k) : rng.NextUint();
    const SobolSeeds seeds{rng.NextUint(), rng.NextUint(), rng.NextUint()};
    ASSERT_EQ(SobolDimension1Reversed(index), ReverseBits32(SobolDimension1(index)));
    const uint32_t i = NestedUniformScramble(index, seeds.shuffle);
    const Vec2f p = ScrambledSobol2D(index, seeds);
    ASSERT_EQ(p.x, FixedPointToFloat(NestedUniformScramble(SobolDimension0(i), seeds.x)));
    ASSERT_EQ(p.y, FixedPointToFloat(NestedUniformScramble(SobolDimension1(i), seeds.y)));
    ASSERT_EQ(ScrambledSobol1D(index, seeds), p.x);
  }
}

TEST(Sobol, UnscrambledBlocksAreZeroNets) {
  for (int m = 0; m <= 12; ++m) {
    for (uint32_t block : {0u, 1u, 5u, 1000u}) {
      std::vector<Vec2f> pts;
      for (uint32_t i = block << m; i < (block + 1) << m; ++i)
        pts.push_back({FixedPointToFloat(SobolDimension0(i)), FixedPointToFloat(SobolDimension1(i))});
      EXPECT_TRUE(IsZeroNet(pts, m)) << "m " << m << " block " << block;
    }
  }
}

TEST(Sobol, ScrambledBlocksAreZeroNets) {
  Pcg32 rng(3, 4);
  for (int trial = 0; trial < 20; ++trial) {
    const SobolSeeds seeds{rng.NextUint(), rng.NextUint(), rng.NextUint()};
    for (int m = 0; m <= 12; ++m) {
      for (uint32_t block : {0u, 1u, 7u}) {
        std::vector<Vec2f> pts;
        for (uint32_t i = block << m; i < (block + 1) << m; ++i) pts.push_back(ScrambledSobol2D(i, seeds));
        ASSERT_TRUE(IsZeroNet(pts, m)) << "trial " << trial << " m " << m << " block " << block;
      }
    }
  }
}

TEST(Sobol, NestedUniformScrambleIsABlockPreservingPermutation) {
  // On 2^16 indices (the high bits fixed): a bijection that maps each aligned block of 2^k
  // indices onto an aligned block of 2^k indices.
  Pcg32 rng(5, 6);
  for (int trial = 0; trial < 4; ++trial) {
    const uint32_t seed = rng.NextUint();
    std::set<uint32_t> seen;
    for (uint32_t i = 0; i < (1u << 16); ++i) seen.insert(NestedUniformScramble(i, seed) >> 16);
    EXPECT_EQ(seen.size(), 1u) << "the high bits depend only on the high bits";
    std::set<uint32_t> low;
    for (uint32_t i = 0; i < (1u << 16); ++i) low.insert(NestedUniformScramble(i, seed) & 0xffffu);
    EXPECT_EQ(low.size(), size_t(1) << 16);
    for (int k = 1; k <= 8; ++k) {
      for (uint32_t b = 0; b < 4; ++b) {
        std::set<uint32_t> blocks;
        for (uint32_t i = b << k; i < (b + 1) << k; ++i) blocks.insert(NestedUniformScramble(i, seed) >> k);
        EXPECT_EQ(blocks.size(), 1u) << "k " << k;
      }
    }
  }
}

TEST(Sobol, ScramblingChangesThePoints) {
  // The scramble is not the identity: two seeds give different first points (a test that the
  // per-pixel seed reaches the points).
  const Vec2f a = ScrambledSobol2D(0, {1, 2, 3}), b = ScrambledSobol2D(0, {4, 5, 6});
  EXPECT_NE(a.x, b.x);
  EXPECT_NE(a.y, b.y);
}

// The sampler's own dimensions: the 16 first dimensions as the integrators read them
// (pixel, lens, then per vertex light pick, triangle, light point, lobe, direction, roulette).
TEST(PathSamplerSobol, FirstSixteenDimensionsAreStratifiedAtPowersOfTwo) {
  for (uint64_t pixel_seed : {1ull, 0x1234567890abcdefull, 42ull}) {
    for (uint32_t dim = 0; dim < 16; ++dim) {
      const bool two_d = dim < 2 || (dim - 2) % kDecisionsPerVertex == uint32_t(Decision::kLightPoint) ||
                         (dim - 2) % kDecisionsPerVertex == uint32_t(Decision::kBsdfDirection);
      for (int m = 0; m <= 10; ++m) {
        for (uint32_t pass = 0; pass < 3; ++pass) {  // samples [pass 2^m, (pass + 1) 2^m)
          std::vector<Vec2f> pts;
          std::vector<float> xs;
          for (uint32_t s = pass << m; s < (pass + 1) << m; ++s) {
            PathSampler sampler(SamplerType::kSobol, pixel_seed, s);
            if (two_d) pts.push_back(sampler.Get2D(dim));
            else xs.push_back(sampler.Get1D(dim));
          }
          if (two_d) {
            ASSERT_TRUE(IsZeroNet(pts, m)) << "dim " << dim << " m " << m << " pass " << pass;
          } else {
            ASSERT_TRUE(IsStratified1D(xs, m)) << "dim " << dim << " m " << m << " pass " << pass;
          }
        }
      }
    }
  }
}

TEST(PathSamplerSobol, SubSamplesStratifyTogether) {
  // Four emitter samples per vertex: the 4 x 2^m points of 2^m pixel samples form one net.
  const uint32_t dim = DecisionDimension(1, Decision::kLightPoint);
  for (int m = 0; m <= 8; ++m) {
    std::vector<Vec2f> pts;
    for (uint32_t s = 0; s < (1u << m); ++s) {
      PathSampler sampler(SamplerType::kSobol, 99, s);
      for (uint32_t i = 0; i < 4; ++i) pts.push_back(sampler.Get2D(dim, i, 4));
    }
    EXPECT_TRUE(IsZeroNet(pts, m + 2)) << m;
  }
}

TEST(PathSamplerSobol, DimensionsAndPixelsDiffer) {
  PathSampler a(SamplerType::kSobol, 7, 0), b(SamplerType::kSobol, 8, 0);
  const Vec2f a0 = a.Get2D(0), a1 = a.Get2D(1), b0 = b.Get2D(0);
  EXPECT_NE(a0.x, a1.x);
  EXPECT_NE(a0.x, b0.x);
  // Asking again gives the same point (no hidden state): dimensions are addressed, not drawn.
  EXPECT_EQ(a.Get2D(0).x, a0.x);
}

TEST(PathSamplerIndependent, ReproducesThePcg32Stream) {
  PathSampler sampler(SamplerType::kIndependent, 1234, 56);
  Pcg32 rng(1234, 56);
  for (int k = 0; k < 100; ++k) {
    if (k % 3 == 0) {
      const Vec2f u = sampler.Get2D(uint32_t(k));
      EXPECT_EQ(u.x, rng.NextFloat());
      EXPECT_EQ(u.y, rng.NextFloat());
    } else {
      EXPECT_EQ(sampler.Get1D(uint32_t(k)), rng.NextFloat());
    }
  }
}

TEST(PathSampler, Names) {
  for (const SamplerType t : {SamplerType::kIndependent, SamplerType::kSobol}) {
    SamplerType back;
    ASSERT_TRUE(SamplerTypeFromName(SamplerTypeName(t), &back));
    EXPECT_EQ(back, t);
  }
  SamplerType unused;
  EXPECT_FALSE(SamplerTypeFromName("halton", &unused));
}

TEST(PathSamplerSobol, ValuesStayBelowOne) {
  // The largest fixed-point value maps below 1 (float rounding of 2^32 - 1 would give 1).
  EXPECT_LT(FixedPointToFloat(0xffffffffu), 1.0f);
  for (uint32_t s = 0; s < 4096; ++s) {
    PathSampler sampler(SamplerType::kSobol, 3, s);
    for (uint32_t d = 0; d < 40; ++d) {
      const Vec2f u = sampler.Get2D(d);
      ASSERT_TRUE(u.x >= 0 && u.x < 1 && u.y >= 0 && u.y < 1);
    }
  }
}

}  // namespace
}  // namespace ptlab
