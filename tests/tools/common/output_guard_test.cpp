// The output guard: outputs that are inputs (by path, symbolic link or hard link) or other
// outputs are refused naming both; names past NAME_MAX/PATH_MAX and missing folders too.
#include "tools/common/output_guard.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/tools/command_test_util.h"
#include "tools/common/exit_codes.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;

class OutputGuardTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test: CTest runs the tests of this fixture side by side.
    dir_ = test_util::TempDir(std::string("output_guard_") +
                              ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::ofstream(dir_ / "scene.xml") << "<scene/>";
  }
  std::string P(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(OutputGuardTest, AnOutputThatIsAnInputIsRefusedNamingBoth) {
  OutputGuard guard;
  guard.AddInput(P("scene.xml"), "scene");
  guard.AddOutput(P("scene.xml"), "--tile-times");
  std::string error;
  EXPECT_EQ(guard.Check(&error), kExitUsage);
  EXPECT_NE(error.find("'" + P("scene.xml") + "' (--tile-times) is the same file as the input '" +
                       P("scene.xml") + "' (scene)"),
            std::string::npos)
      << error;
}

TEST_F(OutputGuardTest, SameFileThroughAnotherPathLinkOrHardLink) {
  fs::create_directories(dir_ / "sub");
  fs::create_symlink(dir_ / "scene.xml", dir_ / "link.xml");
  fs::create_hard_link(dir_ / "scene.xml", dir_ / "hard.xml");
  for (const std::string& out :
       {P("sub/../scene.xml"), P("./scene.xml"), P("link.xml"), P("hard.xml")}) {
    OutputGuard guard;
    guard.AddInput(P("scene.xml"), "scene");
    guard.AddOutput(out, "-o");
    std::string error;
    EXPECT_EQ(guard.Check(&error), kExitUsage) << out;
    EXPECT_NE(error.find("is the same file as the input"), std::string::npos) << error;
  }
  // A relative spelling of the same file, from the current folder.
  const fs::path cwd = fs::current_path();
  fs::current_path(dir_);
  OutputGuard guard;
  guard.AddInput(P("scene.xml"), "scene");
  guard.AddOutput("scene.xml", "-o");
  std::string error;
  EXPECT_EQ(guard.Check(&error), kExitUsage);
  fs::current_path(cwd);
}

TEST_F(OutputGuardTest, TwoOutputsIntoOneFileAreRefused) {
  OutputGuard guard;
  guard.AddOutput(P("x.png"), "PNG output");
  guard.AddOutput(P("./x.png"), "--tile-times");
  std::string error;
  EXPECT_EQ(guard.Check(&error), kExitUsage);
  EXPECT_NE(error.find("are the same file"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(dir_ / "x.png"));
}

TEST_F(OutputGuardTest, NamesTooLongForTheTemporaryAndMissingFoldersAreRefused) {
  std::string error;
  {
    OutputGuard guard;
    guard.AddOutput(P(std::string(250, 'a') + ".exr"), "-o");
    EXPECT_EQ(guard.Check(&error), kExitUsage);
    EXPECT_NE(error.find("expected at most"), std::string::npos) << error;
  }
  {
    std::string deep = P("");
    while (deep.size() < 5000) deep += "d/";
    OutputGuard guard;
    guard.AddOutput(deep + "x.exr", "-o");
    EXPECT_EQ(guard.Check(&error), kExitUsage);
    EXPECT_NE(error.find("PATH_MAX"), std::string::npos) << error;
  }
  {
    OutputGuard guard;
    guard.AddOutput(P("missing/x.exr"), "-o");
    EXPECT_EQ(guard.Check(&error), kExitRunFailed);
    EXPECT_NE(error.find("does not exist"), std::string::npos) << error;
  }
  {
    OutputGuard guard;
    guard.AddOutput(dir_.string(), "-o");
    EXPECT_EQ(guard.Check(&error), kExitUsage);
  }
}

TEST_F(OutputGuardTest, ReadOnlyFoldersFailBeforeAnyWork) {
  if (::geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders";
  fs::create_directories(dir_ / "ro");
  fs::permissions(dir_ / "ro", fs::perms::owner_read | fs::perms::owner_exec);
  std::string error;
  EXPECT_EQ(PrepareOutputFolder(P("ro"), &error), kExitRunFailed);
  EXPECT_NE(error.find("ro"), std::string::npos) << error;
  OutputGuard guard;
  guard.AddOutput(P("ro/x.exr"), "-o");
  EXPECT_EQ(guard.Check(&error), kExitRunFailed);
  fs::permissions(dir_ / "ro", fs::perms::owner_all);
}

TEST_F(OutputGuardTest, DistinctFilesPass) {
  OutputGuard guard;
  guard.AddInput(P("scene.xml"), "scene");
  guard.AddOutput(P("out.exr"), "EXR output");
  guard.AddOutput(P("out.png"), "PNG output");
  guard.AddOutput("", "--tile-times");  // not given
  std::string error;
  EXPECT_EQ(guard.Check(&error), kExitOk) << error;
  EXPECT_FALSE(fs::exists(dir_ / "out.exr"));  // the probe leaves nothing behind
}

}  // namespace
}  // namespace ptlab
