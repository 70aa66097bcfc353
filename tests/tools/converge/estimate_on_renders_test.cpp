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
// scene (whose own noise adds 128/4096 = 3 % to the measured relMSE: divided out), K = 8 seeds.
// path_mis and direct_mis: the mean ratio within 4 standard errors (over seeds) of 1 and within
// 10 %. path_mats (BSDF sampling alone: a pixel's samples are heavy-tailed, mostly dark with a
// rare hit of the light) is a known exception: the rare sample raises the pixel's d² and its
// own mean together, so d²/m² reads low — measured 0.798 ± 0.019; it must stay in [0.7, 1).
// History (issue 44): with a 3x3 neighbourhood mean as the denominator the ratios were
// 0.935 ± 0.012 (path_mis), 0.973 ± 0.024 (path_mats), 0.768 ± 0.056 (direct_mis): the
// neighbourhood blurs every edge (the same halves over the reference's own values gave 0.999
// and 1.036 for path_mis and direct_mis).
TEST(StatConvergeEstimate, TracksTheTrueRelMseOnRenders) {
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
    if (c.type == T::kPathMats) {
      EXPECT_GE(mean, 0.7);
      EXPECT_LT(mean, 1.0);
    } else {
      EXPECT_LT(std::fabs(mean - 1), 4 * se) << IntegratorTypeName(c.type);
      EXPECT_LT(std::fabs(mean - 1), 0.1) << IntegratorTypeName(c.type);
    }
  }
}

}  // namespace
}  // namespace ptlab
