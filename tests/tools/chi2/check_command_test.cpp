// `chi2 check` as a user runs it: same χ² as the C++ route, exit 2 on bad input.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "ptlab/chi2.h"
#include "tests/tools/command_test_util.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;
using test_util::ReadFile;
using test_util::RunShell;
using test_util::TempDir;

constexpr const char* kChi2 = PTLAB_BINARY_DIR "/bin/chi2";
constexpr const char* kPdfProgram =
    "/usr/bin/python3 " PTLAB_SOURCE_DIR "/examples/chi2_cli/power_cosine_pdf.py";
constexpr float kPiF = 3.14159265f;

chi2::Point SamplePowerCosine(float u0, float u1, float n) {
  const float z = std::pow(u0, 1.0f / (n + 1.0f)), r = std::sqrt(std::fmax(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPiF * u1;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// docs/chi2.md's power-cosine subject whose sampler also records the points it returns.
chi2::Subject RecordingPowerCosine(std::vector<chi2::Point>* drawn) {
  chi2::Subject s;
  s.name = "power_cosine_n10";
  s.domain = chi2::Domain::Hemisphere();
  s.sample = [drawn](const float* u, int64_t n, int dims, chi2::Point* p) {
    for (int64_t i = 0; i < n; ++i)
      drawn->push_back(p[i] = SamplePowerCosine(u[i * dims], u[i * dims + 1], 10));
    return chi2::Status::Ok();
  };
  s.pdf = [](const chi2::Point* w, int64_t n, double* d) {
    for (int64_t i = 0; i < n; ++i)
      d[i] = w[i].z > 0 ? 11.0f / (2.0f * kPiF) * std::pow(w[i].z, 10.0f) : 0.0f;
    return chi2::Status::Ok();
  };
  return s;
}

void WriteRaw(const fs::path& path, const std::vector<chi2::Point>& points) {
  std::ofstream out(path, std::ios::binary);
  for (const chi2::Point& p : points) out.write(reinterpret_cast<const char*>(&p.x), 12);
}

// A number from chi2 check's --json output ("key": value).
double JsonNumber(const std::string& json, const std::string& key) {
  const size_t at = json.find("\"" + key + "\": ");
  if (at == std::string::npos) return std::nan("");
  return std::strtod(json.c_str() + at + key.size() + 4, nullptr);
}

// Same samples through the C++ route and the file route (raw float32, pdf from a Python
// program): same verdict, and χ² and p equal up to the pdfs' rounding (float vs double, ~1e-7).
TEST(StatChi2Check, SameResultAsTheCppRoute) {
  const fs::path dir = TempDir("chi2_check_same");
  std::vector<chi2::Point> drawn;
  chi2::Options o;
  o.samples = 200000;
  o.res = 25;
  chi2::Result r;
  ASSERT_TRUE(chi2::Test(RecordingPowerCosine(&drawn), o, &r).ok());
  ASSERT_EQ(drawn.size(), 200000u);
  WriteRaw(dir / "samples.f32", drawn);
  const std::string cmd = std::string(kChi2) + " check --domain hemisphere --dims 3 --samples " +
                          (dir / "samples.f32").string() + " --res 25 --json --pdf-cmd \"" +
                          kPdfProgram + "\"";
  ASSERT_EQ(RunShell(cmd, dir / "out.json"), 0) << ReadFile(dir / "out.json");
  const std::string json = ReadFile(dir / "out.json");
  EXPECT_NE(json.find("\"passed\": true"), std::string::npos) << json;
  EXPECT_TRUE(r.passed);
  EXPECT_NEAR(JsonNumber(json, "chi2"), r.chi2, 1e-5 * r.chi2) << json;
  EXPECT_NEAR(JsonNumber(json, "p_value"), r.p_value, 1e-5) << json;
  EXPECT_EQ(JsonNumber(json, "dof"), r.dof);
}

// docs/chi2.md's broken variants through the file route: a pdf program answering half the
// density, and one answering the n = 11 lobe, are both rejected (exit 1).
TEST(StatChi2Check, BrokenVariantsFail) {
  const fs::path dir = TempDir("chi2_check_broken");
  std::vector<chi2::Point> drawn;
  chi2::Options o;
  o.samples = 200000;
  o.res = 25;
  chi2::Result r;
  ASSERT_TRUE(chi2::Test(RecordingPowerCosine(&drawn), o, &r).ok());
  WriteRaw(dir / "samples.f32", drawn);
  for (const char* formula : {"0.5 * 11 / (2 * np.pi) * np.abs(w[:, 2]) ** 10",
                              "12 / (2 * np.pi) * np.abs(w[:, 2]) ** 11"}) {
    std::ofstream(dir / "pdf.py")
        << "import sys\nimport numpy as np\n"
           "w = np.array(sys.stdin.read().split(), dtype=np.float64).reshape(-1, 3)\n"
           "p = np.where(w[:, 2] > 0, "
        << formula << ", 0.0)\nsys.stdout.write(''.join(f'{v!r}\\n' for v in p.tolist()))\n";
    const std::string cmd = std::string(kChi2) + " check --domain hemisphere --dims 3 --samples " +
                            (dir / "samples.f32").string() +
                            " --res 25 --json --pdf-cmd \"/usr/bin/python3 " +
                            (dir / "pdf.py").string() + "\"";
    EXPECT_EQ(RunShell(cmd, dir / "out.json"), 1) << formula << "\n" << ReadFile(dir / "out.json");
    EXPECT_NE(ReadFile(dir / "out.json").find("\"passed\": false"), std::string::npos);
  }
}

// A pdf tabulated on a 3 x 513 grid of (phi, cos theta) passes; the wrong exponent fails.
TEST(StatChi2Check, PdfGrid) {
  const fs::path dir = TempDir("chi2_check_grid");
  std::vector<chi2::Point> drawn;
  chi2::Options o;
  o.samples = 200000;
  o.res = 25;
  chi2::Result r;
  ASSERT_TRUE(chi2::Test(RecordingPowerCosine(&drawn), o, &r).ok());
  WriteRaw(dir / "samples.f32", drawn);
  for (const double n : {10.0, 11.0}) {
    std::ofstream grid(dir / "grid.txt");
    grid << "# power cosine n=" << n << "\n3 513\n";
    char line[128];
    for (int j = 0; j < 513; ++j) {
      const double v = (n + 1) / (2 * M_PI) * std::pow(j / 512.0, n);
      std::snprintf(line, sizeof(line), "%.17g %.17g %.17g\n", v, v, v);
      grid << line;
    }
    grid.close();
    const std::string cmd = std::string(kChi2) + " check --domain hemisphere --dims 3 --samples " +
                            (dir / "samples.f32").string() + " --res 25 --pdf-grid " +
                            (dir / "grid.txt").string();
    EXPECT_EQ(RunShell(cmd, dir / "out.txt"), n == 10.0 ? 0 : 1) << ReadFile(dir / "out.txt");
  }
}

class Chi2CheckBadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = TempDir(std::string("chi2_check_bad_") +
                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::ofstream good(dir_ / "good.csv");
    good << "x,y,z\n";
    std::vector<chi2::Point> drawn;
    chi2::Options o;
    o.samples = 1000;
    o.res = 4;
    chi2::Result r;
    ASSERT_TRUE(chi2::Test(RecordingPowerCosine(&drawn), o, &r).ok());
    for (const chi2::Point& p : drawn) good << p.x << "," << p.y << "," << p.z << "\n";
  }

  // Runs chi2 check with these arguments; expects exit 2 and `message` in its output.
  void ExpectBadInput(const std::string& args, const std::string& message) {
    const std::string cmd = std::string(kChi2) + " check --res 4 " + args;
    const int rc = RunShell(cmd, dir_ / "log.txt");
    const std::string log = ReadFile(dir_ / "log.txt");
    EXPECT_EQ(rc, 2) << cmd << "\n" << log;
    EXPECT_NE(log.find(message), std::string::npos) << cmd << "\n" << log;
  }

  std::string Good() const {
    return "--domain hemisphere --samples " + (dir_ / "good.csv").string();
  }
  std::string Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }

  fs::path dir_;
};

TEST_F(Chi2CheckBadInput, SampleFiles) {
  const std::string pdf = " --pdf-cmd \"" + std::string(kPdfProgram) + "\"";
  ExpectBadInput("--domain hemisphere --samples " + Write("two.csv", "0.1,0.2\n") + pdf,
                 "two.csv:1: 2 numbers, expected 3 per line (x,y,z)");
  ExpectBadInput("--domain hemisphere --samples " + Write("nan.csv", "0,0,1\nnan,0,1\n") + pdf,
                 "nan.csv:2: the sample is not finite");
  ExpectBadInput("--domain hemisphere --samples " + Write("out.csv", "0,0,1\n0,0,-1\n") + pdf,
                 "out.csv:2: sample 1 is (0, 0, -1): outside the domain hemisphere");
  ExpectBadInput("--domain square --samples " + Write("far.csv", "x,y\n# c\n0.5,0.5\n\n2,0.5\n") + pdf,
                 "far.csv:5: sample 1 is (2, 0.5): outside the domain square");
  ExpectBadInput("--domain hemisphere --samples " + Write("empty.csv", "") + pdf,
                 "the sample file is empty");
  ExpectBadInput("--domain hemisphere --samples " + Write("header.csv", "x,y,z\n") + pdf,
                 "no samples in the file");
  ExpectBadInput("--domain hemisphere --samples " + Write("text.csv", "0,0,1\n0,zero,1\n") + pdf,
                 "text.csv:2: 'zero' is not a number");
  ExpectBadInput("--domain hemisphere --dims 3 --samples " + Write("odd.f32", "0123456789") + pdf,
                 "10 bytes is not a whole number of rows of 3 little-endian float32");
  ExpectBadInput("--domain hemisphere --dims 2 --samples " + Write("d2.f32", "01234567") + pdf,
                 "--dims 2 does not fit the hemisphere domain");
  ExpectBadInput("--domain hemisphere --samples " + (dir_ / "missing.csv").string() + pdf,
                 "missing.csv: cannot read the sample file: No such file or directory");
  ExpectBadInput("--domain cube --samples x.csv" + pdf, "unknown domain \"cube\"");
  ExpectBadInput("--domain box:0,0,0,1 --samples x.csv" + pdf, "x0 < x1");
  ExpectBadInput(Good(), "give the pdf as --pdf-cmd PROGRAM or --pdf-grid FILE");
}

TEST_F(Chi2CheckBadInput, PdfPrograms) {
  ExpectBadInput(Good() + " --pdf-cmd \"exit 3\"", "exited with status 3");
  ExpectBadInput(Good() + " --pdf-cmd \"kill -SEGV \\$\\$\"", "was killed by signal 11");
  ExpectBadInput(Good() + " --pdf-cmd \"cat > /dev/null; echo hello\"",
                 "printed 'hello' on line 1 of its output: expected one density");
  ExpectBadInput(Good() + " --pdf-cmd \"cat > /dev/null; echo 1\"", "printed 1 densities for");
  ExpectBadInput(Good() + " --pdf-cmd no_such_program_ptlab", "exited with status 127");
  const auto start = std::chrono::steady_clock::now();
  ExpectBadInput(Good() + " --pdf-timeout 1 --pdf-cmd \"sleep 30\"",
                 "points within 1 s (killed; --pdf-timeout sets the limit)");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(15));
  ExpectBadInput(Good() + " --pdf-grid " + Write("grid.txt", "3 2\n1 1 1\n1 -1 1\n"),
                 "grid.txt:3: density '-1' is out of range [0, 1e300]");
  ExpectBadInput(Good() + " --pdf-grid " + Write("short.txt", "3 2\n1 1 1\n"),
                 "3 densities, expected NX*NY = 6");
}

TEST_F(Chi2CheckBadInput, JsonCarriesTheError) {
  const int rc = RunShell(std::string(kChi2) + " check --json " + Good() + " --pdf-cmd \"exit 3\"",
                          dir_ / "log.txt");
  EXPECT_EQ(rc, 2);
  EXPECT_NE(ReadFile(dir_ / "log.txt").find("{\"error\": \"the pdf failed: the pdf program"),
            std::string::npos)
      << ReadFile(dir_ / "log.txt");
}

}  // namespace
}  // namespace ptlab
