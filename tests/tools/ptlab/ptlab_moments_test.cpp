// `ptlab render --moments`: NAME_var.exr beside the image, and the Z test with ptlab's own
// variance.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "engine/image/image_io.h"
#include "tests/tools/command_test_util.h"
#include "tools/imgdiff/ztest.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;
using test_util::ReadFile;
using test_util::RunShell;
using test_util::TempDir;

const std::string kPtlab = std::string(PTLAB_BINARY_DIR) + "/bin/ptlab";
const std::string kCbox = std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml";

TEST(PtlabMoments, WritesVarianceThatPassesTheZTestAgainstAReference) {
  const fs::path dir = TempDir("ptlab_moments");
  const std::string img = (dir / "img.exr").string(), ref = (dir / "ref.exr").string();
  ASSERT_EQ(RunShell(kPtlab + " render " + kCbox + " -o " + img +
                         " --width 16 --height 16 --spp 512 --seed 1 -q --moments",
                     dir / "log"),
            0)
      << ReadFile(dir / "log");
  ASSERT_EQ(RunShell(kPtlab + " render " + kCbox + " -o " + ref +
                         " --width 16 --height 16 --spp 4096 --seed 2 -q",
                     dir / "log2"),
            0)
      << ReadFile(dir / "log2");
  EXPECT_FALSE(fs::exists(dir / "ref_var.exr"));  // only with --moments
  StatusOr<Image> var = ReadImage((dir / "img_var.exr").string());
  ASSERT_TRUE(var.ok()) << var.status().message();
  ASSERT_EQ(var->width, 16);
  ASSERT_EQ(var->height, 16);
  const Image var_xyz = RgbToXyz(*var);
  int positive = 0;
  for (float v : var_xyz.rgb) {
    ASSERT_TRUE(std::isfinite(v));
    EXPECT_GE(v, -1e-6f);
    positive += v > 0;
  }
  EXPECT_GT(positive, 3 * 16 * 16 / 2);  // the box's pixels are noisy
  StatusOr<std::vector<std::pair<std::string, std::string>>> attrs =
      ReadExrStringAttributes((dir / "img_var.exr").string());
  ASSERT_TRUE(attrs.ok());
  bool described = false;
  for (const auto& [k, v] : *attrs)
    described |= k == "ptlab:variance" && v.find("32 passes") != std::string::npos;
  EXPECT_TRUE(described);
  StatusOr<Image> image = ReadImage(img), reference = ReadImage(ref);
  ASSERT_TRUE(image.ok() && reference.ok());
  ZTestOptions o;
  o.spp = 512;
  const ZTestResult r = ZTest(*image, *reference, *var, o);
  EXPECT_TRUE(r.pass) << FormatZTestTable(r);
  // 20 % too bright fails with the same variance.
  Image bright = *image;
  for (float& v : bright.rgb) v *= 1.2f;
  EXPECT_FALSE(ZTest(bright, *reference, *var, o).pass);
}

TEST(PtlabMoments, OnePassWarnsAndAdaptiveIsRefused) {
  const fs::path dir = TempDir("ptlab_moments_bad");
  const std::string img = (dir / "img.exr").string();
  ASSERT_EQ(RunShell(kPtlab + " render " + kCbox + " -o " + img +
                         " --width 8 --height 8 --spp 1 -q --moments",
                     dir / "log"),
            0)
      << ReadFile(dir / "log");
  EXPECT_NE(ReadFile(dir / "log").find("no variance estimate"), std::string::npos);
  EXPECT_EQ(RunShell(kPtlab + " render " + kCbox + " -o " + img +
                         " --width 8 --height 8 --spp 64 -q --moments -a 16 0.05",
                     dir / "log2"),
            2);
  EXPECT_NE(ReadFile(dir / "log2").find("--moments"), std::string::npos);
}

}  // namespace
}  // namespace ptlab
