// simd::DecideVertices against its oracle ptlab::DecideVertices (the vertex decisions of every
// integrator: emitter samples, Nori's and Whitted's roulette, BSDF numbers, with the independent
// sampler's draws or Sobol' numbers from columns): every output bit-identical on every compiled
// target, for a million random rows and the hard cases (throughput 0, tiny, huge, Inf and NaN
// in any channel; η 0, tiny, huge, Inf, NaN; numbers at the CDF's steps, 0 and just below 1;
// emitters of power 0; uniform and power selection of 1 to kScanUpperBoundMax emitters and
// more (the guide table: the twin hands those to the oracle); area lights mixed with
// environment maps, distant disks and delta lights; no emitters; every combination of the
// rules, 1 to 7 emitter samples per vertex; batch sizes 0 to 2 vectors and more), the columns
// past the written rows untouched, the paths not in the batch untouched, and no NaN or Inf in
// what the batch draws.
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
#include "engine/render/integrator_common.h"
#include "engine/sampling/guide_table.h"
#include "engine/wavefront/vertices.h"
#include "simd/dispatched_target.h"
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

/// A scene with one emitter per pmf entry and the given selection (the CDF is the pmf's
/// running sum with its last entry 1, as BuildEmitterSelection writes it); emitter e has tag
/// tags[e % tags.size()] (area lights only by default).
Scene SelectionScene(LightSelection mode, const std::vector<float>& pmf,
                     const std::vector<EmitterTag>& tags = {EmitterTag::kArea}) {
  Scene scene;
  scene.integrator.light_selection = mode;
  EmitterSelectionTable& t = scene.emitter_selection;
  float sum = 0.0f;
  for (size_t e = 0; e < pmf.size(); ++e) {
    scene.emitters.push_back(EmitterRef::Make(tags[e % tags.size()], uint32_t(3 * e + 1)));
    t.pmf.push_back(pmf[e]);
    sum += pmf[e];
    t.cdf.push_back(sum);
  }
  if (!t.cdf.empty()) t.cdf.back() = 1.0f;
  t.power = t.pmf;
  t.guide.assign(pmf.size() + 1, 0);
  BuildGuideTable(t.cdf.data(), uint32_t(t.cdf.size()), t.guide.data());
  return scene;
}

/// The wave a batch reads: shading points and wo by queue entry, path state by path, the
/// batch's rows (queue entries in increasing order, each of a different path) and the Sobol'
/// numbers by row (light_point: `samples` blocks of `stride` rows).
struct Wave {
  std::vector<SurfaceInteraction> its;
  std::vector<Vec3f> wo;
  std::vector<uint32_t> owner;
  std::vector<float> eta;
  std::vector<PathSampler> sampler;
  std::vector<Color3f> throughput, nee_throughput;
  std::vector<uint32_t> entries;
  std::vector<Vec2f> light_point, bsdf_direction;
  std::vector<float> roulette, bsdf_lobe;
  size_t stride = 0;
};

float HardValue(Pcg32& rng) {
  static const float kValues[] = {0.0f, 1e-40f, 1e-30f, 0.25f, 1.0f, 3.0f, 1e30f, kInf, kNaN};
  return kValues[rng.NextUint() % (sizeof(kValues) / sizeof(kValues[0]))];
}

/// A number in [0, 1): random, or (hard) one of the edges (0, just below 1, the CDF steps of
/// the scenes' selections, 0.95).
float Number(Pcg32& rng, bool hard) {
  static const float kEdges[] = {0.0f, kOneMinusEpsilon, 0.5f, 0.25f, 0.75f, 0.95f, 0.2f, 0.4f,
                                 1.0f / 16.0f, 0.125f};
  if (hard && rng.NextUint() % 3 == 0) return kEdges[rng.NextUint() % 10];
  return rng.NextFloat();
}

Wave RandomWave(Pcg32& rng, size_t queue, size_t n, bool hard, int samples = 1) {
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
    // Named draws (operands and arguments are evaluated in an unspecified order).
    const uint64_t hi = rng.NextUint(), lo = rng.NextUint();
    const uint32_t sample_index = rng.NextUint();
    w.sampler[i] = PathSampler(SamplerType::kIndependent, (hi << 32) | lo, sample_index);
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
  // Sobol' numbers: a stride of more rows than the batch's (a group's rows within a wave's).
  w.stride = n + rng.NextUint() % 5;
  w.light_point.resize(w.stride * size_t(samples));
  for (Vec2f& u : w.light_point) u = {Number(rng, hard), Number(rng, hard)};
  w.roulette.resize(n), w.bsdf_lobe.resize(n), w.bsdf_direction.resize(n);
  for (size_t k = 0; k < n; ++k) {
    w.roulette[k] = Number(rng, hard), w.bsdf_lobe[k] = Number(rng, hard);
    w.bsdf_direction[k] = {Number(rng, hard), Number(rng, hard)};
  }
  return w;
}

/// Column storage for one implementation's outputs, garbage-filled, with `pad` rows of room
/// after the batch's most rows (starting at `at` rows, as a group after others does).
struct Columns {
  std::vector<uint32_t> a_request, a_entry, a_light, b_path, b_entry, b_material;
  std::vector<uint32_t> o_request, o_entry, o_emitter;
  std::vector<float> a_pmf, a_ref_x, a_ref_y, a_ref_z, a_wo_x, a_wo_y, a_wo_z, a_u_x, a_u_y;
  std::vector<float> o_pmf, o_u_x, o_u_y;
  std::vector<float> b_scale, b_wo_x, b_wo_y, b_wo_z, b_lobe, b_u_x, b_u_y;
  std::vector<uint8_t> traced;
  std::vector<uint32_t> nee_paths, nonfinite;
  VertexBatchOutputs out;

  Columns(size_t rows, size_t requests) {
    for (auto* v : {&a_request, &a_entry, &a_light, &b_path, &b_entry, &b_material, &nonfinite,
                    &o_request, &o_entry, &o_emitter})
      v->assign(rows, kGarbageU);
    for (auto* v : {&a_pmf, &a_ref_x, &a_ref_y, &a_ref_z, &a_wo_x, &a_wo_y, &a_wo_z, &a_u_x, &a_u_y,
                    &b_scale, &b_wo_x, &b_wo_y, &b_wo_z, &b_lobe, &b_u_x, &b_u_y, &o_pmf, &o_u_x,
                    &o_u_y})
      v->assign(rows, kGarbage);
    traced.assign(requests, 7);
    nee_paths.assign(requests, kGarbageU);
  }
  VertexBatchOutputs* Out(size_t at) {
    out.area = {a_request.data() + at, a_entry.data() + at, a_light.data() + at, a_pmf.data() + at,
                a_ref_x.data() + at,   a_ref_y.data() + at, a_ref_z.data() + at, a_wo_x.data() + at,
                a_wo_y.data() + at,    a_wo_z.data() + at,  a_u_x.data() + at,   a_u_y.data() + at};
    out.other = {o_request.data() + at, o_entry.data() + at, o_emitter.data() + at,
                 o_pmf.data() + at,     o_u_x.data() + at,   o_u_y.data() + at};
    out.bsdf = {b_path.data() + at,  b_entry.data() + at, b_material.data() + at,
                b_scale.data() + at, b_wo_x.data() + at,  b_wo_y.data() + at,
                b_wo_z.data() + at,  b_lobe.data() + at,  b_u_x.data() + at,
                b_u_y.data() + at};
    out.request_traced = traced.data(), out.nee_paths = nee_paths.data();
    out.nonfinite = nonfinite.data() + at;
    out.area_rows = out.other_rows = out.bsdf_rows = out.nonfinite_rows = 0;
    return &out;
  }
};

void ExpectSameAsOracle(const Scene& scene, const VertexBatchRules& rules, const Wave& wave,
                        const char* what) {
  SCOPED_TRACE(what);
  SCOPED_TRACE(testing::Message() << "depth " << rules.depth << " emitter_sample "
                                  << rules.emitter_sample << " light_samples "
                                  << rules.light_samples << " ends_path " << rules.ends_path
                                  << " roulette " << int(rules.roulette) << " sobol "
                                  << rules.sobol << " emitters " << scene.emitters.size());
  const size_t n = wave.entries.size();
  const size_t n_light = size_t(rules.light_samples);
  const size_t at = 3, rows = at + n * n_light + 9, requests = rules.first_request + n * n_light + 9;
  Wave want = wave, got = wave;
  Columns want_cols(rows, requests), got_cols(rows, requests);
  const auto run = [&](Wave& w, Columns& c, bool simd) {
    VertexBatchInputs in{w.entries.data(), w.owner.data(), w.its.data(), w.wo.data(),
                         w.eta.data()};
    if (rules.sobol) {
      in.light_point = w.light_point.data(), in.light_stride = w.stride;
      in.roulette = w.roulette.data(), in.bsdf_lobe = w.bsdf_lobe.data();
      in.bsdf_direction = w.bsdf_direction.data();
    }
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
  ASSERT_EQ(wo.other_rows, go.other_rows);
  ASSERT_EQ(wo.bsdf_rows, go.bsdf_rows);
  ASSERT_EQ(wo.nonfinite_rows, go.nonfinite_rows);
  // Every column whole: the rows written and the garbage around them.
  for (auto m : {&Columns::a_request, &Columns::a_entry, &Columns::a_light, &Columns::o_request,
                 &Columns::o_entry, &Columns::o_emitter, &Columns::b_path, &Columns::b_entry,
                 &Columns::b_material, &Columns::nee_paths, &Columns::nonfinite}) {
    EXPECT_TRUE(SameBytes(want_cols.*m, got_cols.*m));
  }
  for (auto m : {&Columns::a_pmf, &Columns::a_ref_x, &Columns::a_ref_y, &Columns::a_ref_z,
                 &Columns::a_wo_x, &Columns::a_wo_y, &Columns::a_wo_z, &Columns::a_u_x,
                 &Columns::a_u_y, &Columns::o_pmf, &Columns::o_u_x, &Columns::o_u_y,
                 &Columns::b_scale, &Columns::b_wo_x, &Columns::b_wo_y, &Columns::b_wo_z,
                 &Columns::b_lobe, &Columns::b_u_x, &Columns::b_u_y}) {
    EXPECT_TRUE(SameBytes(want_cols.*m, got_cols.*m));
  }
  EXPECT_TRUE(SameBytes(want_cols.traced, got_cols.traced));
  // The path state, every path (those not in the batch untouched by both; with Sobol' no
  // stream moves).
  EXPECT_TRUE(want.sampler == got.sampler);
  if (rules.sobol) {
    EXPECT_TRUE(got.sampler == wave.sampler);
  }
  EXPECT_TRUE(SameBytes(want.throughput, got.throughput));
  EXPECT_TRUE(SameBytes(want.nee_throughput, got.nee_throughput));
  // What the batch draws and picks is finite: numbers in [0, 1), pick probabilities in (0, 1].
  for (size_t c = at; c < at + go.area_rows; ++c) {
    EXPECT_TRUE(got_cols.a_pmf[c] > 0 && got_cols.a_pmf[c] <= 1.0f);
    EXPECT_TRUE(got_cols.a_u_x[c] >= 0 && got_cols.a_u_x[c] < 1 && got_cols.a_u_y[c] >= 0 &&
                got_cols.a_u_y[c] < 1);
  }
  for (size_t c = at; c < at + go.other_rows; ++c) {
    EXPECT_TRUE(got_cols.o_pmf[c] > 0 && got_cols.o_pmf[c] <= 1.0f);
    EXPECT_TRUE(got_cols.o_u_x[c] >= 0 && got_cols.o_u_x[c] < 1 && got_cols.o_u_y[c] >= 0 &&
                got_cols.o_u_y[c] < 1);
    EXPECT_NE(EmitterRef{got_cols.o_emitter[c]}.tag(), EmitterTag::kArea);
  }
  for (size_t c = at; c < at + go.bsdf_rows; ++c) {
    EXPECT_TRUE(got_cols.b_lobe[c] >= 0 && got_cols.b_lobe[c] < 1 && got_cols.b_u_x[c] >= 0 &&
                got_cols.b_u_x[c] < 1 && got_cols.b_u_y[c] >= 0 && got_cols.b_u_y[c] < 1);
  }
}

std::vector<Scene> Scenes() {
  const std::vector<EmitterTag> mixed = {EmitterTag::kArea,  EmitterTag::kEnvironment,
                                         EmitterTag::kArea,  EmitterTag::kDistantDisk,
                                         EmitterTag::kPoint, EmitterTag::kDirectional,
                                         EmitterTag::kSpot};
  std::vector<Scene> scenes;
  for (const LightSelection mode : {LightSelection::kUniform, LightSelection::kPower}) {
    scenes.push_back(SelectionScene(mode, {1.0f}));
    scenes.push_back(SelectionScene(mode, {0.5f, 0.0f, 0.25f, 0.25f, 0.0f}));
    std::vector<float> pmf(kScanUpperBoundMax);
    for (size_t e = 0; e < pmf.size(); ++e) pmf[e] = e % 4 == 1 ? 0.0f : 1.0f;
    const float sum = std::accumulate(pmf.begin(), pmf.end(), 0.0f);
    for (float& p : pmf) p /= sum;
    scenes.push_back(SelectionScene(mode, pmf));
    scenes.push_back(SelectionScene(mode, {0.2f, 0.2f, 0.1f, 0.1f, 0.2f, 0.0f, 0.2f}, mixed));
    scenes.push_back(SelectionScene(mode, {1.0f}, {EmitterTag::kPoint}));
    // More emitters than the scan takes: power selection goes through the guide table.
    std::vector<float> many(kScanUpperBoundMax + 3, 1.0f / float(kScanUpperBoundMax + 3));
    scenes.push_back(SelectionScene(mode, many, mixed));
  }
  // Last emitters of power zero: a u at the top of the CDF must still pick the last with power.
  scenes.push_back(SelectionScene(LightSelection::kPower, {0.75f, 0.25f, 0.0f, 0.0f}));
  // No emitters: the requests are untraced, nothing is drawn for them.
  scenes.push_back(Scene{});
  return scenes;
}

/// Rules variant v of the combinations the wavefront uses (and more): emitter samples or not,
/// 1, 2, 3 or 7 of them, the path ending after them or not, each roulette, each sampler.
VertexBatchRules RulesVariant(int v, int depth, uint32_t first_vertex) {
  using Roulette = VertexBatchRules::Roulette;
  static const int kSamples[] = {1, 2, 3, 7};
  VertexBatchRules rules;
  rules.depth = depth;
  rules.emitter_sample = (v & 1) != 0;
  rules.light_samples = kSamples[(v >> 1) & 3];
  rules.ends_path = ((v >> 3) & 3) == 3;
  rules.roulette = static_cast<Roulette>(((v >> 3) & 3) % 3);
  rules.sobol = (v & 32) != 0;
  rules.first_request = first_vertex * uint32_t(rules.light_samples);
  return rules;
}
constexpr int kRulesVariants = 64;

TEST(VertexBatch8, MatchesOracleOnRandomRows) {
  const std::vector<Scene> scenes = Scenes();
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    Pcg32 rng(11, 3);
    size_t rows = 0;
    for (int round = 0; round < 4; ++round) {
      for (int variant = 0; variant < kRulesVariants; ++variant) {
        const Scene& scene = scenes[size_t(round * 7 + variant) % scenes.size()];
        static const int kDepths[] = {1, 3, 5, integrator::kWhittedMaxDepth};
        const VertexBatchRules rules =
            RulesVariant(variant, kDepths[(round + variant) % 4], rng.NextUint() % 100);
        const size_t n = 800 + rng.NextUint() % 500;
        const Wave wave = RandomWave(rng, n + 1000, n, /*hard=*/false, rules.light_samples);
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
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    Pcg32 rng(5, 9);
    for (const Scene& scene : scenes) {
      for (int variant = 0; variant < kRulesVariants; ++variant) {
        // Batch sizes around whole vectors of every target (1, 2, 4, 8 rows), and empty.
        for (const size_t n : {0, 1, 2, 3, 4, 5, 7, 8, 9, 15, 16, 17, 33, 257}) {
          const int depth = variant % 3 == 0 ? integrator::kWhittedMaxDepth : 4;
          const VertexBatchRules rules = RulesVariant(variant, depth, uint32_t(n % 3));
          ExpectSameAsOracle(scene, rules,
                             RandomWave(rng, n + 40, n, /*hard=*/true, rules.light_samples),
                             "hard");
          if (HasFatalFailure()) return;
        }
      }
    }
  });
}

// The pick at the CDF's own steps: a CDF made of the first numbers (the pick numbers) that some
// rows draw, so that those rows' u equals a step exactly and the scan's comparison decides; with
// Sobol', the point's x at the steps (the pick and its remap).
TEST(VertexBatch8, PicksAtTheCdfStepsMatchTheOracle) {
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    for (const bool sobol : {false, true}) {
      Pcg32 rng(21, 1);
      const Wave wave = RandomWave(rng, 80, 64, /*hard=*/false);
      std::vector<float> steps;
      for (size_t k = 0; k < 24; k += 3) {
        PathSampler copy = wave.sampler[wave.owner[wave.entries[k]]];
        steps.push_back(sobol ? wave.light_point[k].x : copy.Get1D(0));
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
      rules.sobol = sobol;
      ExpectSameAsOracle(scene, rules, wave, sobol ? "cdf steps, sobol" : "cdf steps");
    }
  });
}

// The oracle's order of rows and numbers is the scalar integrators': a row's emitter samples
// are requests first_request + k · n + s, each sample draws pick, point x, point y from the
// path's stream in turn, and the BSDF's numbers come after the roulette's (Whitted's and
// Nori's). Checked against PathSampler directly, so the twin cannot agree with a wrong oracle.
TEST(VertexBatch8, OracleDrawsInTheIntegratorsOrder) {
  Pcg32 rng(3, 4);
  const Scene scene = SelectionScene(LightSelection::kUniform, {0.5f, 0.5f});
  const size_t n = 5;
  Wave wave = RandomWave(rng, 9, n, /*hard=*/false);
  for (Color3f& t : wave.throughput) t = {1, 1, 1};
  for (float& e : wave.eta) e = 1.0f;
  VertexBatchRules rules;
  rules.depth = 4;
  rules.emitter_sample = true;
  rules.light_samples = 3;
  rules.roulette = VertexBatchRules::Roulette::kWhitted;
  rules.first_request = 6;
  Wave w = wave;
  Columns c(n * 3 + 9, rules.first_request + n * 3 + 9);
  const VertexBatchInputs in{w.entries.data(), w.owner.data(), w.its.data(), w.wo.data(),
                             w.eta.data()};
  ptlab::DecideVertices(scene, rules, n, in,
                        {w.sampler.data(), w.throughput.data(), w.nee_throughput.data()}, c.Out(0));
  ASSERT_EQ(c.out.area_rows, n * 3);  // both lights have power: every sample picks one
  size_t bsdf = 0;
  for (size_t k = 0; k < n; ++k) {
    const uint32_t i = wave.owner[wave.entries[k]];
    PathSampler s = wave.sampler[i];
    EXPECT_EQ(c.nee_paths[rules.first_request / 3 + k], i);
    for (size_t j = 0; j < 3; ++j) {
      const size_t row = k * 3 + j;
      EXPECT_EQ(c.a_request[row], rules.first_request + row);
      const float pick = s.Get1D(0);
      EXPECT_EQ(c.a_light[row], uint32_t(3 * (pick < 0.5f ? 0 : 1) + 1));
      EXPECT_EQ(c.a_u_x[row], s.Get1D(0));
      EXPECT_EQ(c.a_u_y[row], s.Get1D(0));
    }
    if (!(s.Get1D(0) < integrator::kWhittedContinuation)) continue;
    EXPECT_EQ(c.b_path[bsdf], i);
    EXPECT_EQ(c.b_scale[bsdf], 1.0f / integrator::kWhittedContinuation);
    EXPECT_EQ(c.b_lobe[bsdf], s.Get1D(0));
    EXPECT_EQ(c.b_u_x[bsdf], s.Get1D(0));
    EXPECT_EQ(c.b_u_y[bsdf], s.Get1D(0));
    EXPECT_TRUE(s == w.sampler[i]);
    ++bsdf;
  }
  EXPECT_EQ(c.out.bsdf_rows, bsdf);
}

}  // namespace
}  // namespace ptlab
