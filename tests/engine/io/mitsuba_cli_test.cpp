// `ptlab render` on Mitsuba scenes as a user runs it: -D parameters, and exit status 2 with a
// file:line:col "unsupported" message for a plugin ptlab cannot render.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/tools/command_test_util.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;
using test_util::ReadFile;
using test_util::RunShell;

const std::string kPtlab = std::string(PTLAB_BINARY_DIR) + "/bin/ptlab";

TEST(MitsubaCli, DefinesAndUnsupportedExitTwo) {
  if (!fs::exists(kPtlab)) GTEST_SKIP() << "build the ptlab target first";
  const fs::path dir = test_util::TempDir("mitsuba_cli");
  std::ofstream(dir / "scene.xml")
      << "<scene version=\"3.0.0\">\n"
         "  <default name=\"bsdf\" value=\"diffuse\"/>\n"
         "  <sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" "
         "value=\"4\"/><integer name=\"height\" value=\"4\"/></film></sensor>\n"
         "  <emitter type=\"constant\"/>\n"
         "  <shape type=\"rectangle\">\n"
         "    <bsdf type=\"$bsdf\"/></shape>\n"
         "</scene>\n";
  const fs::path log = dir / "log.txt";
  const std::string render = kPtlab + " render " + (dir / "scene.xml").string() + " -q -s 2 -o " +
                             (dir / "out.exr").string();
  EXPECT_EQ(RunShell(render, log), 0) << ReadFile(log);
  EXPECT_TRUE(fs::exists(dir / "out.exr"));
  // principled: principled loads now (and renders); pplastic is an unsupported BSDF.
  EXPECT_EQ(RunShell(render + " -D bsdf=principled", log), 0) << ReadFile(log);
  EXPECT_EQ(RunShell(render + " -D bsdf=pplastic", log), 2);
  EXPECT_NE(
      ReadFile(log).find((dir / "scene.xml").string() + ":6:5: unsupported: bsdf \"pplastic\""),
      std::string::npos)
      << ReadFile(log);
  EXPECT_EQ(RunShell(render + " -D bsdf", log), 2);
  EXPECT_NE(ReadFile(log).find("malformed parameter definition 'bsdf' (-D)"), std::string::npos)
      << ReadFile(log);
}

}  // namespace
}  // namespace ptlab
