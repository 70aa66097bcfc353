// A Mitsuba 3 test-suite scene that loads fully (floating_sphere: obj meshes, a shared <ref>
// BSDF, a directional emitter, the direct integrator in a moment wrapper) rendered and compared
// with Mitsuba's reference at tolerances derived from the reference's variance image. Label
// `image` (suite name *ImageParity*). The proper per-pixel Z test comes with `imgdiff --ztest`.
#include <gtest/gtest.h>

#include "tests/test_data.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <thread>

#include "engine/image/image_io.h"
#include "engine/io/scene_file.h"
#include "tests/engine/render/packet_render_for_test.h"
#include "tools/imgdiff/imgdiff.h"

namespace ptlab {
namespace {

const std::string kScenes =
    ptlab::test_data::Path("mitsuba3/tests/scenes/");

TEST(MitsubaImageParity, FloatingSphereDirectional) {
  const std::string scene_path = kScenes + "floating_sphere/test_directional_direct.xml";
  const std::string ref_path = kScenes + "floating_sphere/refs/test_directional_ref_rgb.exr";
  const std::string var_path = kScenes + "floating_sphere/refs/test_directional_ref_rgb_var.exr";
  PTLAB_REQUIRE_DATA(scene_path);
  StatusOr<Scene> scene = LoadSceneFile(scene_path);
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  ASSERT_EQ(scene->integrator.type, IntegratorDesc::Type::kDirectMis);
  ASSERT_EQ(scene->directional_lights.size(), 1u);
  StatusOr<Image> ref = ReadImage(ref_path), var = ReadImage(var_path);
  ASSERT_TRUE(ref.ok() && var.ok());

  // Mitsuba's test renders 2,000,000 samples over the image; seed fixed.
  RenderOptions options;
  const int pixels = ref->width * ref->height;
  options.spp = uint32_t(2000000 / pixels);
  options.threads = std::max(1u, std::thread::hardware_concurrency());
  options.seed = 1;
  const RenderResult result = RenderWithPackets(*scene, options);
  ASSERT_EQ(result.image.width, ref->width);
  ASSERT_EQ(result.image.height, ref->height);
  const ImageDiff diff = CompareImages(result.image, *ref, ImageDiffOptions{});

  // var is Mitsuba's per-sample variance per pixel channel. If ptlab's per-sample variance is
  // about Mitsuba's (here both sample the delta light and the pixel area alike), the image mean
  // differs from the reference's by a normal error of deviation sqrt(Σ var / spp) / pixels: we
  // allow 4 deviations (two-sided α ≈ 6e-5 at the fixed seed). The mean squared difference is
  // ≈ mean(var) / spp (the reference's own error is negligible): we allow 1.5 times that, i.e.
  // a ptlab variance per sample up to 1.5 times Mitsuba's (measured: 0.87). And no more than
  // 0.25 % of pixel channels (Mitsuba's failing share) may be 5 deviations off, with var
  // clamped below at 1e-4 as in Mitsuba's test.
  const double spp = options.spp;
  int far_off = 0;
  for (int c = 0; c < 3; ++c) {
    double var_sum = 0;
    for (int i = 0; i < pixels; ++i) {
      const double v = var->rgb[size_t(i) * 3 + c];
      var_sum += std::max(v, 0.0);
      const double d = result.image.rgb[size_t(i) * 3 + c] - ref->rgb[size_t(i) * 3 + c];
      if (std::fabs(d) > 5 * std::sqrt(std::max(v, 1e-4) / spp)) ++far_off;
    }
    const double mean_sigma = std::sqrt(var_sum / spp) / pixels;
    EXPECT_LE(std::fabs(diff.mean_a[c] - diff.mean_b[c]), 4 * mean_sigma)
        << "channel " << c << ": mean " << diff.mean_a[c] << " vs reference " << diff.mean_b[c];
    const double expected_mse = var_sum / pixels / spp;
    EXPECT_LE(diff.mse[c], 1.5 * expected_mse)
        << "channel " << c << ": MSE " << diff.mse[c] << ", expected about " << expected_mse;
  }
  EXPECT_LE(far_off, int(0.0025 * pixels * 3)) << far_off << " pixel channels 5 sigma off";
}

}  // namespace
}  // namespace ptlab
