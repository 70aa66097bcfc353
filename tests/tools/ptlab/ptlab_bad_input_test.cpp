// Issue 12: every hostile input in tests/data/bad/ makes ptlab exit with a code (never a
// signal) and the expected message, or render finite pixels. Each row is a finding that
// crashed, hung or silently misbehaved before.
#include <sys/wait.h>
#include <unistd.h>

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

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

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
    {"huge_sphere.xml", "render", 2, "within +-1e+12"},                  // 2
    {"film_int_max.xml", "render", 2, "expected each side in 1..65536"}, // 3
    {"film_too_many_pixels.xml", "render", 2, "expected at most 67108864"},
    {"filter_radius_1e9.xml", "render", 2, "filter radius in (0, 8]"},  // 4
    {"filter_radius_1e30.xml", "render", 2, "filter radius in (0, 8]"},
    {"chi2_resolution_1000.xml", "test", 2, "expected 1..256"},  // 5
    {"chi2_resolution_65536.xml", "test", 2, "expected 1..256"},
    {"radiance_near_float_max.xml", "render", 2, "expected components in [0, 1e20]"},  // 9
    // 7: a truncated Radiance HDR decoded as black (flat) or hung stb_image (run-length); an
    // EXR attribute claiming 2 GiB was allocated before OpenEXR noticed the file is 1 KiB.
    {"truncated_rle.hdr", "envmap-pdf", 2, "truncated in the run-length data of scanline 1"},
    {"truncated_flat.hdr", "envmap-pdf", 2, "truncated: 8 flat pixels need 32 bytes"},
    {"exr_huge_attribute.exr", "envmap-pdf", 2, "'junk' (blob) claims 2147483647 bytes"},
    {"huge_claim.hdr", "envmap-pdf", 2, "header claims"},
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
                                (std::string(c.command) == "render"       ? " -q -o " + out.string()
                                 : std::string(c.command) == "envmap-pdf" ? " -o " + (dir / "pdf.png").string()
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

// Findings 8, 10 and 11: flags and outputs ptlab cannot use are refused before rendering,
// with exit code 2 for bad usage and 3 for an output or a machine that cannot take the render.
TEST(PtlabBadInput, FlagsAndOutputsAreCheckedBeforeRendering) {
  const fs::path dir = fs::path(PTLAB_BINARY_DIR) / "test-output" / "bad_flags";
  fs::remove_all(dir);
  fs::create_directories(dir / "dir.exr");
  const std::string scene = std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml";
  const std::string small = " --spp 1 --width 8 --height 8 -q -o " + (dir / "x.exr").string();
  struct Case {
    std::string args;
    int exit_code;
    const char* expect;
  };
  const Case cases[] = {
      {"render " + scene + " --seed -1" + small, 2, "not an unsigned integer"},
      {"render " + scene + " --seed 1e3" + small, 2, "not an unsigned integer"},
      {"render " + scene + " --spp 1 -o ''", 2, "output path is empty"},
      {"render " + scene + " --spp 1 -o " + (dir / "missing" / "x.exr").string(), 3,
       "does not exist"},
      {"render " + scene + " --spp 1 -o " + (dir / "dir.exr").string(), 2, "is a directory"},
      {"render " + scene + " --width 65536 --height 65536 -o " + (dir / "x.exr").string(), 2,
       "expected at most 67108864"},
      // 1000 thread stacks do not fit 3 GB of address space: a clear error, not an abort.
      {"render " + scene + " --threads 1000" + small, 3, "cannot start worker thread"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    // Sanitizers reserve terabytes of address space for their shadow memory, so a process
    // under `ulimit -v` cannot start at all: that case needs an uninstrumented build.
    if (kSanitized && c.args.find("--threads 1000") != std::string::npos) continue;
    const std::string prefix =
        c.args.find("--threads 1000") != std::string::npos ? "ulimit -v 3000000; " : "";
    const std::string command = "sh -c \"" + prefix + "timeout 60 " + kPtlab + " " + c.args +
                                " > " + (dir / "log").string() + " 2>&1\"";
    const int rc = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(rc));
    const std::string log = ReadFile(dir / "log");
    EXPECT_EQ(WEXITSTATUS(rc), c.exit_code) << log;
    EXPECT_NE(log.find(c.expect), std::string::npos) << "'" << c.expect << "' not in:\n" << log;
    EXPECT_EQ(log.find("wrote:"), std::string::npos) << log;
  }
}

// Finding 11 in the other tools: NaN passed CLI11's Range and PositiveNumber checks.
TEST(PtlabBadInput, NonFiniteFlagsOfChi2AndImgdiffAreUsageErrors) {
  const fs::path dir = fs::path(PTLAB_BINARY_DIR) / "test-output" / "bad_tool_flags";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string bin = std::string(PTLAB_BINARY_DIR) + "/bin/";
  const std::string image = (dir / "tiny.pfm").string();
  Image tiny(1, 1);
  tiny.rgb = {0.5f, 0.5f, 0.5f};
  ASSERT_TRUE(WriteImage(image, tiny).ok());
  for (const std::string& args :
       {"imgdiff " + image + " " + image + " --tol nan", "imgdiff " + image + " " + image +
        " --fail-rmse inf", std::string("chi2 --alpha nan diffuse"),
        std::string("chi2 --seed -1 diffuse")}) {
    SCOPED_TRACE(args);
    const int rc = std::system((bin + args + " > " + (dir / "log").string() + " 2>&1").c_str());
    ASSERT_TRUE(WIFEXITED(rc));
    const std::string log = ReadFile(dir / "log");
    EXPECT_EQ(WEXITSTATUS(rc), 2) << log;  // the usage-error code of every tool
    EXPECT_TRUE(log.find("not a finite number") != std::string::npos ||
                log.find("not an unsigned integer") != std::string::npos)
        << log;
  }
}

// Finding 12: the temporaries a killed render left beside the output are removed by the next
// render to the same output when their process is gone; a live process's are kept.
TEST(PtlabBadInput, StaleTemporariesOfDeadProcessesAreRemoved) {
  const fs::path dir = fs::path(PTLAB_BINARY_DIR) / "test-output" / "stale_tmp";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // A pid that is not running: a child that has exited and been reaped.
  const pid_t dead = fork();
  ASSERT_GE(dead, 0);
  if (dead == 0) _exit(0);
  waitpid(dead, nullptr, 0);
  const fs::path stale_exr = dir / ("x.exr.tmp-" + std::to_string(dead));
  const fs::path stale_png = dir / ("x.png.tmp-" + std::to_string(dead));
  const fs::path live = dir / ("x.exr.tmp-" + std::to_string(getpid()));
  for (const fs::path& p : {stale_exr, stale_png, live}) std::ofstream(p) << "partial";
  const std::string command = kPtlab + " render " + PTLAB_SOURCE_DIR +
                              "/scenes/cbox.xml --spp 1 --width 8 --height 8 -q -o " +
                              (dir / "x.exr").string() + " > " + (dir / "log").string() + " 2>&1";
  const int rc = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(rc));
  EXPECT_EQ(WEXITSTATUS(rc), 0) << ReadFile(dir / "log");
  EXPECT_FALSE(fs::exists(stale_exr));
  EXPECT_FALSE(fs::exists(stale_png));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(dir / "x.exr"));
  EXPECT_TRUE(fs::exists(dir / "x.png"));
}

// Every scene, test file or image in tests/data/bad/ is a row of the table above.
TEST(PtlabBadInput, TableCoversTheDirectory) {
  std::set<std::string> listed;
  for (const BadInput& c : kBadInputs) listed.insert(c.file);
  for (const auto& e : fs::directory_iterator(kBad)) {
    const std::string ext = e.path().extension().string();
    if (ext == ".xml" || ext == ".hdr" || ext == ".exr") {
      EXPECT_TRUE(listed.count(e.path().filename().string())) << e.path();
    }
  }
}

}  // namespace
}  // namespace ptlab
