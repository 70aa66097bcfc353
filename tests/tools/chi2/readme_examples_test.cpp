// docs/chi2.md's "Validating your own sampler": its examples are the files tests run, verbatim.
#include <gtest/gtest.h>

#include <string>

#include "tests/tools/command_test_util.h"

namespace ptlab {
namespace {

using test_util::ReadFile;
using test_util::RunShell;
using test_util::TempDir;

// Each example file appears in docs/chi2.md as a whole fenced block.
TEST(Chi2Readme, ExamplesAreIncludedVerbatim) {
  const std::string readme = ReadFile(PTLAB_SOURCE_DIR "/docs/chi2.md");
  ASSERT_FALSE(readme.empty());
  const struct {
    const char* path;
    const char* lang;
  } files[] = {{"examples/chi2_external/CMakeLists.txt", "cmake"},
               {"examples/chi2_external/power_cosine_check.cpp", "cpp"},
               {"examples/chi2_python/power_cosine.py", "python"},
               {"examples/chi2_cli/check.sh", "sh"},
               {"examples/chi2_cli/power_cosine_samples.py", "python"},
               {"examples/chi2_cli/power_cosine_pdf.py", "python"}};
  for (const auto& f : files) {
    const std::string text = ReadFile(std::string(PTLAB_SOURCE_DIR "/") + f.path);
    ASSERT_FALSE(text.empty()) << f.path;
    const std::string block = "```" + std::string(f.lang) + "\n" + text + "```\n";
    EXPECT_NE(readme.find(block), std::string::npos)
        << f.path << " is not in docs/chi2.md verbatim as a ```" << f.lang << " block";
  }
}

// The file-based route exactly as docs/chi2.md shows it (with the built chi2 as $CHI2).
TEST(StatChi2Readme, CliRouteRunsAsWritten) {
  const auto dir = TempDir("chi2_readme_cli");
  const std::string cmd = "cd " + dir.string() +
                          " && CHI2=" PTLAB_BINARY_DIR "/bin/chi2 " PTLAB_SOURCE_DIR
                          "/examples/chi2_cli/check.sh";
  ASSERT_EQ(RunShell(cmd, dir / "log.txt"), 0) << ReadFile(dir / "log.txt");
  const std::string log = ReadFile(dir / "log.txt");
  EXPECT_NE(log.find("\"passed\": true"), std::string::npos) << log;
  EXPECT_FALSE(ReadFile(dir / "chi2_images" / "samples.png").empty());
}

}  // namespace
}  // namespace ptlab
