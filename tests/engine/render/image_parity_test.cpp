// Image parity with Nori's official references (../shared/PARITY.md), label `image`.
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "engine/bvh/bvh.h"
#include "engine/image/image_io.h"
#include "engine/render/render.h"
#include "engine/scene/xml_loader.h"
#include "tools/imgdiff/imgdiff.h"

namespace ptlab {
namespace {

const std::string kData = std::string(PTLAB_SOURCE_DIR) + "/../shared/data/nori/";

struct ParityCase {
  const char* name;
  const char* scene;      // under kData
  const char* reference;  // under kData
  double floor;           // PARITY.md's f
  // The eth2015 references were rendered by the 2015-16 Nori, whose lookat frame is mirrored
  // (PARITY.md's mirror convention) and, when `up` is not perpendicular to the view
  // direction, not normalised (a zoom: 4.3 % for odyssey). A horizontal flip alone leaves
  // odyssey 8 % too dark and 45 % of blocks off; so we render those scenes with the old
  // frame (LookatConvention::kNori2015) and compare without flipping.
  LookatConvention lookat;
};

void PrintTo(const ParityCase& c, std::ostream* os) { *os << c.name; }

class ImageParity : public ::testing::TestWithParam<ParityCase> {};

TEST_P(ImageParity, MatchesReference) {
  const ParityCase& c = GetParam();
  const std::string scene_path = kData + c.scene, ref_path = kData + c.reference;
  if (!std::filesystem::exists(scene_path) || !std::filesystem::exists(ref_path))
    GTEST_SKIP() << "reference data not found under " << kData;
  StatusOr<Scene> scene = LoadScene(scene_path, LoadOptions{c.lookat});
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  StatusOr<Image> reference = ReadImage(ref_path);
  ASSERT_TRUE(reference.ok()) << reference.status().message();

  RenderOptions options;
  // At the XML's sample count, as the references were rendered.
  options.spp = scene->sampler.sample_count;
  options.threads = std::max(1u, std::thread::hardware_concurrency());
  options.seed = 1;
  const Bvh bvh = BuildBvh(scene->triangles);
  const RenderResult result = Render(*scene, bvh, options);
  ASSERT_EQ(result.spp_done, options.spp);

  const ParityResult parity = CheckParity(result.image, *reference, c.floor, /*flip_x=*/false);
  const std::string out_dir = std::string(PTLAB_BINARY_DIR) + "/test-output";
  std::filesystem::create_directories(out_dir);
  ASSERT_TRUE(WriteExr(out_dir + "/" + c.name + ".exr", result.image, {}).ok());
  EXPECT_TRUE(parity.pass) << c.name << ": " << parity.summary << "\n(render written to "
                           << out_dir << "/" << c.name << ".exr)";
  std::printf("%s: %s  [%u spp, %.1f s]\n", c.name, parity.summary.c_str(), result.spp_done,
              result.seconds);
}

INSTANTIATE_TEST_SUITE_P(
    Foundation, ImageParity,
    ::testing::Values(
        ParityCase{"bunny", "epfl/scenes/pa1/bunny.xml", "epfl/references/bunny.exr", 0.97, LookatConvention::kNori},
        ParityCase{"cbox_distributed", "epfl/scenes/pa4/cbox/cbox-distributed.xml",
                   "epfl/references/cbox-distributed.exr", 0.97, LookatConvention::kNori},
        ParityCase{"motto_diffuse", "epfl/scenes/pa4/motto/motto-diffuse.xml",
                   "epfl/references/motto-diffuse.exr", 0.95, LookatConvention::kNori},
        ParityCase{"odyssey_ems", "eth2015/scenes/pa3/odyssey/odyssey_ems.xml",
                   "eth2015/scenes/pa3/odyssey/ref/odyssey_ems_64spp.exr", 0.95, LookatConvention::kNori2015},
        ParityCase{"odyssey_mats", "eth2015/scenes/pa3/odyssey/odyssey_mats.xml",
                   "eth2015/scenes/pa3/odyssey/ref/odyssey_mats_64spp.exr", 0.95, LookatConvention::kNori2015},
        ParityCase{"odyssey_mis", "eth2015/scenes/pa3/odyssey/odyssey_mis.xml",
                   "eth2015/scenes/pa3/odyssey/ref/odyssey_mis_32spp.exr", 0.95, LookatConvention::kNori2015}),
    [](const ::testing::TestParamInfo<ParityCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace ptlab
