// Issue 12: every hostile input in tests/data/bad/ makes ptlab exit with a code (never a
// signal) and the expected message, or render finite pixels. Each row is a finding that
// crashed, hung or silently misbehaved before.
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "engine/image/image_io.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;

const std::string kPtlab = std::string(PTLAB_BINARY_DIR) + "/bin/ptlab";
const std::string kBad = std::string(PTLAB_SOURCE_DIR) + "/tests/data/bad/";

struct BadInput {
  const char* file;     // in tests/data/bad/
  const char* command;  // ptlab subcommand
  int exit_code;        // 0: renders (finite pixels checked)
  const char* expect;   // in the output
};

// Finding numbers refer to issue 12.
const BadInput kBadInputs[] = {
    {"cr_only_obj.xml", "render", 0, "wrote:"},                          // 1
    {"huge_sphere.xml", "render", 1, "within +-1e+12"},                  // 2
    {"film_int_max.xml", "render", 1, "expected each side in 1..65536"}, // 3
    {"film_too_many_pixels.xml", "render", 1, "expected at most 67108864"},
    {"filter_radius_1e9.xml", "render", 1, "filter radius in (0, 8]"},  // 4
    {"filter_radius_1e30.xml", "render", 1, "filter radius in (0, 8]"},
    {"chi2_resolution_1000.xml", "test", 3, "expected 1..256"},  // 5
    {"chi2_resolution_65536.xml", "test", 3, "expected 1..256"},
};

std::string ReadFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(PtlabBadInput, EveryFileExitsWithACodeAndAMessage) {
  const fs::path dir = fs::path(PTLAB_BINARY_DIR) / "test-output" / "bad_input";
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const BadInput& c : kBadInputs) {
    SCOPED_TRACE(c.file);
    const fs::path out = dir / "out.exr";
    fs::remove(out);
    const std::string command = "timeout 60 " + kPtlab + " " + c.command + " " + kBad + c.file +
                                (std::string(c.command) == "render" ? " -q -o " + out.string()
                                                                    : std::string()) +
                                " > " + (dir / "log").string() + " 2>&1";
    const int rc = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(rc));
    const int code = WEXITSTATUS(rc);
    const std::string log = ReadFile(dir / "log");
    EXPECT_NE(code, 124) << "timed out\n" << log;
    EXPECT_LT(code, 128) << "died by signal " << code - 128 << "\n" << log;
    EXPECT_EQ(code, c.exit_code) << log;
    EXPECT_NE(log.find(c.expect), std::string::npos) << "'" << c.expect << "' not in:\n" << log;
    if (c.exit_code == 0 && std::string(c.command) == "render") {
      const StatusOr<Image> image = ReadImage(out.string());
      ASSERT_TRUE(image.ok()) << image.status().message();
      for (const float v : image->rgb) ASSERT_TRUE(std::isfinite(v));
    }
  }
}

// Every scene or test file in tests/data/bad/ is a row of the table above.
TEST(PtlabBadInput, TableCoversTheDirectory) {
  std::set<std::string> listed;
  for (const BadInput& c : kBadInputs) listed.insert(c.file);
  for (const auto& e : fs::directory_iterator(kBad)) {
    if (e.path().extension() == ".xml")
      EXPECT_TRUE(listed.count(e.path().filename().string())) << e.path();
  }
}

}  // namespace
}  // namespace ptlab
