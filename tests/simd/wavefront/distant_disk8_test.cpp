// simd::SampleDistantDiskBatch against its oracle ptlab::SampleDistantDiskBatch
// (SampleDistantDisk per row), on every compiled target: radiance, pdf and the cone offset
// bit-identical, wi within simd/wavefront/distant_disk8.h's contract, for 10^6 random rows and the hard
// cases (u = 0, the largest float below 1, 1; cones from the smallest accepted to the full
// sphere; rotated frames; batch tails; a black disk), and no NaN or Inf out. NaN numbers are
// not fed: SampleDistantDisk itself returns a NaN direction for them.
#include "simd/targets.h"  // first: the same target policy as simd/
#include "simd/dispatched_target.h"
#include "simd/wavefront/distant_disk8.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/core/rng.h"
#include "engine/core/transform.h"
#include "engine/light/distant_disk.h"
#include "engine/wavefront/distant_disk.h"
#include "tests/simd/for_each_target.h"
#include "tests/simd/sample_columns.h"

namespace ptlab {
namespace {

constexpr float kWiTolerance = 1e-6f;  // |Δ| per component, simd/wavefront/distant_disk8.h

using test::SampleColumns;

// `random` random rows, then each number on 0, the largest float below 1 and 1 (and tiny) with
// the other random, and every pair of those.
void MakeRows(size_t random, std::vector<float>* u_x, std::vector<float>* u_y) {
  Pcg32 rng(7, 11);
  for (size_t i = 0; i < random; ++i)
    u_x->push_back(rng.NextFloat()), u_y->push_back(rng.NextFloat());
  const float edges[] = {0.0f, -0.0f, 1e-40f, 0x1p-24f, 0.5f, 0x1.fffffep-1f, 1.0f};
  for (float a : edges) {
    u_x->push_back(a), u_y->push_back(rng.NextFloat());
    u_x->push_back(rng.NextFloat()), u_y->push_back(a);
    for (float b : edges) u_x->push_back(a), u_y->push_back(b);
  }
}

void ExpectBatchMatchesOracle(const DistantDiskTable& table, uint32_t disk, size_t random) {
  std::vector<float> u_x, u_y;
  MakeRows(random, &u_x, &u_y);
  const size_t n = u_x.size();
  const EnvironmentBatchInputs in{u_x.data(), u_y.data()};
  SampleColumns want(n);
  SampleDistantDiskBatch(table, disk, n, in, want.Out());
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
    float seen_wi = 0;
    // Every tail length: batches of n, and of n - 1 ... n - 7 rows.
    for (size_t cut = 0; cut < 8; ++cut) {
      const size_t m = n - cut;
      SampleColumns got(m);
      simd::SampleDistantDiskBatch(table, disk, m, in, got.Out());
      // pdf tolerance 0: the disk's pdf is its constant 1 / solid angle on both paths.
      const test::SampleColumnsDiff diff =
          test::ExpectSampleColumnsMatch(got, want, m, kWiTolerance, 0);
      seen_wi = std::max(seen_wi, diff.seen_wi);
      const size_t first = diff.first;
      if (first < m) {
        ADD_FAILURE() << "row " << first << " u = (" << u_x[first] << ", " << u_y[first]
                      << "): wi (" << got.col[0][first] << ", " << got.col[1][first] << ", "
                      << got.col[2][first] << ") want (" << want.col[0][first] << ", "
                      << want.col[1][first] << ", " << want.col[2][first] << ")";
        break;
      }
    }
    std::printf("  %s: %zu rows, seen |Δwi| %.3g\n", target, n, double(seen_wi));
  });
}

// The cone's local z: 1 - s is exact on both paths, so the oracle's cosθ is reproduced too.
void ExpectLocalZBitIdentical(const DistantDiskTable& table) {
  std::vector<float> u_x, u_y;
  MakeRows(10007, &u_x, &u_y);
  const size_t n = u_x.size();
  SampleColumns want(n);
  SampleDistantDiskBatch(table, 0, n, {u_x.data(), u_y.data()}, want.Out());
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    SampleColumns got(n);
    simd::SampleDistantDiskBatch(table, 0, n, {u_x.data(), u_y.data()}, got.Out());
    for (size_t i = 0; i < n; ++i)
      ASSERT_EQ(std::bit_cast<uint32_t>(got.col[2][i]), std::bit_cast<uint32_t>(want.col[2][i]))
          << "row " << i;
  });
}

Frame Rotated(const Vec3f& axis, float degrees) {
  const Transform rotate = Transform::Rotate(Normalize(axis), degrees);
  Frame f;
  f.s = rotate.ApplyVector({1, 0, 0}), f.t = rotate.ApplyVector({0, 1, 0});
  f.n = rotate.ApplyVector({0, 0, 1});
  return f;
}

DistantDiskTable OneDisk(float theta_a, const Frame& to_world,
                         const Color3f& radiance = {2, 3, 4}) {
  DistantDiskTable table;
  const StatusOr<uint32_t> row = AddDistantDisk(radiance, theta_a, to_world, "test", &table);
  EXPECT_TRUE(row.ok() && *row == 0);
  return table;
}

TEST(DistantDisk8, BatchMatchesOracleOnRotatedCone) {
  ExpectBatchMatchesOracle(OneDisk(10, Rotated({1, 2, 3}, 40)), 0, 1000003);
}

TEST(DistantDisk8, BatchMatchesOracleFromTinyConesToTheFullSphere) {
  // 3.3e-5 degrees: the smallest cone AddDistantDisk accepts (solid angle ~1e-12 sr).
  for (float theta_a : {3.3e-5f, 1e-3f, 0.53f, 45.0f, 90.0f, 135.0f, 179.99f, 180.0f}) {
    SCOPED_TRACE(theta_a);
    ExpectBatchMatchesOracle(OneDisk(theta_a, Rotated({-1, 0.5f, 0.25f}, 123)), 0, 100003);
  }
}

TEST(DistantDisk8, LocalCosThetaIsBitIdenticalOnTheAxisFrame) {
  // Under the identity frame wi.z = 1 - s exactly (s.z = t.z = 0), whatever sinφ and cosφ are.
  for (float theta_a : {3.3e-5f, 10.0f, 180.0f}) ExpectLocalZBitIdentical(OneDisk(theta_a, {}));
}

TEST(DistantDisk8, SecondRowOfATableAndABlackDisk) {
  DistantDiskTable table = OneDisk(30, {});
  ASSERT_TRUE(AddDistantDisk({0.5f, 0, 7}, 5, Rotated({0, 1, 0}, 90), "test", &table).ok());
  ExpectBatchMatchesOracle(table, 1, 10003);
  // A black disk gives no sample: every row all zero on both paths.
  const DistantDiskTable black = OneDisk(20, {}, {0, 0, 0});
  ExpectBatchMatchesOracle(black, 0, 10003);
  std::vector<float> u(17, 0.25f), col(17 * 7, -1.0f);
  simd::SampleDistantDiskBatch(black, 0, 17, {u.data(), u.data()},
                               {col.data(), col.data() + 17, col.data() + 34, col.data() + 51,
                                col.data() + 68, col.data() + 85, col.data() + 102});
  for (float v : col) EXPECT_EQ(v, 0.0f);
}

}  // namespace
}  // namespace ptlab
