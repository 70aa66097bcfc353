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

TEST(AdaptiveSampling, StoppingRuleIsCs184s) {
  // Mean 1, sample variance 1/3 (n = 4: 0.5, 0.5, 1.5, 1.5): I = 1.96 sqrt(1/12) = 0.5658.
  const PixelMoments m = MomentsOf({0.5, 0.5, 1.5, 1.5});
  EXPECT_TRUE(PixelConverged(m, 0.57f));
  EXPECT_FALSE(PixelConverged(m, 0.56f));
  EXPECT_FALSE(PixelConverged(MomentsOf({1.0}), 1.0f));  // one sample: no variance yet
  EXPECT_TRUE(PixelConverged(MomentsOf({0.0, 0.0}), 0.05f));  // black: I = 0 <= 0
  EXPECT_TRUE(PixelConverged(MomentsOf({2.0, 2.0, 2.0}), 1e-6f));
  // A non-finite sample is taken but not in the moments.
  PixelMoments inf = MomentsOf({1.0, 1.0});
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
    EXPECT_GE(n, 8u);
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
