// simd::ContinuePaths against its oracle ptlab::ContinuePaths (the wavefront's per-row update
// of each sampled path after the bsdf slot): the spawn rows, owners and the whole path state
// bit-identical on every compiled target, for a million random rows and the hard cases (pdf 0,
// -0, NaN, denormal, negative; weights 0, -0, Inf, NaN, denormal; throughputs that turn black,
// with cut_black on and off; eta 0, Inf, NaN; Whitted's roulette scale; batch sizes 0 to 2
// vectors and more), the rows past the written ones and the paths not in the batch untouched.
#include "simd/wavefront/continuation8.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "engine/core/rng.h"
#include "engine/wavefront/continuation.h"
#include "simd/dispatched_target.h"
#include "simd/targets.h"                // first: the same target policy as simd/
#include "tests/simd/for_each_target.h"
#include "tests/simd/row_checks.h"  // hwy/targets.h, after the policy

namespace ptlab {
namespace {

using test::kGarbage;
using test::kGarbageU;
using test::kInf;
using test::kNaN;
using test::SameBytes;

template <size_t N>
float Pick(Pcg32& rng, const float (&values)[N]) {
  return values[rng.NextUint() % N];
}

/// A wave after the bsdf slot: shading points by queue entry, path state by path, and the
/// batch's rows (one tag's BSDF columns, each row of a different path).
struct Wave {
  std::vector<SurfaceInteraction> its;
  std::vector<Color3f> throughput;
  std::vector<float> eta, prev_pdf;
  std::vector<uint32_t> specular;
  std::vector<Vec3f> prev_p;
  std::vector<uint32_t> path, entry;
  std::vector<float> weight_r, weight_g, weight_b, roulette_scale, pdf, row_eta, wi_x, wi_y, wi_z;
};

/// n rows over a wave of n + 5 paths and n + 7 queue entries; `hard`: the values above mixed in
/// (a third of the rows and paths), else plain ones with a few rows of no sample and of
/// weight 0.
Wave RandomWave(Pcg32& rng, size_t n, bool hard) {
  static const float kPdfs[] = {0.0f, -0.0f, kNaN, 1e-40f, -1.0f, 0.5f, 3.0f, kInf};
  static const float kWeights[] = {0.0f, -0.0f, kInf, kNaN, 1e-40f, 1.0f, 1e30f, -0.5f};
  static const float kThroughputs[] = {0.0f, -0.0f, 1e-30f, 1e-40f, 0.25f, 1e30f, kInf, kNaN};
  static const float kEtas[] = {0.0f, kInf, kNaN, 1.0f, 1.5f, 1.0f / 1.5f, 1e-20f};
  const auto u = [&rng] { return rng.NextFloat(); };
  const auto odd = [&rng, hard] { return hard && rng.NextUint() % 3 == 0; };
  Wave w;
  const size_t paths = n + 5, queue = n + 7;
  w.its.resize(queue);
  for (SurfaceInteraction& s : w.its) {
    s.p = {u() * 8 - 4, u() * 8 - 4, u() * 8 - 4};
    s.ng = {0, 0, 1};
  }
  w.throughput.resize(paths), w.eta.resize(paths), w.prev_pdf.resize(paths);
  w.specular.resize(paths), w.prev_p.resize(paths);
  for (size_t i = 0; i < paths; ++i) {
    w.throughput[i] = {odd() ? Pick(rng, kThroughputs) : u(), odd() ? Pick(rng, kThroughputs) : u(),
                       odd() ? Pick(rng, kThroughputs) : u()};
    w.eta[i] = odd() ? Pick(rng, kEtas) : 1.0f;
    w.prev_pdf[i] = u() * 4, w.specular[i] = rng.NextUint() % 2;
    w.prev_p[i] = {u(), u(), u()};
  }
  const std::vector<uint32_t> perm = test::Shuffled(rng, paths);
  w.path.assign(perm.begin(), perm.begin() + long(n));
  for (size_t k = 0; k < n; ++k) {
    w.entry.push_back(rng.NextUint() % uint32_t(queue));
    const bool no_sample = rng.NextUint() % 8 == 0, zero_weight = rng.NextUint() % 16 == 0;
    const float w0 = zero_weight ? 0.0f : u() * 2;
    w.weight_r.push_back(odd() ? Pick(rng, kWeights) : w0);
    w.weight_g.push_back(odd() ? Pick(rng, kWeights) : zero_weight ? 0.0f : u() * 2);
    w.weight_b.push_back(odd() ? Pick(rng, kWeights) : zero_weight ? -0.0f : u() * 2);
    w.roulette_scale.push_back(odd() ? Pick(rng, kWeights) : 1.0f / 0.95f);
    w.pdf.push_back(odd() ? Pick(rng, kPdfs) : no_sample ? 0.0f : u() * 4 + 0.01f);
    w.row_eta.push_back(odd() ? Pick(rng, kEtas) : Pick(rng, {1.0f, 1.5f, 1.0f / 1.5f}));
    w.wi_x.push_back(u() - 0.5f), w.wi_y.push_back(u() - 0.5f), w.wi_z.push_back(u());
  }
  return w;
}

/// Output storage for one implementation, garbage-filled: `at` rows written before the batch
/// (as by a group before it), room for the batch's rows and 9 more.
struct Columns {
  std::vector<uint32_t> entry, owner;
  std::vector<float> wi_x, wi_y, wi_z;
  ContinueBatchOutputs out;

  Columns(size_t at, size_t n) {
    entry.assign(at + n + 9, kGarbageU), owner.assign(at + n + 9, kGarbageU);
    wi_x.assign(at + n + 9, kGarbage), wi_y.assign(at + n + 9, kGarbage);
    wi_z.assign(at + n + 9, kGarbage);
    out = {entry.data(), wi_x.data(), wi_y.data(), wi_z.data(), owner.data(), at};
  }
};

/// Bit-identical, except that a NaN may be another NaN: when both factors of a multiply are
/// NaN, IEEE 754 does not say whose payload the product carries, and x86 returns the first
/// operand's, but the compiler may commute the multiply (the hard cases make such pairs, e.g.
/// a NaN throughput times Inf · 0; the bsdf slot's weights are finite, so renders never do).
template <class T>
bool SameBitsUpToNaNs(const std::vector<T>& a, const std::vector<T>& b) {
  static_assert(sizeof(T) % sizeof(float) == 0);
  if (a.size() != b.size()) return false;
  const size_t floats = a.size() * sizeof(T) / sizeof(float);
  for (size_t k = 0; k < floats; ++k) {
    float x, y;
    std::memcpy(&x, reinterpret_cast<const char*>(a.data()) + k * sizeof(float), sizeof(float));
    std::memcpy(&y, reinterpret_cast<const char*>(b.data()) + k * sizeof(float), sizeof(float));
    if (std::memcmp(&x, &y, sizeof(float)) != 0 && !(std::isnan(x) && std::isnan(y))) return false;
  }
  return true;
}

void ExpectSameAsOracle(const ContinueBatchRules& rules, bool whitted, const Wave& wave,
                        const char* what) {
  SCOPED_TRACE(what);
  const size_t n = wave.path.size(), at = 3;
  Wave want = wave, got = wave;
  Columns want_cols(at, n), got_cols(at, n);
  const auto run = [&](Wave& w, Columns& c, bool simd) {
    const ContinueBatchInputs in{
        w.path.data(),     w.entry.data(),    w.weight_r.data(),
        w.weight_g.data(), w.weight_b.data(), whitted ? w.roulette_scale.data() : nullptr,
        w.pdf.data(),      w.row_eta.data(),  w.wi_x.data(),
        w.wi_y.data(),     w.wi_z.data(),     w.its.data()};
    const ContinueBatchPaths paths{w.throughput.data(), w.eta.data(), w.specular.data(),
                                   w.prev_pdf.data(), w.prev_p.data()};
    if (simd) {
      simd::ContinuePaths(rules, n, in, paths, &c.out);
    } else {
      ptlab::ContinuePaths(rules, n, in, paths, &c.out);
    }
  };
  run(want, want_cols, false);
  run(got, got_cols, true);
  ASSERT_EQ(want_cols.out.rows, got_cols.out.rows);
  // Every column whole: the rows written and the garbage around them.
  EXPECT_TRUE(SameBytes(want_cols.entry, got_cols.entry));
  EXPECT_TRUE(SameBytes(want_cols.owner, got_cols.owner));
  EXPECT_TRUE(SameBytes(want_cols.wi_x, got_cols.wi_x));
  EXPECT_TRUE(SameBytes(want_cols.wi_y, got_cols.wi_y));
  EXPECT_TRUE(SameBytes(want_cols.wi_z, got_cols.wi_z));
  // The path state, every path (those not in the batch untouched by both).
  EXPECT_TRUE(SameBitsUpToNaNs(want.throughput, got.throughput));
  EXPECT_TRUE(SameBitsUpToNaNs(want.eta, got.eta));
  EXPECT_TRUE(SameBytes(want.specular, got.specular));
  EXPECT_TRUE(SameBytes(want.prev_pdf, got.prev_pdf));
  EXPECT_TRUE(SameBytes(want.prev_p, got.prev_p));
  // The inputs are only read.
  EXPECT_TRUE(SameBytes(want.path, got.path) && SameBytes(wave.path, got.path));
  EXPECT_TRUE(SameBytes(wave.pdf, got.pdf) && SameBytes(wave.its, got.its));
}

TEST(Continue8, MatchesOracleOnRandomRows) {
  // 10^6 rows over the targets this CPU runs, whatever their number.
  const size_t targets = hwy::SupportedAndGeneratedTargets().size();
  const size_t rows_per_target = (1000000 + targets - 1) / std::max<size_t>(targets, 1);
  size_t rows = 0;
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    Pcg32 rng(17, 5);
    for (size_t target_rows = 0; target_rows < rows_per_target;) {
      const uint32_t variant = rng.NextUint();
      const ContinueBatchRules rules{(variant & 1) != 0, (variant & 2) != 0};
      const size_t n = 1500 + rng.NextUint() % 500;
      ExpectSameAsOracle(rules, (variant & 4) != 0, RandomWave(rng, n, /*hard=*/false), "random");
      target_rows += n;
      if (HasFatalFailure()) return;
    }
    rows += rows_per_target;
  });
  EXPECT_GE(rows, size_t(1000000));
}

TEST(Continue8, MatchesOracleOnHardCases) {
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    Pcg32 rng(5, 9);
    for (int variant = 0; variant < 8; ++variant) {
      const ContinueBatchRules rules{(variant & 1) != 0, (variant & 2) != 0};
      const bool whitted = (variant & 4) != 0;
      // Batch sizes around whole vectors of every target (1, 2, 4, 8 rows), and empty.
      for (const size_t n : {0, 1, 2, 3, 4, 5, 7, 8, 9, 15, 16, 17, 33, 257}) {
        for (int round = 0; round < 4; ++round) {
          ExpectSameAsOracle(rules, whitted, RandomWave(rng, n, /*hard=*/true), "hard");
          if (HasFatalFailure()) return;
        }
      }
    }
  });
}

// Whole vectors of one kind: no row sampled, every row ending black (cut_black), every row
// going on; the kernel's shortcuts for them must write what the oracle writes.
TEST(Continue8, MatchesOracleOnUniformVectors) {
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    Pcg32 rng(3, 1);
    for (int kind = 0; kind < 3; ++kind) {
      Wave wave = RandomWave(rng, 64, /*hard=*/false);
      for (size_t k = 0; k < 64; ++k) {
        wave.pdf[k] = kind == 0 ? (k % 2 ? 0.0f : kNaN) : 1.0f;
        if (kind == 1) wave.weight_r[k] = wave.weight_g[k] = wave.weight_b[k] = 0.0f;
      }
      for (const bool cut_black : {false, true})
        ExpectSameAsOracle({true, cut_black}, false, wave, "uniform");
    }
  });
}

}  // namespace
}  // namespace ptlab
