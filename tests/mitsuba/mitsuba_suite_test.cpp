// Mitsuba 3's render-test suite: each scene of tests/mitsuba/suite.txt rendered by the ptlab CLI
// at Mitsuba's spp and judged by Mitsuba's Z test, or expected to stop as its row says.
#include <gtest/gtest.h>

#include "tests/test_data.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "engine/image/image_io.h"
#include "tests/tools/command_test_util.h"
#include "tools/imgdiff/ztest.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;

const std::string kTable = PTLAB_SOURCE_DIR "/tests/mitsuba/suite.txt";
const std::string kScenes = ptlab::test_data::Path("mitsuba3/tests/scenes");
const std::string kPtlab = PTLAB_BINARY_DIR "/bin/ptlab";

struct SuiteRow {
  std::string name, scene, expected, mitsuba_var, arguments;
  int line = 0;
};

// gtest prints a parameter with this (instead of its bytes).
void PrintTo(const SuiteRow& r, std::ostream* os) { *os << r.name; }

// The rows of the table, and the problems found reading it ("suite.txt:LINE: ...").
struct SuiteTable {
  std::vector<SuiteRow> rows;
  std::vector<std::string> errors;
};

SuiteTable ReadSuiteTable() {
  SuiteTable t;
  std::ifstream in(kTable);
  if (!in) {
    t.errors.push_back(kTable + ": cannot read the table");
    return t;
  }
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream fields(line);
    SuiteRow r;
    r.line = n;
    if (!(fields >> r.name)) continue;  // blank or comment
    const std::string where = "suite.txt:" + std::to_string(n) + ": ";
    if (!(fields >> r.scene >> r.expected >> r.mitsuba_var)) {
      t.errors.push_back(where + "expected: name scene expected mitsuba_var [arguments]");
      continue;
    }
    std::getline(fields, r.arguments);
    if (r.expected != "pass" && r.expected != "unsupported" && r.expected != "error" &&
        r.expected != "fail")
      t.errors.push_back(where + "expected '" + r.expected +
                         "'; use pass, fail, unsupported or error");
    if (r.mitsuba_var != "pass" && r.mitsuba_var != "fail" && r.mitsuba_var != "-")
      t.errors.push_back(where + "mitsuba_var '" + r.mitsuba_var + "'; use pass, fail or -");
    for (char c : r.name)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_')
        t.errors.push_back(where + "name '" + r.name + "': letters, digits and _ only");
    if (r.arguments.find('\'') != std::string::npos)
      t.errors.push_back(where + "arguments may not contain a single quote");
    t.rows.push_back(r);
  }
  return t;
}

const SuiteTable& Table() {
  static const SuiteTable table = ReadSuiteTable();
  return table;
}

// Mitsuba's reference names: the scene's stem without its last "_<integrator>".
std::string ReferenceStem(const std::string& scene) {
  const fs::path p(scene);
  std::string stem = p.stem().string();
  const size_t underscore = stem.rfind('_');
  if (underscore != std::string::npos) stem.resize(underscore);
  return (fs::path(kScenes) / p.parent_path() / "refs" / stem).string();
}


TEST(MitsubaSuiteTable, IsWellFormedAndListsEverySceneOnce) {
  for (const std::string& e : Table().errors) ADD_FAILURE() << e;
  PTLAB_REQUIRE_DATA(kScenes);
  std::set<std::string> listed, names;
  for (const SuiteRow& r : Table().rows) {
    EXPECT_TRUE(listed.insert(r.scene).second)
        << "suite.txt:" << r.line << ": " << r.scene << " listed twice";
    EXPECT_TRUE(names.insert(r.name).second)
        << "suite.txt:" << r.line << ": " << r.name << " named twice";
    EXPECT_TRUE(fs::exists(kScenes + "/" + r.scene)) << "suite.txt:" << r.line;
    EXPECT_TRUE(fs::exists(ReferenceStem(r.scene) + "_ref_rgb.exr")) << "suite.txt:" << r.line;
  }
  // Every scene that has an RGB reference is in the table.
  for (const fs::directory_entry& dir : fs::directory_iterator(kScenes)) {
    if (!dir.is_directory()) continue;
    for (const fs::directory_entry& f : fs::directory_iterator(dir.path())) {
      if (f.path().extension() != ".xml") continue;
      const std::string scene = dir.path().filename().string() + "/" + f.path().filename().string();
      if (!fs::exists(ReferenceStem(scene) + "_ref_rgb.exr")) continue;
      EXPECT_TRUE(listed.count(scene)) << scene << " has a reference but no row in suite.txt";
    }
  }
  EXPECT_EQ(listed.size(), 29u);
}

class MitsubaSuite : public ::testing::TestWithParam<SuiteRow> {};

// ptlab's own per-sample variance comes from the tested render's passes when it has at least
// this many samples per pixel; below, from a second render of VarianceSpp(spp) samples with
// seed 1 (independent of the tested image, seed 0). A few samples cannot estimate the variance
// of a pixel whose rare bright paths they miss, and a Z test is only as good as its variance.
// Measured on various_emitters (61 spp, paths of ~1 in 1000 samples carry much of some pixels'
// light; Mitsuba's variance passes 99.877 % of channels, 99.75 % needed): with the image's own
// variance 95.4 % pass (pixels whose 61 samples all missed have variance 0), with a 1024-spp
// variance 99.71 %, 4096 spp 99.85 %, 8192 spp 99.885 %.
constexpr uint32_t kOwnVarianceMinSpp = 256;
uint32_t VarianceSpp(uint32_t spp) { return std::max<uint32_t>(1024, 64 * spp); }

// Writes the Z test's p-value and failed-pixel images of a failure beside the render.
void WriteFailure(const ZTestResult& r, const fs::path& prefix) {
  EXPECT_TRUE(WriteExr(prefix.string() + "_pvalue.exr", r.p_value).ok());
  EXPECT_TRUE(WriteExr(prefix.string() + "_failed.exr", r.failed_pixels).ok());
}

TEST_P(MitsubaSuite, Renders) {
  const SuiteRow& row = GetParam();
  PTLAB_REQUIRE_DATA(kScenes);
  const std::string ref_path = ReferenceStem(row.scene) + "_ref_rgb.exr";
  const StatusOr<Image> ref = ReadImage(ref_path);
  ASSERT_TRUE(ref.ok()) << ref.status().message();
  const int64_t pixels = int64_t(ref->width) * ref->height;
  const uint32_t spp = uint32_t(2000000 / pixels);  // Mitsuba's budget, integer division
  const fs::path dir = test_util::TempDir("mitsuba/" + row.name);
  const fs::path out = dir / (row.name + ".exr"), log = dir / "log.txt";
  const std::string command = kPtlab + " render " + kScenes + "/" + row.scene + " --spp " +
                              std::to_string(spp) + " --seed 0 --moments -q -o " + out.string() +
                              " " + row.arguments;
  const auto start = std::chrono::steady_clock::now();
  const int rc = test_util::RunShell(command, log);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string output = test_util::ReadFile(log);
  SCOPED_TRACE("suite.txt:" + std::to_string(row.line) + ": " + row.name + " expected " +
               row.expected + "\n$ " + command + "\n" + output);
  if (row.expected == "error") {
    EXPECT_EQ(rc, 2);
    std::printf("mitsuba-suite | %s | error (as expected: exit %d) | %.1f s | %s", row.name.c_str(),
                rc, seconds, output.c_str());
    return;
  }
  if (row.expected == "unsupported") {
    EXPECT_EQ(rc, 2);
    EXPECT_NE(output.find("unsupported"), std::string::npos);
    std::printf("mitsuba-suite | %s | unsupported | %.1f s | %s", row.name.c_str(), seconds,
                output.c_str());
    return;
  }
  ASSERT_EQ(rc, 0);
  std::string var_path = (dir / (row.name + "_var.exr")).string();
  if (spp < kOwnVarianceMinSpp) {
    const fs::path pilot = dir / (row.name + "_variance.exr");
    const std::string pilot_command = kPtlab + " render " + kScenes + "/" + row.scene +
                                      " --spp " + std::to_string(VarianceSpp(spp)) +
                                      " --seed 1 --moments -q -o " + pilot.string() + " " +
                                      row.arguments;
    ASSERT_EQ(test_util::RunShell(pilot_command, log), 0)
        << "$ " << pilot_command << "\n" << test_util::ReadFile(log);
    var_path = (dir / (row.name + "_variance_var.exr")).string();
  }
  const StatusOr<Image> image = ReadImage(out.string());
  const StatusOr<Image> own_var = ReadImage(var_path);
  const StatusOr<Image> ref_var = ReadImage(ReferenceStem(row.scene) + "_ref_rgb_var.exr");
  ASSERT_TRUE(image.ok()) << image.status().message();
  ASSERT_TRUE(own_var.ok()) << own_var.status().message();
  ASSERT_TRUE(ref_var.ok()) << ref_var.status().message();
  ASSERT_TRUE(image->width == ref->width && image->height == ref->height)
      << "render " << image->width << "x" << image->height << ", reference " << ref->width << "x"
      << ref->height;
  ZTestOptions options;
  options.spp = spp;
  const ZTestResult own = ZTest(*image, *ref, *own_var, options);
  const ZTestResult mitsuba = ZTest(*image, *ref, *ref_var, options);
  std::printf(
      "mitsuba-suite | %s | %s (own variance, %.4f %% of channels) | Mitsuba's variance: "
      "%s (%.4f %%) | %u spp%s | %.1f s\n",
      row.name.c_str(), own.pass ? "pass" : "FAIL", 100 * own.pass_share,
      mitsuba.pass ? "pass" : "fail", 100 * mitsuba.pass_share, spp,
      spp < kOwnVarianceMinSpp
          ? (" (own variance from " + std::to_string(VarianceSpp(spp)) + " spp, seed 1)").c_str()
          : "",
      seconds);
  if (!own.pass) WriteFailure(own, dir / (row.name + "_own"));
  if (!mitsuba.pass) WriteFailure(mitsuba, dir / (row.name + "_mitsuba"));
  // expected = fail: a known failure (the row's comment says why); when it starts to pass,
  // flip the row.
  if (row.expected == "fail") {
    EXPECT_FALSE(own.pass) << "passes now: flip the row to pass";
  } else {
    EXPECT_TRUE(own.pass) << FormatZTestTable(own);
  }
  if (row.mitsuba_var == "pass") {
    EXPECT_TRUE(mitsuba.pass) << FormatZTestTable(mitsuba);
  } else if (row.mitsuba_var == "fail") {
    EXPECT_FALSE(mitsuba.pass) << FormatZTestTable(mitsuba);
  }
}

std::string RowName(const ::testing::TestParamInfo<SuiteRow>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Scenes, MitsubaSuite, ::testing::ValuesIn(Table().rows), RowName);

}  // namespace
}  // namespace ptlab
