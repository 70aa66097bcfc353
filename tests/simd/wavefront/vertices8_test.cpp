// simd::DecideVertices against its oracle ptlab::DecideVertices (the wavefront's per-row
// emitter pick, roulette and BSDF numbers): every output bit-identical on every compiled
// target, for a million random rows and the hard cases (throughput 0, tiny, huge, Inf and NaN
// in any channel; η 0, tiny, huge, Inf, NaN; numbers at the CDF's steps; emitters of power 0;
// uniform and power selection of 1 to kScanUpperBoundMax emitters; every combination of the
// rules; batch sizes 0 to 2 vectors and more), the columns past the written rows untouched,
// the paths not in the batch untouched, and no NaN or Inf in what the batch draws.
#include "simd/wavefront/vertices8.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <vector>

#include "engine/core/rng.h"
#include "engine/wavefront/vertices.h"
#include "engine/sampling/guide_table.h"
#include "simd/targets.h"  // first: the same target policy as simd/
#include "tests/simd/for_each_target.h"
#include "tests/simd/row_checks.h"

namespace ptlab {
namespace {

using test::kGarbage;
using test::kGarbageU;
using test::kInf;
using test::kNaN;
using test::SameBytes;

/// A scene with `n` area lights and the given selection (pmf per emitter; the CDF is their
/// running sum with its last entry 1, as BuildEmitterSelection writes it).
Scene SelectionScene(LightSelection mode, const std::vector<float>& pmf) {
  Scene scene;
  scene.integrator.light_selection = mode;
  EmitterSelectionTable& t = scene.emitter_selection;
  float sum = 0.0f;
  for (size_t e = 0; e < pmf.size(); ++e) {
    scene.emitters.push_back(EmitterRef::Make(EmitterTag::kArea, uint32_t(3 * e + 1)));
    t.pmf.push_back(pmf[e]);
    sum += pmf[e];
    t.cdf.push_back(sum);
  }
  t.cdf.back() = 1.0f;
  t.power = t.pmf;
  t.guide.assign(pmf.size() + 1, 0);
  BuildGuideTable(t.cdf.data(), uint32_t(t.cdf.size()), t.guide.data());
  return scene;
}

/// The wave a batch reads: shading points and wo by queue entry, path state by path, and the
/// batch's rows (queue entries in increasing order, each of a different path).
struct Wave {
  std::vector<SurfaceInteraction> its;
  std::vector<Vec3f> wo;
  std::vector<uint32_t> owner;
  std::vector<float> eta;
  std::vector<PathSampler> sampler;
  std::vector<Color3f> throughput, nee_throughput;
  std::vector<uint32_t> entries;
};

float HardValue(Pcg32& rng) {
  static const float kValues[] = {0.0f, 1e-40f, 1e-30f, 0.25f, 1.0f, 3.0f, 1e30f, kInf, kNaN};
  return kValues[rng.NextUint() % (sizeof(kValues) / sizeof(kValues[0]))];
}

Wave RandomWave(Pcg32& rng, size_t queue, size_t n, bool hard) {
  Wave w;
  const size_t paths = queue + 5;
  w.its.resize(queue), w.wo.resize(queue), w.owner.resize(queue);
  const std::vector<uint32_t> perm = test::Shuffled(rng, paths);
  for (size_t q = 0; q < queue; ++q) {
    SurfaceInteraction& s = w.its[q];
    s.p = {rng.NextFloat() * 8 - 4, rng.NextFloat() * 8 - 4, rng.NextFloat() * 8 - 4};
    s.ng = {0, 0, 1};
    s.material = MaterialRef::Make(MaterialTag(rng.NextUint() % kMaterialTagCount),
                                   rng.NextUint() & 0x0fffffffu);
    s.emitter = EmitterRef::None();
    w.wo[q] = {rng.NextFloat() - 0.5f, rng.NextFloat() - 0.5f, rng.NextFloat()};
    w.owner[q] = perm[q];
  }
  w.eta.resize(paths), w.sampler.resize(paths), w.throughput.resize(paths);
  w.nee_throughput.assign(paths, Color3f{kGarbage, kGarbage, kGarbage});
  for (size_t i = 0; i < paths; ++i) {
    w.sampler[i] = PathSampler(SamplerType::kIndependent,
                               (uint64_t(rng.NextUint()) << 32) | rng.NextUint(), rng.NextUint());
    // Advance some streams a few steps, as paths deeper in their life are.
    for (uint32_t s = rng.NextUint() % 6; s > 0; --s) w.sampler[i].Get1D(0);
    const bool odd = hard && rng.NextUint() % 3 == 0;
    w.throughput[i] = {odd ? HardValue(rng) : rng.NextFloat(),
                       odd ? HardValue(rng) : rng.NextFloat(),
                       odd ? HardValue(rng) : rng.NextFloat()};
    const float etas[] = {1.0f, 1.5f, 1.0f / 1.5f, 0.0f, 1e-20f, 1e20f, kInf, kNaN};
    w.eta[i] = hard ? etas[rng.NextUint() % 8] : etas[rng.NextUint() % 3];
  }
  // n distinct entries of [0, queue), in increasing order.
  w.entries = test::DistinctRows(rng, queue, n);
  std::sort(w.entries.begin(), w.entries.end());
  return w;
}

/// Column storage for one implementation's outputs, garbage-filled, with `pad` rows of room
/// after the batch's most rows (starting at `at` rows, as a group after others does).
struct Columns {
  std::vector<uint32_t> a_request, a_entry, a_light, b_path, b_entry, b_material;
  std::vector<float> a_pmf, a_ref_x, a_ref_y, a_ref_z, a_wo_x, a_wo_y, a_wo_z, a_u_x, a_u_y;
  std::vector<float> b_scale, b_wo_x, b_wo_y, b_wo_z, b_lobe, b_u_x, b_u_y;
  std::vector<uint8_t> traced;
  std::vector<uint32_t> nee_paths, nonfinite;
  VertexBatchOutputs out;

  Columns(size_t rows, size_t requests) {
    for (auto* v : {&a_request, &a_entry, &a_light, &b_path, &b_entry, &b_material, &nonfinite})
      v->assign(rows, kGarbageU);
    for (auto* v : {&a_pmf, &a_ref_x, &a_ref_y, &a_ref_z, &a_wo_x, &a_wo_y, &a_wo_z, &a_u_x, &a_u_y,
                    &b_scale, &b_wo_x, &b_wo_y, &b_wo_z, &b_lobe, &b_u_x, &b_u_y})
      v->assign(rows, kGarbage);
    traced.assign(requests, 7);
    nee_paths.assign(requests, kGarbageU);
  }
  VertexBatchOutputs* Out(size_t at) {
    out.area = {a_request.data() + at, a_entry.data() + at, a_light.data() + at, a_pmf.data() + at,
                a_ref_x.data() + at,   a_ref_y.data() + at, a_ref_z.data() + at, a_wo_x.data() + at,
                a_wo_y.data() + at,    a_wo_z.data() + at,  a_u_x.data() + at,   a_u_y.data() + at};
    out.bsdf = {b_path.data() + at,  b_entry.data() + at, b_material.data() + at,
                b_scale.data() + at, b_wo_x.data() + at,  b_wo_y.data() + at,
                b_wo_z.data() + at,  b_lobe.data() + at,  b_u_x.data() + at,
                b_u_y.data() + at};
    out.request_traced = traced.data(), out.nee_paths = nee_paths.data();
    out.nonfinite = nonfinite.data() + at;
    out.area_rows = out.bsdf_rows = out.nonfinite_rows = 0;
    return &out;
  }
};

void ExpectSameAsOracle(const Scene& scene, const VertexBatchRules& rules, const Wave& wave,
                        const char* what) {
  SCOPED_TRACE(what);
  const size_t n = wave.entries.size();
  const size_t at = 3, rows = at + n + 9, requests = rules.first_request + n + 9;
  Wave want = wave, got = wave;
  Columns want_cols(rows, requests), got_cols(rows, requests);
  const auto run = [&](Wave& w, Columns& c, bool simd) {
    const VertexBatchInputs in{w.entries.data(), w.owner.data(), w.its.data(), w.wo.data(),
                               w.eta.data()};
    const VertexBatchPaths paths{w.sampler.data(), w.throughput.data(), w.nee_throughput.data()};
    VertexBatchOutputs* out = c.Out(at);
    if (simd) {
      simd::DecideVertices(scene, rules, n, in, paths, out);
    } else {
      ptlab::DecideVertices(scene, rules, n, in, paths, out);
    }
  };
  run(want, want_cols, false);
  run(got, got_cols, true);
  const VertexBatchOutputs& wo = want_cols.out;
  const VertexBatchOutputs& go = got_cols.out;
  ASSERT_EQ(wo.area_rows, go.area_rows);
  ASSERT_EQ(wo.bsdf_rows, go.bsdf_rows);
  ASSERT_EQ(wo.nonfinite_rows, go.nonfinite_rows);
  // Every column whole: the rows written and the garbage around them.
  EXPECT_TRUE(SameBytes(want_cols.a_request, got_cols.a_request));
  EXPECT_TRUE(SameBytes(want_cols.a_entry, got_cols.a_entry));
  EXPECT_TRUE(SameBytes(want_cols.a_light, got_cols.a_light));
  for (auto m : {&Columns::a_pmf, &Columns::a_ref_x, &Columns::a_ref_y, &Columns::a_ref_z,
                 &Columns::a_wo_x, &Columns::a_wo_y, &Columns::a_wo_z, &Columns::a_u_x,
                 &Columns::a_u_y, &Columns::b_scale, &Columns::b_wo_x, &Columns::b_wo_y,
                 &Columns::b_wo_z, &Columns::b_lobe, &Columns::b_u_x, &Columns::b_u_y}) {
    EXPECT_TRUE(SameBytes(want_cols.*m, got_cols.*m));
  }
  EXPECT_TRUE(SameBytes(want_cols.b_path, got_cols.b_path));
  EXPECT_TRUE(SameBytes(want_cols.b_entry, got_cols.b_entry));
  EXPECT_TRUE(SameBytes(want_cols.b_material, got_cols.b_material));
  EXPECT_TRUE(SameBytes(want_cols.traced, got_cols.traced));
  EXPECT_TRUE(SameBytes(want_cols.nee_paths, got_cols.nee_paths));
  EXPECT_TRUE(SameBytes(want_cols.nonfinite, got_cols.nonfinite));
  // The path state, every path (those not in the batch untouched by both).
  EXPECT_TRUE(want.sampler == got.sampler);
  EXPECT_TRUE(SameBytes(want.throughput, got.throughput));
  EXPECT_TRUE(SameBytes(want.nee_throughput, got.nee_throughput));
  // What the batch draws and picks is finite: numbers in [0, 1), pick probabilities in (0, 1].
  for (size_t c = at; c < at + go.area_rows; ++c) {
    EXPECT_TRUE(got_cols.a_pmf[c] > 0 && got_cols.a_pmf[c] <= 1.0f);
    EXPECT_TRUE(got_cols.a_u_x[c] >= 0 && got_cols.a_u_x[c] < 1 && got_cols.a_u_y[c] >= 0 &&
                got_cols.a_u_y[c] < 1);
  }
  for (size_t c = at; c < at + go.bsdf_rows; ++c) {
    EXPECT_TRUE(got_cols.b_lobe[c] >= 0 && got_cols.b_lobe[c] < 1 && got_cols.b_u_x[c] >= 0 &&
                got_cols.b_u_x[c] < 1 && got_cols.b_u_y[c] >= 0 && got_cols.b_u_y[c] < 1);
  }
}

std::vector<Scene> Scenes() {
  std::vector<Scene> scenes;
  for (const LightSelection mode : {LightSelection::kUniform, LightSelection::kPower}) {
    scenes.push_back(SelectionScene(mode, {1.0f}));
    scenes.push_back(SelectionScene(mode, {0.5f, 0.0f, 0.25f, 0.25f, 0.0f}));
    std::vector<float> pmf(kScanUpperBoundMax);
    for (size_t e = 0; e < pmf.size(); ++e) pmf[e] = e % 4 == 1 ? 0.0f : 1.0f;
    const float sum = std::accumulate(pmf.begin(), pmf.end(), 0.0f);
    for (float& p : pmf) p /= sum;
    scenes.push_back(SelectionScene(mode, pmf));
  }
  // Last emitters of power zero: a u at the top of the CDF must still pick the last with power.
  scenes.push_back(SelectionScene(LightSelection::kPower, {0.75f, 0.25f, 0.0f, 0.0f}));
  return scenes;
}

TEST(VertexBatch8, FitsOnlyAreaLightsAndScannableSelections) {
  EXPECT_FALSE(VertexBatchFits(Scene{}));
  Scene scene = SelectionScene(LightSelection::kPower, {0.5f, 0.5f});
  EXPECT_TRUE(VertexBatchFits(scene));
  scene.emitters[1] = EmitterRef::Make(EmitterTag::kPoint, 0);
  EXPECT_FALSE(VertexBatchFits(scene));
  std::vector<float> many(kScanUpperBoundMax + 1, 1.0f / float(kScanUpperBoundMax + 1));
  EXPECT_FALSE(VertexBatchFits(SelectionScene(LightSelection::kPower, many)));
  EXPECT_TRUE(VertexBatchFits(SelectionScene(LightSelection::kUniform, many)));
}

TEST(VertexBatch8, MatchesOracleOnRandomRows) {
  const std::vector<Scene> scenes = Scenes();
  test::ForEachTarget(simd::VertexBatch8TargetName, [&](const char*) {
    Pcg32 rng(11, 3);
    size_t rows = 0;
    for (int round = 0; round < 40; ++round) {
      for (int variant = 0; variant < 4; ++variant) {
        const Scene& scene = scenes[size_t(round + variant) % scenes.size()];
        VertexBatchRules rules;
        rules.depth = (variant & 2) ? 3 : 1;
        rules.emitter_sample = (variant & 1) != 0;
        rules.roulette = (variant & 2) != 0;
        rules.first_request = rng.NextUint() % 100;
        const size_t n = 1500 + rng.NextUint() % 500;
        const Wave wave = RandomWave(rng, n + 1000, n, /*hard=*/false);
        ExpectSameAsOracle(scene, rules, wave, "random");
        rows += n;
        if (HasFatalFailure()) return;
      }
    }
    EXPECT_GE(rows, size_t(250000));  // per target; four targets: 10^6 rows
  });
}

TEST(VertexBatch8, MatchesOracleOnHardCases) {
  const std::vector<Scene> scenes = Scenes();
  test::ForEachTarget(simd::VertexBatch8TargetName, [&](const char*) {
    Pcg32 rng(5, 9);
    for (const Scene& scene : scenes) {
      for (int variant = 0; variant < 4; ++variant) {
        // Batch sizes around whole vectors of every target (1, 2, 4, 8 rows), and empty.
        for (const size_t n : {0, 1, 2, 3, 4, 5, 7, 8, 9, 15, 16, 17, 33, 257}) {
          VertexBatchRules rules;
          rules.depth = 4;
          rules.emitter_sample = (variant & 1) != 0;
          rules.roulette = (variant & 2) != 0;
          rules.first_request = uint32_t(n % 3);
          ExpectSameAsOracle(scene, rules, RandomWave(rng, n + 40, n, /*hard=*/true), "hard");
          if (HasFatalFailure()) return;
        }
      }
    }
  });
}

// The pick at the CDF's own steps: a CDF made of the first numbers (the pick numbers) that some
// rows draw, so that those rows' u equals a step exactly and the scan's comparison decides.
TEST(VertexBatch8, PicksAtTheCdfStepsMatchTheOracle) {
  test::ForEachTarget(simd::VertexBatch8TargetName, [&](const char*) {
    Pcg32 rng(21, 1);
    const Wave wave = RandomWave(rng, 80, 64, /*hard=*/false);
    std::vector<float> steps;
    for (size_t k = 0; k < 24; k += 3) {
      PathSampler copy = wave.sampler[wave.owner[wave.entries[k]]];
      steps.push_back(copy.Get1D(0));
    }
    std::sort(steps.begin(), steps.end());
    std::vector<float> pmf;
    float below = 0.0f;
    for (const float c : steps) pmf.push_back(c - below), below = c;
    pmf.push_back(1.0f - below);
    Scene scene = SelectionScene(LightSelection::kPower, pmf);
    std::copy(steps.begin(), steps.end(), scene.emitter_selection.cdf.begin());
    VertexBatchRules rules;
    rules.emitter_sample = true;
    ExpectSameAsOracle(scene, rules, wave, "cdf steps");
  });
}

}  // namespace
}  // namespace ptlab
