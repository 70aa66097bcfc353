// Adaptive sampling (CS184's -a batch tolerance): the stopping rule, the sample counts, and the
// same result on the packet and the scalar path.
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "engine/render/render.h"
#include "engine/io/xml_loader.h"
#include "tests/engine/render/packet_render_for_test.h"

namespace ptlab {
namespace {

PixelMoments MomentsOf(const std::vector<double>& samples) {
  PixelMoments m;
  for (const double y : samples) ++m.taken, ++m.n, m.sum += y, m.sum2 += y * y;
  return m;
}

// n copies of each value.
std::vector<double> Repeat(const std::vector<double>& values, int n) {
  std::vector<double> out;
  for (int k = 0; k < n; ++k) out.insert(out.end(), values.begin(), values.end());
  return out;
}

TEST(AdaptiveSampling, StoppingRuleIsCs184sWithAMinimumAndNoBlackStop) {
  // 32 samples, mean 1, sample variance 0.25 · 32/31: I = 1.96 sqrt(0.25 / 31) = 0.17601.
  const PixelMoments m = MomentsOf(Repeat({0.5, 1.5}, 16));
  EXPECT_TRUE(PixelConverged(m, 0.177f));
  EXPECT_FALSE(PixelConverged(m, 0.175f));
  // Fewer than kAdaptiveMinSamples samples never stop, however tight.
  EXPECT_FALSE(PixelConverged(MomentsOf(Repeat({2.0}, 31)), 1.0f));
  EXPECT_TRUE(PixelConverged(MomentsOf(Repeat({2.0}, 32)), 1e-6f));
  // A pixel that has seen no light does not stop (CS184's rule did: I = 0 <= 0).
  EXPECT_FALSE(PixelConverged(MomentsOf(Repeat({0.0}, 1024)), 0.05f));
  // A non-finite sample is taken but not in the moments.
  PixelMoments inf = MomentsOf(Repeat({1.0}, 32));
  ++inf.taken;
  EXPECT_TRUE(PixelConverged(inf, 0.01f));
}

struct AdaptiveRun {
  RenderResult result;
  std::vector<PixelMoments> moments;  // after the last pass
  std::vector<uint32_t> pass_spp;
};

enum class RenderPath { kScalar, kOracleWavefront, kSimdWavefront };

AdaptiveRun RenderAdaptive(const Scene& scene, RenderPath path) {
  RenderOptions options;
  options.spp = 128;
  options.threads = 2;
  options.seed = 3;
  options.adaptive = {8, 0.05f};
  AdaptiveRun run;
  options.on_pass = [&run](const RenderPass& pass) {
    ASSERT_NE(pass.pixels, nullptr);
    run.moments = *pass.pixels;
    run.pass_spp.push_back(pass.spp_done);
  };
  switch (path) {
    case RenderPath::kScalar: {
      const Bvh bvh = BuildBvh(scene.triangles, scene.spheres);
      run.result = Render(scene, bvh, options);
      break;
    }
    case RenderPath::kOracleWavefront:
      run.result = RenderWithOracleWavefront(scene, options);
      break;
    case RenderPath::kSimdWavefront:
      run.result = RenderWithPackets(scene, options);
      break;
  }
  return run;
}

TEST(AdaptiveSampling, PixelsStopByTheRuleAndCountsAddUp) {
  StatusOr<Scene> scene = LoadScene(std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml");
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  scene->camera.width = scene->camera.height = 48;
  const AdaptiveRun run = RenderAdaptive(*scene, RenderPath::kSimdWavefront);
  const RenderResult& r = run.result;
  ASSERT_EQ(r.pixel_samples.size(), size_t(48 * 48));
  EXPECT_FALSE(r.interrupted);
  // Passes are batches of 8 samples.
  for (size_t k = 0; k < run.pass_spp.size(); ++k) EXPECT_EQ(run.pass_spp[k], 8 * (k + 1));
  uint64_t sum = 0;
  int stopped = 0, full = 0;
  for (size_t p = 0; p < r.pixel_samples.size(); ++p) {
    const uint32_t n = r.pixel_samples[p];
    sum += n;
    EXPECT_EQ(n % 8, 0u) << p;
    EXPECT_GE(n, kAdaptiveMinSamples);
    EXPECT_LE(n, 128u);
    EXPECT_EQ(run.moments[p].taken, n);
    if (n < r.spp_done) {
      ++stopped;
      // It stopped because the rule held after its last batch...
      EXPECT_TRUE(PixelConverged(run.moments[p], 0.05f)) << "pixel " << p << " n " << n;
    } else {
      ++full;
    }
  }
  EXPECT_EQ(sum, r.samples_taken);  // the sample-rate image sums to the samples taken
  // ...and the run is not trivial: some pixels stopped early, some took every sample.
  EXPECT_GT(stopped, 48 * 48 / 10);
  EXPECT_GT(full, 0);
  EXPECT_LT(r.samples_taken, uint64_t(48 * 48) * 128);
}

TEST(AdaptiveSampling, OracleWavefrontAndScalarPathsAgreeBitForBit) {
  StatusOr<Scene> scene = LoadScene(std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml");
  ASSERT_TRUE(scene.ok());
  scene->camera.width = 40, scene->camera.height = 24;
  // The wavefront with the oracle's kernel table: its adaptive bookkeeping, bit for bit.
  const AdaptiveRun a = RenderAdaptive(*scene, RenderPath::kOracleWavefront),
                    b = RenderAdaptive(*scene, RenderPath::kScalar);
  EXPECT_EQ(a.result.pixel_samples, b.result.pixel_samples);
  ASSERT_EQ(a.result.image.rgb.size(), b.result.image.rgb.size());
  EXPECT_EQ(std::memcmp(a.result.image.rgb.data(), b.result.image.rgb.data(),
                        a.result.image.rgb.size() * sizeof(float)),
            0);
}

}  // namespace
}  // namespace ptlab
