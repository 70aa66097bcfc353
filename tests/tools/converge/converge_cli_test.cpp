// `ptlab converge` run as a user would: outputs, bad arguments, and the statistics it reports
// (slope -1 of relMSE against spp for an unbiased estimator; the two-halves estimate).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/image/image_io.h"
#include "tests/tools/command_test_util.h"
#include "tools/converge/convergence.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;
using test_util::ReadFile;
using test_util::RunShell;

const std::string kPtlab = std::string(PTLAB_BINARY_DIR) + "/bin/ptlab";
const std::string kCbox = std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml";

// scenes/cbox.xml at size x size pixels with another integrator, written into dir.
fs::path SmallCbox(const fs::path& dir, int size, const std::string& integrator) {
  std::string xml = ReadFile(kCbox);
  auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = xml.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) xml.replace(at, from.size(), to);
  };
  replace("<integrator type=\"direct_mis\"/>", "<integrator type=\"" + integrator + "\"/>");
  replace("name=\"width\" value=\"512\"", "name=\"width\" value=\"" + std::to_string(size) + "\"");
  replace("name=\"height\" value=\"512\"", "name=\"height\" value=\"" + std::to_string(size) + "\"");
  const fs::path path = dir / "cbox_small.xml";
  std::ofstream(path) << xml;
  return path;
}

// converge.csv rows as column name -> text (RFC 4180 quotes).
std::vector<std::map<std::string, std::string>> ReadCsv(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  auto split = [](const std::string& l) {
    std::vector<std::string> f(1);
    bool quoted = false;
    for (size_t i = 0; i < l.size(); ++i) {
      const char c = l[i];
      if (c == '"' && quoted && i + 1 < l.size() && l[i + 1] == '"') f.back() += '"', ++i;
      else if (c == '"') quoted = !quoted;
      else if (c == ',' && !quoted) f.emplace_back();
      else f.back() += c;
    }
    return f;
  };
  std::vector<std::map<std::string, std::string>> rows;
  if (!std::getline(in, line)) return rows;
  const std::vector<std::string> names = split(line);
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split(line);
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < names.size() && i < f.size(); ++i) row[names[i]] = f[i];
    rows.push_back(row);
  }
  return rows;
}

TEST(ConvergeCli, WritesCsvJsonSummaryAndPlots) {
  const fs::path dir = test_util::TempDir("converge/outputs");
  const fs::path scene = SmallCbox(dir, 32, "direct_mis");
  const int rc = RunShell(kPtlab + " converge " + scene.string() +
                              " --ref auto --spp 32 --threads 1 --variant integrator=direct_mis"
                              " --variant integrator=direct_ems,lightSamples=2 -o " +
                              (dir / "out").string(),
                          dir / "log");
  ASSERT_EQ(rc, 0) << ReadFile(dir / "log");
  for (const char* f : {"converge.csv", "converge.json", "summary.md", "cbox_small_reference.exr",
                        "cbox_small_seconds.svg", "cbox_small_seconds.png", "cbox_small_spp.svg",
                        "cbox_small_spp.png", "cbox_small_efficiency.svg",
                        "cbox_small_efficiency.png"}) {
    ASSERT_TRUE(fs::exists(dir / "out" / f)) << f;
    EXPECT_GT(fs::file_size(dir / "out" / f), 100u) << f;
  }
  auto rows = ReadCsv(dir / "out" / "converge.csv");
  ASSERT_EQ(rows.size(), 4u);  // 2 variants x 2 passes of 16 spp
  for (const char* column : {"scene", "variant", "seed", "pass", "spp", "seconds", "rel_mse",
                             "rmse", "mae", "bias_r", "bias_g", "bias_b", "parity_share",
                             "estimated_rel_mse", "cpu_seconds"})
    EXPECT_TRUE(rows[0].count(column)) << column;
  // CPU time of the render: positive and growing pass by pass within a run.
  EXPECT_GT(std::stod(rows[0]["cpu_seconds"]), 0.0);
  EXPECT_GT(std::stod(rows[1]["cpu_seconds"]), std::stod(rows[0]["cpu_seconds"]));
  EXPECT_EQ(rows[3]["variant"], "integrator=direct_ems,lightSamples=2");
  EXPECT_EQ(rows[3]["spp"], "32");
  EXPECT_EQ(rows[0]["estimated_rel_mse"], "nan");  // one pass: no two halves yet
  EXPECT_NE(rows[1]["estimated_rel_mse"], "nan");
  const std::string json = ReadFile(dir / "out" / "converge.json");
  for (const char* key : {"\"references\"", "\"points\"", "\"summary\"", "\"efficiency\"",
                          "\"slope_spp\"", "\"seconds_to_rel_mse_1e-2\"", "auto: rendered by ptlab"})
    EXPECT_NE(json.find(key), std::string::npos) << key;
  EXPECT_NE(ReadFile(dir / "out" / "summary.md").find("| cbox_small | integrator=direct_mis |"),
            std::string::npos);
}

TEST(ConvergeCli, AdaptiveVariantWritesTheSampleRateImage) {
  const fs::path dir = test_util::TempDir("converge/adaptive");
  const fs::path scene = SmallCbox(dir, 32, "direct_mis");
  const int rc = RunShell(kPtlab + " converge " + scene.string() +
                              " --ref auto --spp 64 --threads 2 --no-plots"
                              " --variant adaptive=8:0.05 --variant adaptive=off -o " +
                              (dir / "out").string(),
                          dir / "log");
  ASSERT_EQ(rc, 0) << ReadFile(dir / "log");
  StatusOr<Image> counts =
      ReadImage((dir / "out" / "cbox_small_adaptive_8_0_05_seed1_samples.exr").string());
  ASSERT_TRUE(counts.ok()) << counts.status().message();
  EXPECT_TRUE(fs::exists(dir / "out" / "cbox_small_adaptive_8_0_05_seed1_samples.png"));
  double sum = 0;
  for (size_t i = 0; i < counts->rgb.size(); i += 3) sum += counts->rgb[i];
  // The last pass of the adaptive run: its mean spp times the pixels is the image's sum.
  const auto rows = ReadCsv(dir / "out" / "converge.csv");
  double mean_spp = -1;
  for (const auto& r : rows)
    if (r.at("variant") == "adaptive=8:0.05") mean_spp = std::stod(r.at("mean_spp"));
  EXPECT_NEAR(sum, mean_spp * 32 * 32, 1e-3 * sum);
  EXPECT_LT(mean_spp, 64.0);
  // Without adaptive sampling every pixel takes every sample.
  EXPECT_EQ(rows.back().at("variant"), "adaptive=off");
  EXPECT_EQ(rows.back().at("mean_spp"), "64");
}

TEST(ConvergeCli, BadArgumentsAreClearErrorsWithExitTwo) {
  const fs::path dir = test_util::TempDir("converge/bad");
  const fs::path scene = SmallCbox(dir, 16, "direct_mis");
  Image other(17, 16), nan_ref(16, 16);
  nan_ref.rgb[3 * (16 * 2 + 5)] = std::nanf("");
  ASSERT_TRUE(WriteExr((dir / "other.exr").string(), other, {}).ok());
  ASSERT_TRUE(WriteExr((dir / "nan.exr").string(), nan_ref, {}).ok());
  struct Case {
    std::string args, says;
  };
  const std::string out = " -o " + (dir / "out").string();
  for (const Case& c :
       {Case{"--ref auto --variant integrater=path_mis", "unknown key 'integrater'"},
        Case{"--ref auto --variant maxDepth=deep", "'deep' is not an integer in [-1, 1048576]"},
        Case{"--ref auto --variant adaptive=1:0.05", "'1:0.05' is not BATCH:TOLERANCE"},
        Case{"--ref " + (dir / "other.exr").string(), "is 17x16 but the scene renders 16x16"},
        Case{"--ref " + (dir / "nan.exr").string(), "NaN/Inf value at pixel 5,2"},
        Case{"--ref auto --ref auto", "give one reference per scene"},
        Case{"--ref " + (dir / "missing.exr").string(), "missing.exr"}}) {
    const int rc = RunShell(kPtlab + " converge " + scene.string() + " " + c.args + out, dir / "log");
    const std::string log = ReadFile(dir / "log");
    EXPECT_EQ(rc, 2) << c.args << "\n" << log;
    EXPECT_NE(log.find(c.says), std::string::npos) << c.args << "\n" << log;
  }
}

// path_mis on a 16x16 Cornell box, eight seeds of 16 passes against a reference with 128 times
// the samples (its own error adds 1/128 of the last pass's relMSE: a slope bias of ~0.005). An unbiased estimator's relMSE
// falls as spp^-1: the mean of the eight fitted slopes must be -1 within three standard errors
// of that mean (the spread over seeds), and the two-halves estimate within 1.5x of the measured relMSE.
TEST(StatConverge, PathMisSlopeIsMinusOneAndTheEstimateTracksTheTruth) {
  const fs::path dir = test_util::TempDir("converge/stat");
  const fs::path scene = SmallCbox(dir, 16, "path_mis");
  ASSERT_EQ(RunShell(kPtlab + " render " + scene.string() + " --spp 32768 --seed 99 -q -o " +
                         (dir / "ref.exr").string(),
                     dir / "ref.log"),
            0)
      << ReadFile(dir / "ref.log");
  ASSERT_EQ(RunShell(kPtlab + " converge " + scene.string() + " --ref " +
                         (dir / "ref.exr").string() +
                         " --spp 256 --seeds 8 --seed 1 --no-plots -o " + (dir / "out").string(),
                     dir / "log"),
            0)
      << ReadFile(dir / "log");
  const auto rows = ReadCsv(dir / "out" / "converge.csv");
  ASSERT_EQ(rows.size(), 8u * 16u);
  std::map<std::string, std::vector<double>> spp, rel;
  std::vector<double> estimated, measured;  // at the last pass, per seed
  for (const auto& r : rows) {
    const std::string seed = r.at("seed");
    spp[seed].push_back(std::stod(r.at("spp")));
    rel[seed].push_back(std::stod(r.at("rel_mse")));
    if (r.at("spp") == "256") {
      estimated.push_back(std::stod(r.at("estimated_rel_mse")));
      measured.push_back(rel[seed].back());
    }
  }
  std::vector<double> slopes;
  for (const auto& [seed, x] : spp) slopes.push_back(FitLogLog(x, rel[seed]).slope);
  double mean = 0, var = 0;
  for (const double s : slopes) mean += s / double(slopes.size());
  for (const double s : slopes) var += (s - mean) * (s - mean) / double(slopes.size() - 1);
  const double stderr_mean = std::sqrt(var / double(slopes.size()));
  EXPECT_LT(std::abs(mean + 1.0), 3 * stderr_mean + 1e-9)
      << "mean slope " << mean << " +- " << stderr_mean;
  EXPECT_LT(stderr_mean, 0.1) << "the spread is too wide for the test to mean anything";
  // Both are estimates of the expected relMSE; on 256 pixels one seed's relMSE is dominated by
  // a few bright paths (single seeds measured 0.65x to 2.6x), so compare the means over seeds.
  ASSERT_EQ(estimated.size(), 8u);
  double est_sum = 0, true_sum = 0;
  for (size_t i = 0; i < estimated.size(); ++i) est_sum += estimated[i], true_sum += measured[i];
  EXPECT_GT(est_sum / true_sum, 1 / 1.5);
  EXPECT_LT(est_sum / true_sum, 1.5);
}

}  // namespace
}  // namespace ptlab
