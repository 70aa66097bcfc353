// The reference-free relMSE estimate (two halves) on real renders, several scenes and integrators:
// the mean over seeds of estimate / true relMSE, with its standard error, against 1.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/io/xml_loader.h"
#include "engine/render/render.h"
#include "tests/engine/render/packet_render_for_test.h"
#include "tools/converge/convergence.h"
#include "tools/imgdiff/imgdiff.h"
#include "tests/test_data.h"

namespace ptlab {
namespace {

Image RenderAt(const Scene& scene, uint32_t spp, uint64_t seed) {
  RenderOptions options;
  options.spp = spp;
  options.threads = 2;
  options.seed = seed;
  return RenderWithPackets(scene, options).image;
}

// The merged image of two independent halves of 64 spp against a 4096-spp reference of the same
// scene (whose own noise adds 128/4096 = 3 % to the measured relMSE: divided out), K = 8 seeds.
// Smooth pixels (kSmooth: MIS or emitter sampling on cbox and Nori's table): the mean ratio
// within 4 standard errors (over seeds) of 1 and within 10 %. Heavy-tailed pixels (kHeavyTailed)
// are the known limit: a pixel whose samples are mostly dark with a rare bright one (a rare hit
// of the light, a glint smaller than the pixel) has its d² and its own mean raised together by
// that sample, or sees no variance at all when neither half draws it, so d²/m² reads low; the
// mean ratio must lie in [0.7, 1). Such cases: path_mats on cbox (BSDF sampling alone; measured
// 0.798 ± 0.019) and path_mis on Nori's veach_mis (the small bright lights' glints on the smooth
// plates cover part of a pixel: the four pixels of largest true error, on the plates, hold 13 % of
// it and the estimate sees under half of theirs; hiding the emitters seen directly moves neither
// them nor the ratio much (0.760), nor does 96 px (0.785 ± 0.034)). History (issue 44): with a 3x3 neighbourhood mean as the denominator the cbox ratios
// were 0.935 ± 0.012 (path_mis), 0.973 ± 0.024 (path_mats), 0.768 ± 0.056 (direct_mis): the
// neighbourhood blurs every edge (the same halves over the reference's own values gave 0.999
// and 1.036 for path_mis and direct_mis).
TEST(StatConvergeEstimate, TracksTheTrueRelMseOnRenders) {
  enum class Pixels { kSmooth, kHeavyTailed };
  struct Case {
    std::string scene;
    IntegratorDesc::Type type;
    int width, height;
    Pixels pixels;
  };
  using T = IntegratorDesc::Type;
  using P = Pixels;
  const std::string cbox = std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml";
  const std::string table = test_data::Path("nori/epfl/scenes/pa5/table/table_mis.xml");
  const std::string veach = test_data::Path("nori/epfl/scenes/pa5/veach_mi/veach_mis.xml");
  PTLAB_REQUIRE_DATA(table);
  PTLAB_REQUIRE_DATA(veach);
  const Case cases[] = {
      {cbox, T::kPathMis, 48, 48, P::kSmooth},       {cbox, T::kPathMats, 48, 48, P::kHeavyTailed},
      {cbox, T::kDirectMis, 48, 48, P::kSmooth},     {table, T::kPathMis, 48, 36, P::kSmooth},
      {table, T::kPathEms, 48, 36, P::kSmooth},      {veach, T::kPathMis, 48, 32, P::kHeavyTailed}};
  for (const Case& c : cases) {
    StatusOr<Scene> loaded = LoadScene(c.scene);
    ASSERT_TRUE(loaded.ok()) << loaded.status().message();
    Scene scene = *loaded;
    scene.integrator.type = c.type;
    scene.camera.width = c.width, scene.camera.height = c.height;
    const Image reference = RenderAt(scene, 4096, 1000);
    std::vector<double> ratios;
    for (uint64_t seed = 1; seed <= 8; ++seed) {
      const Image a = RenderAt(scene, 64, 2 * seed), b = RenderAt(scene, 64, 2 * seed + 1);
      Image merged = a;
      for (size_t i = 0; i < merged.rgb.size(); ++i) merged.rgb[i] = 0.5f * (a.rgb[i] + b.rgb[i]);
      const double truth = CompareImages(merged, reference, {}).rel_mse_all / (1 + 128.0 / 4096);
      ratios.push_back(EstimateRelMseFromHalves(a, b) / truth);
    }
    double mean = 0, var = 0, lo = 1e300, hi = 0;
    for (double r : ratios) mean += r / 8, lo = std::min(lo, r), hi = std::max(hi, r);
    for (double r : ratios) var += (r - mean) * (r - mean) / 7;
    const double se = std::sqrt(var / 8);
    const std::string name = c.scene + " " + IntegratorTypeName(c.type);
    std::printf("%s %dx%d: estimate/true over 8 seeds: mean %.3f +- %.3f (range %.3f-%.3f)\n",
                name.c_str(), c.width, c.height, mean, se, lo, hi);
    if (c.pixels == P::kHeavyTailed) {
      EXPECT_GE(mean, 0.7) << name;
      EXPECT_LT(mean, 1.0) << name;
    } else {
      EXPECT_LT(std::fabs(mean - 1), 4 * se) << name;
      EXPECT_LT(std::fabs(mean - 1), 0.1) << name;
    }
  }
}

}  // namespace
}  // namespace ptlab
