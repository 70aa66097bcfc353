// `ptlab render --integrator NAME`: overrides the scene's integrator, says when bdpt falls back
// to the scalar oracle, and refuses what bdpt does not run with.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "engine/image/image_io.h"
#include "tests/tools/command_test_util.h"

using namespace ptlab::test_util;

namespace ptlab {
namespace {

namespace fs = std::filesystem;

const std::string kPtlab = std::string(PTLAB_BINARY_DIR) + "/bin/ptlab";
const std::string kCbox = std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml";

TEST(PtlabIntegratorFlag, OverridesTheSceneAndReportsTheScalarFallback) {
  const fs::path dir = TempDir("integrator_flag");
  const fs::path out = dir / "cbox.exr";
  ASSERT_EQ(RunShell(kPtlab + " render " + kCbox + " -o " + out.string() +
                         " --spp 2 --width 32 --height 24 --integrator bdpt --stats -q",
                     dir / "log"),
            0)
      << ReadFile(dir / "log");
  EXPECT_NE(ReadFile(dir / "log").find("bdpt has no wavefront yet"), std::string::npos)
      << ReadFile(dir / "log");
  StatusOr<Image> image = ReadImage(out.string());
  ASSERT_TRUE(image.ok());
  EXPECT_EQ(image->width, 32);
  // The EXR header names the integrator that rendered it.
  EXPECT_NE(ReadFile(out).find("bdpt"), std::string::npos);
}

TEST(PtlabIntegratorFlag, RefusesUnknownNamesAndAdaptiveSampling) {
  const fs::path dir = TempDir("integrator_flag_bad");
  EXPECT_EQ(RunShell(kPtlab + " render " + kCbox + " -o " + (dir / "a.exr").string() +
                         " --spp 2 --width 32 --height 24 --integrator bidir -q",
                     dir / "log"),
            2);
  EXPECT_EQ(RunShell(kPtlab + " render " + kCbox + " -o " + (dir / "b.exr").string() +
                         " --spp 2 --width 32 --height 24 --integrator ptracer -a 8 0.05 -q",
                     dir / "log2"),
            2);
  EXPECT_NE(ReadFile(dir / "log2").find("ptracer does not run with -a"), std::string::npos)
      << ReadFile(dir / "log2");
}

}  // namespace
}  // namespace ptlab
