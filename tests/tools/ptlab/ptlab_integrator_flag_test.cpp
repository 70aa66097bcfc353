// `ptlab render --integrator NAME`: overrides the scene's integrator, writes bdpt's per-strategy
// images with --strategies, and refuses what bdpt does not run with.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "engine/image/image_io.h"
#include "engine/render/strategy_figure.h"
#include "tests/tools/command_test_util.h"

using namespace ptlab::test_util;

namespace ptlab {
namespace {

namespace fs = std::filesystem;

const std::string kPtlab = std::string(PTLAB_BINARY_DIR) + "/bin/ptlab";
const std::string kCbox = std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml";

TEST(PtlabIntegratorFlag, OverridesTheSceneAndWritesStrategyImages) {
  const fs::path dir = TempDir("integrator_flag");
  const fs::path out = dir / "cbox.exr";
  ASSERT_EQ(RunShell(kPtlab + " render " + kCbox + " -o " + out.string() +
                         " --spp 2 --width 32 --height 24 --integrator bdpt --stats -q" +
                         " --strategies " + (dir / "st").string(),
                     dir / "log"),
            0)
      << ReadFile(dir / "log");
  // bdpt's rays go through the packet traversal.
  EXPECT_EQ(ReadFile(dir / "log").find(" 0 packets"), std::string::npos) << ReadFile(dir / "log");
  for (const char* name : {"s0_t2.exr", "s1_t2.exr", "s2_t1.exr", "s2_t2.exr"}) {
    StatusOr<Image> part = ReadImage((dir / "st" / name).string());
    ASSERT_TRUE(part.ok()) << name << ": " << ReadFile(dir / "log");
    EXPECT_EQ(part->width, 32);
  }
  // Veach's figure: 5 rows (0-4 bounces) and 6 columns of 32 x 24 tiles with their gaps.
  StatusOr<Image> figure = ReadImage((dir / "st" / "figure.png").string());
  ASSERT_TRUE(figure.ok()) << ReadFile(dir / "log");
  EXPECT_EQ(figure->width, 6 * 32 + 5 * kStrategyFigureGap);
  EXPECT_EQ(figure->height, 5 * 24 + 4 * kStrategyFigureGap);
  // Only for the bidirectional integrators.
  EXPECT_EQ(RunShell(kPtlab + " render " + kCbox + " -o " + (dir / "p.exr").string() +
                         " --spp 1 --width 32 --height 24 --integrator path_mis -q --strategies " +
                         (dir / "st2").string(),
                     dir / "log3"),
            2);
  EXPECT_NE(ReadFile(dir / "log3").find("--strategies"), std::string::npos)
      << ReadFile(dir / "log3");
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
