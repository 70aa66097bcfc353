// simd::StartCameraPaths against its oracle ptlab::StartCameraPaths: every output bit-identical
// on every compiled target, for both samplers, random rows and the hard cases (pixel 0, the
// largest sample index, seeds 0 and 2^64 - 1, image widths 1 and 2^31 with pixel indices near
// 2^63, batch tails of every length); the sampler's film and lens columns untouched by `sobol`.
// Plus the oracle against PCG32 itself: the stream Pcg32(PixelSeed, s) and its first four draws.
#include "simd/wavefront/camera_paths8.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "engine/core/rng.h"
#include "engine/wavefront/camera_paths.h"
#include "simd/dispatched_target.h"
#include "simd/targets.h"  // first: the same target policy as simd/
#include "tests/simd/for_each_target.h"

namespace ptlab {
namespace {

struct Rows {
  std::vector<int32_t> px, py;
  std::vector<uint32_t> sample;
  size_t size() const { return px.size(); }
  void Push(int32_t x, int32_t y, uint32_t s) {
    px.push_back(x), py.push_back(y), sample.push_back(s);
  }
  CameraPathInputs In(size_t from = 0) const {
    return {px.data() + from, py.data() + from, sample.data() + from};
  }
};

/// Output columns, the float ones preset to a NaN pattern that no kernel writes.
struct Result {
  std::vector<PathSampler> sampler;
  std::vector<float> sx, sy;
  std::vector<Vec2f> lens;
  explicit Result(size_t n)
      : sampler(n), sx(n, kSentinel), sy(n, kSentinel), lens(n, {kSentinel, kSentinel}) {}
  CameraPathOutputs Out(size_t from = 0) {
    return {sampler.data() + from, sx.data() + from, sy.data() + from, lens.data() + from};
  }
  static inline const float kSentinel = std::bit_cast<float>(0x7fc0beefu);
};

bool SameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

void ExpectSame(const Result& want, const Result& got, size_t n, const char* what) {
  for (size_t k = 0; k < n; ++k) {
    ASSERT_TRUE(want.sampler[k] == got.sampler[k]) << what << " row " << k;
    ASSERT_TRUE(SameBits(want.sx[k], got.sx[k]) && SameBits(want.sy[k], got.sy[k]))
        << what << " row " << k << ": " << want.sx[k] << " " << got.sx[k];
    ASSERT_TRUE(SameBits(want.lens[k].x, got.lens[k].x) && SameBits(want.lens[k].y, got.lens[k].y))
        << what << " row " << k;
  }
}

Rows RandomRows(Pcg32& rng, size_t n, int32_t max_x, int32_t max_y) {
  Rows r;
  for (size_t k = 0; k < n; ++k) {
    r.Push(int32_t(rng.NextUint() % uint32_t(max_x)), int32_t(rng.NextUint() % uint32_t(max_y)),
           rng.NextUint() % 4 == 0 ? rng.NextUint() % 8 : rng.NextUint());
  }
  return r;
}

TEST(CameraPaths, OracleIsPcg32SeededByThePixelAndSample) {
  Pcg32 rng(3, 1);
  const Rows rows = RandomRows(rng, 100, 4096, 4096);
  const uint64_t seed = 12345, width = 4096;
  Result out(rows.size());
  StartCameraPaths(SamplerType::kIndependent, seed, width, rows.size(), rows.In(), out.Out());
  for (size_t k = 0; k < rows.size(); ++k) {
    const uint64_t pixel = uint64_t(rows.py[k]) * width + uint64_t(rows.px[k]);
    const uint64_t pixel_seed = MixBits(seed * kPixelSeedStride + pixel);
    Pcg32 stream(pixel_seed, rows.sample[k]);
    const float jx = stream.NextFloat(), jy = stream.NextFloat();
    const float lx = stream.NextFloat(), ly = stream.NextFloat();
    EXPECT_EQ(out.sx[k], float(rows.px[k]) + jx);
    EXPECT_EQ(out.sy[k], float(rows.py[k]) + jy);
    EXPECT_EQ(out.lens[k].x, lx);
    EXPECT_EQ(out.lens[k].y, ly);
    // The sampler goes on where the four draws left the stream.
    PathSampler expected(SamplerType::kIndependent, pixel_seed, rows.sample[k]);
    for (int i = 0; i < 2; ++i) expected.Get2D(0);
    EXPECT_TRUE(out.sampler[k] == expected) << k;
    EXPECT_EQ(out.sampler[k].Get1D(0), stream.NextFloat()) << k;
    EXPECT_EQ(out.sampler[k].pixel_seed32(), uint32_t(pixel_seed) ^ uint32_t(pixel_seed >> 32));
    EXPECT_EQ(out.sampler[k].index(), rows.sample[k]);
  }
}

TEST(CameraPaths, SimdEqualsOracleOnEveryTarget) {
  Pcg32 rng(17, 5);
  struct Case {
    uint64_t seed, width;
    Rows rows;
  };
  std::vector<Case> cases;
  cases.push_back({1, 640, RandomRows(rng, 4099, 640, 480)});
  cases.push_back({0, 1, RandomRows(rng, 77, 1, 1 << 20)});
  cases.push_back({~0ull, 1u << 31, RandomRows(rng, 333, 1 << 30, 1 << 30)});
  // Hard rows: pixel 0, the last pixel of a huge image (py · width + px = 2^63 − 1), the
  // sample indices 0 and 2^32 − 1.
  Rows hard;
  const int32_t big = std::numeric_limits<int32_t>::max();
  for (uint32_t s : {0u, 1u, 0xffffffffu, 0x80000000u}) {
    hard.Push(0, 0, s), hard.Push(big, 0, s), hard.Push(0, big, s), hard.Push(big, big, s);
  }
  cases.push_back({0x9e3779b97f4a7c15ull, uint64_t(1) << 32, hard});
  cases.push_back({7, uint64_t(1) << 32, hard});
  for (const Case& c : cases) {
    for (SamplerType type : {SamplerType::kIndependent, SamplerType::kSobol}) {
      const size_t n = c.rows.size();
      Result want(n);
      StartCameraPaths(type, c.seed, c.width, n, c.rows.In(), want.Out());
      test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
        Result got(n);
        simd::StartCameraPaths(type, c.seed, c.width, n, c.rows.In(), got.Out());
        ExpectSame(want, got, n, target);
        // Every tail length, starting at an offset that is not a multiple of a vector.
        for (size_t m = 0; m <= 17 && m + 3 < n; ++m) {
          Result part(n);
          simd::StartCameraPaths(type, c.seed, c.width, m, c.rows.In(3), part.Out(3));
          for (size_t k = 0; k < m; ++k) {
            ASSERT_TRUE(part.sampler[3 + k] == want.sampler[3 + k]) << target << " m " << m;
            ASSERT_TRUE(SameBits(part.sx[3 + k], want.sx[3 + k])) << target << " m " << m;
          }
          ASSERT_TRUE(SameBits(part.sx[3 + m], Result::kSentinel)) << target << " m " << m;
        }
      });
      // The independent sampler's numbers: finite, inside the pixel, lens point in [0, 1)².
      // `sobol` leaves the film and lens columns to the wavefront's batch draws.
      for (size_t k = 0; k < n; ++k) {
        if (type == SamplerType::kSobol) {
          ASSERT_TRUE(SameBits(want.sx[k], Result::kSentinel) &&
                      SameBits(want.lens[k].y, Result::kSentinel));
          continue;
        }
        ASSERT_GE(want.sx[k], float(c.rows.px[k]));
        ASSERT_LE(want.sx[k], float(c.rows.px[k]) + 1.0f);  // = px + 1 only where float rounds
        ASSERT_TRUE(want.lens[k].x >= 0.0f && want.lens[k].x < 1.0f);
        ASSERT_TRUE(want.lens[k].y >= 0.0f && want.lens[k].y < 1.0f);
      }
    }
  }
}

}  // namespace
}  // namespace ptlab
