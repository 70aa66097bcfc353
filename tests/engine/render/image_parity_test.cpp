// Image parity with Nori's official references (docs/parity.md), label `image`.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "engine/bvh/bvh.h"
#include "engine/image/image_io.h"
#include "engine/io/xml_loader.h"
#include "engine/render/render.h"
#include "tests/engine/render/packet_render_for_test.h"
#include "tests/test_data.h"
#include "tools/imgdiff/imgdiff.h"

namespace ptlab {
namespace {

const std::string kData = test_data::Path("nori/");

struct ParityCase {
  const char* name;
  const char* scene;      // under kData
  const char* reference;  // under kData
  double floor;           // docs/parity.md's f
  // The eth2015 references were rendered by the 2015-16 Nori, whose lookat frame is mirrored
  // (docs/parity.md's mirror convention) and, when `up` is not perpendicular to the view
  // direction, not normalised (a zoom: 4.3 % for odyssey). A horizontal flip alone leaves
  // odyssey 8 % too dark and 45 % of blocks off; so we render those scenes with the old
  // frame (LookatConvention::kNori2015) and compare without flipping.
  LookatConvention lookat;
  // Sample counts: 0 = the XML's. `full_spp` overrides it for every run (a reference rendered
  // at more samples than its XML says); `quick_spp`, if set, is used by `./lab test` without
  // --full (PTLAB_FULL unset) for the expensive path-traced scenes, to keep the suite short.
  uint32_t full_spp = 0;
  uint32_t quick_spp = 0;
  // The sampler to render with instead of the XML's (null: the XML's, `independent` in every
  // Nori scene).
  const char* sampler = nullptr;
};

bool FullQuality() {
  const char* v = std::getenv("PTLAB_FULL");
  return v != nullptr && std::string(v) == "1";
}

void PrintTo(const ParityCase& c, std::ostream* os) { *os << c.name; }

class ImageParity : public ::testing::TestWithParam<ParityCase> {};

TEST_P(ImageParity, MatchesReference) {
  const ParityCase& c = GetParam();
  const std::string scene_path = kData + c.scene, ref_path = kData + c.reference;
  PTLAB_REQUIRE_DATA(scene_path);
  PTLAB_REQUIRE_DATA(ref_path);
  StatusOr<Scene> scene = LoadScene(scene_path, LoadOptions{c.lookat});
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  if (c.sampler) {
    ASSERT_TRUE(SamplerTypeFromName(c.sampler, &scene->sampler.type));
  }
  StatusOr<Image> reference = ReadImage(ref_path);
  ASSERT_TRUE(reference.ok()) << reference.status().message();

  RenderOptions options;
  // At the XML's sample count, as the references were rendered (see ParityCase).
  options.spp = c.full_spp ? c.full_spp : scene->sampler.sample_count;
  if (!FullQuality() && c.quick_spp) options.spp = std::min(options.spp, c.quick_spp);
  options.threads = std::max(1u, std::thread::hardware_concurrency());
  options.seed = 1;
  const RenderResult result = RenderWithPackets(*scene, options);
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

// Direct illumination from Nori's ETH `distantdisk` (issue 5): a constant environment (ao) and a
// small cone ("sun", side), rendered with the 2015-16 lookat like every eth2015 reference.
INSTANTIATE_TEST_SUITE_P(
    DistantDisk, ImageParity,
    ::testing::Values(
        ParityCase{"sphere_ao_ems", "eth2015/scenes/pa3/sphere/sphere_ao_ems.xml",
                   "eth2015/scenes/pa3/sphere/ref/sphere_ao_ems_256spp.exr", 0.97,
                   LookatConvention::kNori2015},
        ParityCase{"sphere_ao_mats", "eth2015/scenes/pa3/sphere/sphere_ao_mats.xml",
                   "eth2015/scenes/pa3/sphere/ref/sphere_ao_mats_256spp.exr", 0.97,
                   LookatConvention::kNori2015},
        ParityCase{"sphere_ao_mis", "eth2015/scenes/pa3/sphere/sphere_ao_mis.xml",
                   "eth2015/scenes/pa3/sphere/ref/sphere_ao_mis_128spp.exr", 0.97,
                   LookatConvention::kNori2015},
        ParityCase{"sphere_side_ems", "eth2015/scenes/pa3/sphere/sphere_side_ems.xml",
                   "eth2015/scenes/pa3/sphere/ref/sphere_side_ems_256spp.exr", 0.94,
                   LookatConvention::kNori2015},
        // BSDF sampling of a 10° cone is noisy: at the reference's 256 spp we agree on 91 % of
        // blocks (< 0.94), so this one renders at 4x the reference's samples (docs/parity.md
        // allows more).
        ParityCase{"sphere_side_mats", "eth2015/scenes/pa3/sphere/sphere_side_mats.xml",
                   "eth2015/scenes/pa3/sphere/ref/sphere_side_mats_256spp.exr", 0.94,
                   LookatConvention::kNori2015, 1024},
        ParityCase{"sphere_side_mis", "eth2015/scenes/pa3/sphere/sphere_side_mis.xml",
                   "eth2015/scenes/pa3/sphere/ref/sphere_side_mis_128spp.exr", 0.95,
                   LookatConvention::kNori2015}),
    [](const ::testing::TestParamInfo<ParityCase>& info) { return std::string(info.param.name); });

// Materials (issue 4): glass text under Whitted.
INSTANTIATE_TEST_SUITE_P(
    Materials, ImageParity,
    ::testing::Values(ParityCase{"motto_dielectric", "epfl/scenes/pa4/motto/motto-dielectric.xml",
                                 "epfl/references/motto-dielectric.exr", 0.95,
                                 LookatConvention::kNori, 0, 128}),
    [](const ::testing::TestParamInfo<ParityCase>& info) { return std::string(info.param.name); });

// Path tracing (issue 5): Veach's MIS plates (Beckmann rough plastic) and the table (glass,
// water, rough plastic). The eth2015 table XMLs reach their meshes through a symlink that
// ../shared/data stores as a plain file, so they are rendered from the byte-identical epfl
// XMLs at the eth2015 XML's 512 spp.
INSTANTIATE_TEST_SUITE_P(
    PathTracing, ImageParity,
    ::testing::Values(
        // BSDF sampling alone rarely finds the small lights, and this reference is the noisiest
        // of the three: at its own 256 spp our render agrees on 80 % of blocks (< 0.84; vs the
        // less noisy veach_ems reference 88.5 %). Rendered at 4x the reference's samples
        // (docs/parity.md allows more): 87.2 %. Always at 1024 spp.
        ParityCase{"veach_mats", "epfl/scenes/pa5/veach_mi/veach_mats.xml",
                   "epfl/references/veach_mats.exr", 0.84, LookatConvention::kNori, 1024, 0},
        ParityCase{"veach_ems", "epfl/scenes/pa5/veach_mi/veach_ems.xml",
                   "epfl/references/veach_ems.exr", 0.84, LookatConvention::kNori, 0, 64},
        ParityCase{"veach_mis", "epfl/scenes/pa5/veach_mi/veach_mis.xml",
                   "epfl/references/veach_mis.exr", 0.88, LookatConvention::kNori, 0, 64},
        ParityCase{"table_ems", "epfl/scenes/pa5/table/table_ems.xml",
                   "epfl/references/table_ems.exr", 0.97, LookatConvention::kNori, 0, 64},
        ParityCase{"table_path_mats_512spp", "epfl/scenes/pa5/table/table_mats.xml",
                   "eth2015/scenes/pa4/table/ref/table_path_mats_512spp.exr", 0.97,
                   LookatConvention::kNori2015, 512, 64},
        ParityCase{"table_path_mis_512spp", "epfl/scenes/pa5/table/table_mis.xml",
                   "eth2015/scenes/pa4/table/ref/table_path_mis_512spp.exr", 0.97,
                   LookatConvention::kNori2015, 512, 64}),
    [](const ::testing::TestParamInfo<ParityCase>& info) { return std::string(info.param.name); });

// The Sobol' sampler (issue 15) reaches the same references as the independent one, with the
// default power light selection and solid-angle triangle sampling (every case above runs
// those too, with the XMLs' independent sampler).
INSTANTIATE_TEST_SUITE_P(
    Samplers, ImageParity,
    ::testing::Values(
        ParityCase{"veach_mis_sobol", "epfl/scenes/pa5/veach_mi/veach_mis.xml",
                   "epfl/references/veach_mis.exr", 0.88, LookatConvention::kNori, 0, 64,
                   "sobol"},
        ParityCase{"table_path_mis_512spp_sobol", "epfl/scenes/pa5/table/table_mis.xml",
                   "eth2015/scenes/pa4/table/ref/table_path_mis_512spp.exr", 0.97,
                   LookatConvention::kNori2015, 512, 64, "sobol"},
        ParityCase{"cbox_distributed_sobol", "epfl/scenes/pa4/cbox/cbox-distributed.xml",
                   "epfl/references/cbox-distributed.exr", 0.97, LookatConvention::kNori, 0, 0,
                   "sobol"}),
    [](const ::testing::TestParamInfo<ParityCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace ptlab
