// simd::SplatSamples against its oracle ptlab::SplatSamples: bit-identical film sums on every
// compiled target, for every filter shape and radius, samples inside, on the edges of and
// outside the block, in random and in the wavefront's order, with extreme radiance.
#include "simd/wavefront/splat8.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "engine/core/rng.h"
#include "engine/render/filter.h"
#include "engine/wavefront/splat.h"
#include "simd/dispatched_target.h"
#include "simd/targets.h"  // first: the same target policy as simd/
#include "tests/simd/for_each_target.h"

namespace ptlab {
namespace {

struct Columns {
  std::vector<float> sx, sy, r, g, b;
  FilmSamples View() const {
    return {sx.data(), sy.data(), r.data(), g.data(), b.data(), sx.size()};
  }
};

// Random positions over the block and a margin around it, plus the hard cases: pixel corners
// and centres (taps exactly at the radius), the block's edges, far outside.
Columns MakeSamples(const FilmBlock& block, size_t random_count, Pcg32& rng) {
  Columns c;
  const auto push = [&c, &rng](float x, float y) {
    c.sx.push_back(x), c.sy.push_back(y);
    c.r.push_back(rng.NextFloat() * 4.0f), c.g.push_back(rng.NextFloat());
    c.b.push_back(rng.NextFloat() < 0.1f ? 0.0f : 1e3f * rng.NextFloat());
  };
  const float x0 = float(block.x0()) - 10.0f, y0 = float(block.y0()) - 10.0f;
  const float w = float(block.width()) + 20.0f, h = float(block.height()) + 20.0f;
  for (size_t i = 0; i < random_count; ++i) {
    const float sx = x0 + w * rng.NextFloat(), sy = y0 + h * rng.NextFloat();  // in this order
    push(sx, sy);
  }
  for (int y = block.y0() - 9; y <= block.y0() + block.height() + 9; ++y)
    for (int x = block.x0() - 9; x <= block.x0() + block.width() + 9; ++x)
      for (const float f : {0.0f, 0.5f, 0.25f}) {
        push(float(x) + f, float(y) + 0.5f - f);
        push(float(x) + f, float(y) + f);
      }
  push(-1e6f, 3.0f), push(3.0f, 1e6f);
  return c;
}

/// How many accumulators of the two blocks differ in their bits.
size_t DifferentSums(const FilmBlock& a, const FilmBlock& b) {
  size_t differ = 0;
  for (size_t i = 0; i < a.sums().size(); ++i)
    differ += std::memcmp(&a.sums()[i], &b.sums()[i], sizeof(float)) != 0;
  return differ;
}

TEST(Splat8, MatchesOracleBitForBitOnEveryTarget) {
  using T = FilterDesc::Type;
  const std::vector<FilterDesc> filters = {
      {T::kGaussian, 2.0f, 0.5f},
      {T::kGaussian, 3.0f, 1.0f},
      {T::kGaussian, 8.0f, 2.0f},
      {T::kGaussian, 0.5f, 0.25f},
      {T::kTent, 1.0f, 0},
      {T::kTent, 2.5f, 0},
      {T::kBox, 0.5f, 0},
      {T::kBox, 1.5f, 0},
      {T::kBox, 0.0f, 0},
      // Mitsuba's staircase (FilterDesc::steps), as Mitsuba scenes splat.
      {T::kGaussian, 2.0f, 0.5f, 31},
      {T::kTent, 1.0f, 0, 31}};
  Pcg32 rng(5, 11);
  for (const FilterDesc& desc : filters) {
    const PixelFilter filter(desc);
    SCOPED_TRACE("type " + std::to_string(int(desc.type)) + " radius " +
                 std::to_string(desc.radius));
    // An odd-sized block away from the origin (rows of odd pixel counts at its edges).
    FilmBlock oracle(-3, 5, 37, 21);
    const Columns samples = MakeSamples(oracle, 20000, rng);
    SplatSamples(filter, samples.View(), &oracle);
    test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
      FilmBlock block(-3, 5, 37, 21);
      simd::SplatSamples(filter, samples.View(), &block);
      ASSERT_EQ(block.sums().size(), oracle.sums().size());
      EXPECT_EQ(DifferentSums(block, oracle), 0u) << target;
    });
    double total = 0;
    for (const float v : oracle.sums()) total += v;
    EXPECT_GT(total, 0.0);  // the samples reached the block
  }
}

// The wavefront's order (row, pixel, 8 samples per pixel: runs of samples on one pixel, whose
// footprints overlap and shift by one pixel) with extreme radiance: zero, subnormal, tiny,
// huge (w·L overflows to infinity), on a block whose edges cut the footprints.
TEST(Splat8, MatchesOracleInWaveOrderWithExtremeRadianceOnEveryTarget) {
  using T = FilterDesc::Type;
  const float radiance[] = {0.0f, 1e-41f, 1e-30f, 0.5f, 7.0f, 1e30f, 3e38f};
  for (const FilterDesc& desc :
       {FilterDesc{T::kGaussian, 2.0f, 0.5f}, FilterDesc{T::kTent, 1.5f, 0},
        FilterDesc{T::kBox, 0.5f, 0}, FilterDesc{T::kGaussian, 2.0f, 0.5f, 31}}) {
    const PixelFilter filter(desc);
    Pcg32 rng(17, 3);
    Columns c;
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 20; ++x)
        for (int s = 0; s < 8; ++s) {
          // Every fourth sample on a pixel edge or centre (taps exactly at the radius).
          const bool edge = rng.NextFloat() < 0.25f;
          c.sx.push_back(float(x) + (edge ? 0.5f * float(s & 1) : rng.NextFloat()));
          c.sy.push_back(float(y) + (edge ? 0.5f * float(s >> 2) : rng.NextFloat()));
          c.r.push_back(radiance[rng.NextUint() % 7]), c.g.push_back(radiance[rng.NextUint() % 7]);
          c.b.push_back(radiance[rng.NextUint() % 7]);
        }
    // Positions from 2^24 on (the 8-sample groups' vector footprint hands them to the
    // per-sample path), in the middle of the samples.
    for (const float far : {16777216.0f, -16777216.0f, 3e7f, 16777215.0f}) {
      c.sx.insert(c.sx.begin() + 100, far), c.sy.insert(c.sy.begin() + 100, 3.5f);
      c.r.insert(c.r.begin() + 100, 1.0f), c.g.insert(c.g.begin() + 100, 1.0f);
      c.b.insert(c.b.begin() + 100, 1.0f);
    }
    // The block starts inside the samples' range and ends before it: clipped footprints.
    FilmBlock oracle(1, 2, 17, 9);
    SplatSamples(filter, c.View(), &oracle);
    test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
      FilmBlock block(1, 2, 17, 9);
      simd::SplatSamples(filter, c.View(), &block);
      EXPECT_EQ(DifferentSums(block, oracle), 0u) << target << " radius " << desc.radius;
    });
  }
}

// The box filter's common case: runs of 8 and 16 samples inside one pixel (each 8-sample group
// on one pixel: the kernel adds the group in a register), groups that straddle two pixels
// (runs of 12), with ordinary and extreme radiance.
TEST(Splat8, BoxRunsOnOnePixelMatchOracleOnEveryTarget) {
  const PixelFilter filter(FilterDesc{FilterDesc::Type::kBox, 0.5f, 0});
  const float radiance[] = {0.0f, 1e-41f, 0.25f, 0.5f, 7.0f, 1e30f, 3e38f};
  for (int run : {8, 16, 12}) {
    Pcg32 rng(23, uint64_t(run));
    Columns c;
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 10; ++x)
        for (int s = 0; s < run; ++s) {
          c.sx.push_back(float(x) + rng.NextFloat()), c.sy.push_back(float(y) + rng.NextFloat());
          const bool extreme = rng.NextFloat() < 0.1f;
          c.r.push_back(extreme ? radiance[rng.NextUint() % 7] : rng.NextFloat());
          c.g.push_back(rng.NextFloat());
          c.b.push_back(extreme ? radiance[rng.NextUint() % 7] : 1.0f);
        }
    FilmBlock oracle(0, 0, 10, 6);
    SplatSamples(filter, c.View(), &oracle);
    test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
      FilmBlock block(0, 0, 10, 6);
      simd::SplatSamples(filter, c.View(), &block);
      EXPECT_EQ(DifferentSums(block, oracle), 0u) << target << " run " << run;
    });
  }
}

}  // namespace
}  // namespace ptlab
