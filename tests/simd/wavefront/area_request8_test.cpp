// simd::AreaEmitterRequestBatch against its oracle ptlab::AreaEmitterRequestBatch
// (integrator::AreaEmitterSampleRequest per row), on every compiled target, for every material
// tag, with and without MIS and with either heuristic: 2·10⁵ random rows per case on the shared
// scenes' geometry and lights and the hard cases of tests/simd/area_request_rows.h, at every
// tail length. Contract (simd/wavefront/area_request8.h): traced flags equal (except where the oracle's
// contribution is not finite: the kernel does not trace those), shadow rays bit-identical,
// contributions per channel within 1e-4 |oracle| + 1e-30, every output finite, untraced rows 0.
#include "simd/targets.h"  // first: the same target policy as simd/
#include "simd/dispatched_target.h"
#include "simd/wavefront/area_request8.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/bsdf/bsdf.h"
#include "engine/core/rng.h"
#include "engine/io/scene_file.h"
#include "tests/simd/area_request_rows.h"
#include "tests/simd/for_each_target.h"
#include "tests/test_data.h"

namespace ptlab {
namespace {

constexpr double kRelative = 1e-4, kAbsolute = 1e-30;

bool Finite(const test::AreaRequestColumns& c, size_t i) {
  for (const auto& col : c.col)
    if (!std::isfinite(col[i])) return false;
  return true;
}

// Checks got (n rows) against want; returns the largest relative contribution error seen.
double ExpectWithinContract(const test::AreaRequestColumns& want,
                            const test::AreaRequestColumns& got, size_t n) {
  double worst = 0;
  size_t flag_differs = 0, ray_differs = 0, out_of_tolerance = 0, nonfinite = 0, not_zero = 0,
         unwritten = 0;
  size_t first = n;
  const auto fail = [&](size_t* count, size_t i) { ++*count, first = std::min(first, i); };
  for (size_t i = 0; i < n; ++i) {
    if (!Finite(got, i)) fail(&nonfinite, i);
    if (got.traced[i] > 1) fail(&unwritten, i);
    if (!got.traced[i]) {
      for (const auto& col : got.col)
        if (std::bit_cast<uint32_t>(col[i]) != 0) fail(&not_zero, i);
    }
    if (got.traced[i] != want.traced[i]) {
      // The oracle traces an infinite contribution (pdf_light underflowed); the kernel does not.
      if (!(want.traced[i] && !Finite(want, i))) fail(&flag_differs, i);
      continue;
    }
    if (!want.traced[i]) continue;
    for (int c = 0; c < 6; ++c)
      if (std::bit_cast<uint32_t>(got.col[c][i]) != std::bit_cast<uint32_t>(want.col[c][i]))
        fail(&ray_differs, i);
    for (int c = 6; c < 9; ++c) {
      const double g = got.col[c][i], w = want.col[c][i], err = std::fabs(g - w);
      if (err > kRelative * std::fabs(w) + kAbsolute) fail(&out_of_tolerance, i);
      if (std::fabs(w) > 1e-20) worst = std::max(worst, err / std::fabs(w));
    }
  }
  EXPECT_EQ(flag_differs, 0u) << "first bad row " << first << " of " << n;
  EXPECT_EQ(ray_differs, 0u) << "first bad row " << first << " of " << n;
  EXPECT_EQ(out_of_tolerance, 0u) << "first bad row " << first << " of " << n;
  EXPECT_EQ(nonfinite, 0u) << "first bad row " << first << " of " << n;
  EXPECT_EQ(not_zero, 0u) << "first bad row " << first << " of " << n;
  EXPECT_EQ(unwritten, 0u) << "first bad row " << first << " of " << n;
  return worst;
}

void ExpectBatchMatchesOracle(const std::string& path) {
  PTLAB_REQUIRE_DATA(path);
  StatusOr<Scene> loaded = LoadSceneFile(path);
  ASSERT_TRUE(loaded.ok()) << loaded.status().message();
  Scene& scene = *loaded;
  ASSERT_GT(scene.area_lights.size(), 0u);
  test::AddRequestMaterials(&scene);
  Pcg32 rng(5, 17);
  for (int t = 0; t < kMaterialTagCount; ++t) {
    const MaterialTag tag = static_cast<MaterialTag>(t);
    if (test::MaterialRows(scene.materials, tag) == 0) continue;  // another branch's tag
    SCOPED_TRACE("tag " + std::to_string(t));
    const test::AreaRequestRows rows = test::MakeAreaRequestRows(scene, tag, 200000, true, rng);
    const size_t n = rows.size();
    for (const bool mis : {true, false}) {
      for (const bool power : {true, false}) {
        if (!mis && !power) continue;
        SCOPED_TRACE(mis ? (power ? "mis power" : "mis balance") : "no mis");
        scene.integrator.power_heuristic = power;
        test::AreaRequestColumns want(n);
        AreaEmitterRequestBatch(scene, tag, mis, n, rows.In(), want.Out());
        size_t traced = 0;
        for (size_t i = 0; i < n; ++i) traced += want.traced[i];
        if (!IsDeltaMaterial(tag)) {
          EXPECT_GT(traced, n / 50);  // not all degenerate
        }
        test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
          double worst = 0;
          for (size_t cut = 0; cut < 8; ++cut) {  // every tail length
            const size_t m = n - cut;
            test::AreaRequestColumns got(m);
            simd::AreaEmitterRequestBatch(scene, tag, mis, m, rows.In(), got.Out());
            worst = std::max(worst, ExpectWithinContract(want, got, m));
          }
          std::printf(
              "  [%s tag %d mis %d power %d] %zu rows, %zu traced, worst relative "
              "contribution error %.3g\n",
              target, t, int(mis), int(power), n, traced, worst);
        });
      }
    }
  }
}

// Short batches (one partial vector, one vector and a tail, a chunk and a tail) against the
// oracle, and nothing written past n.
TEST(AreaRequest8, ShortBatchesMatchOracle) {
  StatusOr<Scene> loaded = LoadSceneFile(std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml");
  ASSERT_TRUE(loaded.ok()) << loaded.status().message();
  Scene& scene = *loaded;
  test::AddRequestMaterials(&scene);
  Pcg32 rng(2, 9);
  const test::AreaRequestRows rows =
      test::MakeAreaRequestRows(scene, MaterialTag::kRoughPlastic, 200, false, rng);
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    for (const size_t n : {1, 3, 7, 8, 9, 15, 16, 17, 63, 64, 65, 129}) {
      SCOPED_TRACE(n);
      test::AreaRequestColumns want(n + 1), got(n + 1);
      AreaEmitterRequestBatch(scene, MaterialTag::kRoughPlastic, true, n, rows.In(), want.Out());
      simd::AreaEmitterRequestBatch(scene, MaterialTag::kRoughPlastic, true, n, rows.In(),
                                    got.Out());
      ExpectWithinContract(want, got, n);
      EXPECT_EQ(got.traced[n], 7) << "wrote past n";
      EXPECT_EQ(got.col[8][n], -7.0f) << "wrote past n";
    }
  });
}

// The samples' own radiance (le columns, textured area lights) instead of the light's: random
// per-row values, among them 0, tiny and huge, on every material tag and tail length.
TEST(AreaRequest8, PerSampleRadianceMatchesOracle) {
  StatusOr<Scene> loaded = LoadSceneFile(std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml");
  ASSERT_TRUE(loaded.ok()) << loaded.status().message();
  Scene& scene = *loaded;
  test::AddRequestMaterials(&scene);
  Pcg32 rng(6, 21);
  static const float kOdd[] = {0.0f, 1e-30f, 1e20f, 3.5f};
  for (int t = 0; t < kMaterialTagCount; ++t) {
    const MaterialTag tag = static_cast<MaterialTag>(t);
    if (test::MaterialRows(scene.materials, tag) == 0) continue;
    SCOPED_TRACE("tag " + std::to_string(t));
    test::AreaRequestRows rows = test::MakeAreaRequestRows(scene, tag, 20000, true, rng);
    const size_t n = rows.size();
    std::vector<float> le[3];
    for (auto& col : le) {
      col.resize(n);
      for (float& x : col) x = rng.NextUint() % 5 == 0 ? kOdd[rng.NextUint() % 4] : rng.NextFloat();
    }
    AreaRequestInputs in = rows.In();
    in.le_r = le[0].data(), in.le_g = le[1].data(), in.le_b = le[2].data();
    test::AreaRequestColumns want(n);
    AreaEmitterRequestBatch(scene, tag, true, n, in, want.Out());
    test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
      for (size_t cut = 0; cut < 8; ++cut) {
        const size_t m = n - cut;
        test::AreaRequestColumns got(m);
        simd::AreaEmitterRequestBatch(scene, tag, true, m, in, got.Out());
        ExpectWithinContract(want, got, m);
      }
    });
  }
}

const std::string kSharedData = test_data::Dir();

TEST(AreaRequest8, MatchesOracleOnCbox) {
  ExpectBatchMatchesOracle(std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml");
}

TEST(AreaRequest8, MatchesOracleOnVeach) {
  ExpectBatchMatchesOracle(kSharedData + "nori/epfl/scenes/pa5/veach_mi/veach_mis.xml");
}

TEST(AreaRequest8, MatchesOracleOnTable) {
  ExpectBatchMatchesOracle(kSharedData + "nori/epfl/scenes/pa5/table/table_mis.xml");
}

}  // namespace
}  // namespace ptlab
