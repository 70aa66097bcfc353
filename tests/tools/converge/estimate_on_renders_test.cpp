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
// scene (whose own noise adds 128/4096 = 3 % to the measured relMSE: divided out), K = 8 seeds;
// the mean ratio must be within 4 standard errors (over seeds) of 1.
// DISABLED: it fails today, and the failure is the finding (issue 44). Measured 2026-12-06
// (--gtest_also_run_disabled_tests --gtest_filter='*ConvergeEstimate*'), 48x48 cbox:
//   path_mis   0.935 +- 0.012 (single seeds 0.894-0.978)
//   path_mats  0.973 +- 0.024 (0.872-1.071)
//   direct_mis 0.768 +- 0.056 (0.589-0.971)
// The estimate reads low on real renders, beyond the +3 % its 3x3 denominator explains
// (convergence_test.cpp); not yet understood (a bias between 64-spp and 4096-spp renders would
// do it). Enable once explained or fixed; do not widen it.
TEST(StatConvergeEstimate, DISABLED_TracksTheTrueRelMseOnRenders) {
  struct Case {
    std::string scene;
    IntegratorDesc::Type type;
  };
  using T = IntegratorDesc::Type;
  const std::string cbox = std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml";
  const Case cases[] = {{cbox, T::kPathMis}, {cbox, T::kPathMats}, {cbox, T::kDirectMis}};
  for (const Case& c : cases) {
    StatusOr<Scene> loaded = LoadScene(c.scene);
    ASSERT_TRUE(loaded.ok()) << loaded.status().message();
    Scene scene = *loaded;
    scene.integrator.type = c.type;
    scene.camera.width = 48, scene.camera.height = 48;
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
    std::printf("%s %s: estimate/true over 8 seeds: mean %.3f +- %.3f (range %.3f-%.3f)\n",
                c.scene.c_str(), IntegratorTypeName(c.type), mean, se, lo, hi);
    EXPECT_LT(std::fabs(mean - 1), 4 * se) << IntegratorTypeName(c.type);
  }
}

}  // namespace
}  // namespace ptlab
