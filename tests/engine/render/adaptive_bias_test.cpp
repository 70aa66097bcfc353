// Adaptive sampling is unbiased enough: block-wise test of an adaptive render's pixel estimates
// against a non-adaptive render with twice the samples, on a scene lit by a small bright light.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/io/xml_loader.h"
#include "engine/render/render.h"
#include "tests/engine/render/packet_render_for_test.h"
#include "tools/chi2/stats_math.h"

namespace ptlab {
namespace {

// A diffuse 4 x 4 floor under a small (0.5 x 0.5) bright light, seen from above at an angle, traced by
// BSDF sampling only (path_mats): about one floor sample in eight hits the light, so about a
// third of the floor pixels' first batches of 8 are all black — the case CS184's rule stopped
// black (0 <= 0) for good.
constexpr const char* kSmallLightScene = R"(<scene>
  <integrator type="path_mats"/>
  <camera type="perspective">
    <transform name="toWorld"><lookat origin="0,2.5,3" target="0,0,0" up="0,1,0"/></transform>
    <float name="fov" value="40"/><integer name="width" value="64"/><integer name="height" value="64"/>
  </camera>
  <shape type="rectangle"><transform name="toWorld"><scale value="2,2,1"/>
    <rotate axis="1,0,0" angle="-90"/></transform>
    <bsdf type="diffuse"><color name="albedo" value="0.6,0.6,0.6"/></bsdf></shape>
  <shape type="rectangle"><transform name="toWorld"><scale value="0.25,0.25,1"/>
    <rotate axis="1,0,0" angle="90"/><translate value="0,0.8,0"/></transform>
    <emitter type="area"><color name="radiance" value="20,20,20"/></emitter></shape>
</scene>)";

// Per-pixel luminance moments of a render (adaptive sampling records them; tolerance 0 keeps
// every pixel that has any variance going to the last sample).
std::vector<PixelMoments> RenderMoments(const Scene& scene, uint32_t spp, float tolerance,
                                        uint64_t seed) {
  RenderOptions options;
  options.spp = spp;
  options.threads = 2;
  options.seed = seed;
  options.adaptive = {8, tolerance};
  std::vector<PixelMoments> moments;
  options.on_pass = [&moments](const RenderPass& pass) { moments = *pass.pixels; };
  RenderWithPackets(scene, options);
  return moments;
}

// Per 8x8 block: the mean of the pixels' luminance estimates and the variance of that mean
// (Σ s_p² / n_p over the pixels, / 64²).
void BlockMeans(const std::vector<PixelMoments>& m, int width, int height, std::vector<double>* mean,
                std::vector<double>* var) {
  const int bw = width / 8, bh = height / 8;
  mean->assign(size_t(bw * bh), 0.0);
  var->assign(size_t(bw * bh), 0.0);
  for (int y = 0; y < bh * 8; ++y) {
    for (int x = 0; x < bw * 8; ++x) {
      const PixelMoments& p = m[size_t(y * width + x)];
      const size_t b = size_t((y / 8) * bw + x / 8);
      if (p.n < 2) continue;
      const double n = p.n, mu = p.sum / n;
      const double s2 = std::max(0.0, (p.sum2 - n * mu * mu) / (n - 1));
      (*mean)[b] += mu / 64, (*var)[b] += s2 / n / (64.0 * 64.0);
    }
  }
}

// Every block's adaptive mean against the reference's, z = Δ / sqrt(v_a + v_r), two-sided at
// α = 0.01 Šidák-corrected over the blocks; and the image means within 4 standard errors.
TEST(StatAdaptiveSampling, AgreesWithNonAdaptiveRenderBlockByBlock) {
  StatusOr<Scene> scene = LoadSceneFromString(kSmallLightScene, ".", "small_light.xml");
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  const int w = scene->camera.width, h = scene->camera.height;
  const std::vector<PixelMoments> adaptive = RenderMoments(*scene, 1024, 0.25f, 5);
  const std::vector<PixelMoments> reference = RenderMoments(*scene, 2048, 0.0f, 6);
  ASSERT_EQ(adaptive.size(), size_t(w * h));
  ASSERT_EQ(reference.size(), size_t(w * h));
  uint64_t taken = 0;
  for (const PixelMoments& p : adaptive) taken += p.taken;
  std::vector<double> ma, va, mr, vr;
  BlockMeans(adaptive, w, h, &ma, &va);
  BlockMeans(reference, w, h, &mr, &vr);
  const double alpha = SidakAlpha(0.01, int(ma.size()));
  double sum_a = 0, sum_r = 0, var_a = 0, var_r = 0;
  int lit = 0;
  for (size_t b = 0; b < ma.size(); ++b) {
    sum_a += ma[b], sum_r += mr[b], var_a += va[b], var_r += vr[b];
    if (!(mr[b] > 0)) continue;
    ++lit;
    const double z = (ma[b] - mr[b]) / std::sqrt(va[b] + vr[b]);
    const double p = std::erfc(std::fabs(z) / std::sqrt(2.0));
    EXPECT_GE(p, alpha) << "block " << b << ": adaptive " << ma[b] << " vs " << mr[b]
                        << " (z = " << z << ")";
  }
  EXPECT_GT(lit, int(ma.size()) / 2);
  EXPECT_LT(std::fabs(sum_a - sum_r), 4 * std::sqrt(var_a + var_r))
      << "image means " << sum_a << " vs " << sum_r;
  // The run is adaptive: some pixels stopped early.
  EXPECT_LT(taken, uint64_t(w) * uint64_t(h) * 1024);
  std::printf("adaptive: %.1f samples per pixel on average; image mean %.5f vs %.5f\n",
              double(taken) / double(w * h), sum_a, sum_r);
}

}  // namespace
}  // namespace ptlab
