// Nori's statistical test files run as written; the Student t math; a wrong reference fails.
#include "tools/chi2/nori_tests.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "engine/core/rng.h"
#include "tests/test_data.h"
#include "tools/chi2/stats_math.h"

namespace ptlab {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// Incomplete beta and Student t

TEST(Chi2MathStudentTBeta, ClosedForms) {
  for (double x : {0.0, 1e-9, 0.1, 0.37, 0.5, 0.9, 1.0 - 1e-9, 1.0}) {
    SCOPED_TRACE(x);
    EXPECT_NEAR(RegularizedIncompleteBeta(1, 1, x), x, 1e-14);
    EXPECT_NEAR(RegularizedIncompleteBeta(3.5, 1, x), std::pow(x, 3.5), 1e-14);
    EXPECT_NEAR(RegularizedIncompleteBeta(1, 2.5, x), 1 - std::pow(1 - x, 2.5), 1e-14);
    // I_x(1/2, 1/2) = (2/π) asin(sqrt(x)) = 1 - (2/π) asin(sqrt(1 - x)): the arcsine law
    // (each form evaluated where asin is well conditioned).
    const double arcsine =
        x < 0.5 ? 2 / kPiD * std::asin(std::sqrt(x)) : 1 - 2 / kPiD * std::asin(std::sqrt(1 - x));
    EXPECT_NEAR(RegularizedIncompleteBeta(0.5, 0.5, x), arcsine, 1e-14);
  }
  for (double a : {0.5, 2.0, 17.0}) EXPECT_NEAR(RegularizedIncompleteBeta(a, a, 0.5), 0.5, 1e-13);
  // At Nori's 99999 dof the prefactor lgamma(a + b) - lgamma(a) - lgamma(b) cancels ~10^6-sized
  // terms: ~1e-10 relative is what double lgamma allows there.
  EXPECT_NEAR(RegularizedIncompleteBeta(5e4, 5e4, 0.5), 0.5, 1e-9);
}

TEST(Chi2MathStudentTBeta, BinomialTails) {
  // I_x(k, n - k + 1) = P[Binomial(n, x) >= k], summed term by term.
  for (int n : {4, 20, 200}) {
    for (double x : {0.05, 0.4, 0.93}) {
      for (int k = 1; k <= n; k += (n / 4 > 0 ? n / 4 : 1)) {
        double tail = 0;
        for (int j = k; j <= n; ++j)
          tail += std::exp(std::lgamma(n + 1.0) - std::lgamma(j + 1.0) - std::lgamma(n - j + 1.0) +
                           j * std::log(x) + (n - j) * std::log1p(-x));
        EXPECT_NEAR(RegularizedIncompleteBeta(k, n - k + 1, x), tail, 1e-12 + 1e-10 * tail)
            << "n=" << n << " x=" << x << " k=" << k;
      }
    }
  }
  EXPECT_NEAR(RegularizedIncompleteBeta(2, 3, 0.4), 0.5248, 1e-15);
}

TEST(Chi2MathStudentTBeta, SymmetryAndInvalidArguments) {
  for (double x : {0.01, 0.3, 0.77}) {
    EXPECT_NEAR(RegularizedIncompleteBeta(2.5, 7.0, x),
                1 - RegularizedIncompleteBeta(7.0, 2.5, 1 - x), 1e-14);
  }
  EXPECT_TRUE(std::isnan(RegularizedIncompleteBeta(0, 1, 0.5)));
  EXPECT_TRUE(std::isnan(RegularizedIncompleteBeta(1, -1, 0.5)));
  EXPECT_TRUE(std::isnan(RegularizedIncompleteBeta(1, 1, 1.5)));
  EXPECT_TRUE(std::isnan(RegularizedIncompleteBeta(1, 1, NAN)));
}

TEST(Chi2MathStudentT, CdfClosedFormsAndTables) {
  for (double t : {-30.0, -2.0, -0.3, 0.0, 0.7, 4.0, 1e3}) {
    SCOPED_TRACE(t);
    EXPECT_NEAR(StudentTCdf(t, 1), 0.5 + std::atan(t) / kPiD, 1e-14);             // Cauchy
    EXPECT_NEAR(StudentTCdf(t, 2), 0.5 + t / (2 * std::sqrt(2 + t * t)), 1e-14);  // ν = 2
  }
  // Two-tailed critical values of printed t tables (4-6 significant digits).
  EXPECT_NEAR(StudentTTwoTailedPValue(2.228139, 10), 0.05, 1e-7);
  EXPECT_NEAR(StudentTTwoTailedPValue(2.749996, 30), 0.01, 1e-8);
  EXPECT_NEAR(StudentTTwoTailedPValue(-3.169273, 10), 0.01, 1e-8);
  EXPECT_NEAR(StudentTTwoTailedPValue(63.65674, 1), 0.01, 1e-8);
  EXPECT_NEAR(StudentTCdf(1.812461, 10), 0.95, 1e-7);
  EXPECT_DOUBLE_EQ(StudentTTwoTailedPValue(0, 7), 1.0);
  EXPECT_EQ(StudentTTwoTailedPValue(INFINITY, 7), 0.0);
  EXPECT_TRUE(std::isnan(StudentTTwoTailedPValue(NAN, 7)));
  EXPECT_TRUE(std::isnan(StudentTTwoTailedPValue(1, 0)));
}

TEST(Chi2MathStudentT, LargeDofApproachesTheNormal) {
  // Nori's t-tests have 99999 dof. To first order in 1/ν the two-tailed p-value is the normal
  // one plus 2 φ(t) (t³ + t) / (4ν) (Abramowitz & Stegun 26.7.5); the rest is O(t⁸/ν²).
  const double nu = 99999;
  for (double t : {0.5, 1.959964, 3.290527, 5.0}) {
    const double phi = std::exp(-0.5 * t * t) / std::sqrt(2 * kPiD);
    const double expected = std::erfc(t / std::sqrt(2.0)) + 2 * phi * (t * t * t + t) / (4 * nu);
    EXPECT_NEAR(StudentTTwoTailedPValue(t, nu), expected, 1e-5 * expected) << t;
  }
  const double p = StudentTTwoTailedPValue(12.0, 99999);  // keeps its digits far in the tail
  const double normal = std::erfc(12.0 / std::sqrt(2.0));
  EXPECT_GT(p, normal);
  EXPECT_LT(p, 1.1 * normal);
}

TEST(Chi2MathStudentT, OneSampleTestAsNori) {
  // Nori: t = |mean − ref| sqrt(n / max(var, 1e-5)), dof n − 1, Šidák over the tests.
  TTestResult r = OneSampleTTest(0.52, 0.04, 10000, 0.5, 0.01, 5);
  EXPECT_NEAR(r.t, 0.02 / std::sqrt(0.04 / 10000), 1e-12);
  EXPECT_EQ(r.dof, 9999);
  EXPECT_NEAR(r.alpha, SidakAlpha(0.01, 5), 1e-18);
  EXPECT_NEAR(r.p_value, StudentTTwoTailedPValue(10.0, 9999), 1e-20);
  EXPECT_FALSE(r.pass);
  r = OneSampleTTest(0.4999, 0.04, 10000, 0.5, 0.01, 5);
  EXPECT_TRUE(r.pass);
  EXPECT_LT(r.t, 0);
  // A constant estimator (total internal reflection: always exactly 1).
  EXPECT_TRUE(OneSampleTTest(1.0, 0.0, 100000, 1.0, 0.01, 24).pass);
  r = OneSampleTTest(1.0, 0.0, 100000, 1.001, 0.01, 24);
  EXPECT_NEAR(r.t, -0.001 * std::sqrt(100000 / 1e-5), 1e-6);
  EXPECT_FALSE(r.pass);
  EXPECT_FALSE(OneSampleTTest(NAN, 0.1, 1000, 1.0, 0.01, 1).pass);
}

TEST(Chi2MathStudentT, WelchTest) {
  // s1 = 4/10, s2 = 9/15: t = 2 / sqrt(1), ν = 1 / (0.4²/9 + 0.6²/14).
  TTestResult r = WelchTTest(10, 4, 10, 8, 9, 15, 0.05, 1);
  EXPECT_NEAR(r.t, 2.0, 1e-14);
  EXPECT_NEAR(r.dof, 1.0 / (0.16 / 9 + 0.36 / 14), 1e-12);
  EXPECT_NEAR(r.p_value, StudentTTwoTailedPValue(2.0, r.dof), 1e-15);
  EXPECT_GT(r.p_value, 0.05);  // t_{0.975}(23) = 2.069
  EXPECT_LT(r.p_value, 0.06);
  EXPECT_TRUE(r.pass);
  EXPECT_NEAR(WelchTTest(8, 9, 15, 10, 4, 10, 0.05, 1).t, -2.0, 1e-14);
  EXPECT_TRUE(WelchTTest(3, 0, 5, 3, 0, 7, 0.01, 1).pass);
  EXPECT_FALSE(WelchTTest(3, 0, 5, 3.5, 0, 7, 0.01, 1).pass);
}

TEST(Chi2MathStudentT, RunningMomentsMergeInAnyChunking) {
  Pcg32 rng(3, 4);
  std::vector<double> x(1001);
  for (double& v : x) v = 5.0 + rng.NextFloat() * rng.NextFloat();
  RunningMoments all, merged, chunk;
  double sum = 0;
  for (double v : x) all.Add(v), sum += v;
  for (size_t i = 0; i < x.size(); ++i) {
    chunk.Add(x[i]);
    if (i % 97 == 96 || i + 1 == x.size()) merged.Merge(chunk), chunk = RunningMoments{};
  }
  const double mean = sum / double(x.size());
  double ss = 0;
  for (double v : x) ss += (v - mean) * (v - mean);
  EXPECT_EQ(all.n, 1001);
  EXPECT_EQ(merged.n, 1001);
  EXPECT_NEAR(all.mean, mean, 1e-13);
  EXPECT_NEAR(merged.mean, mean, 1e-13);
  EXPECT_NEAR(all.Variance(), ss / 1000, 1e-13);
  EXPECT_NEAR(merged.Variance(), ss / 1000, 1e-13);
}

// ---------------------------------------------------------------------------------------------
// The runner on small in-memory files

const std::string kMicrofacet =
    "<bsdf type=\"microfacet\"><float name=\"alpha\" value=\"0.1\"/>"
    "<float name=\"intIOR\" value=\"1.5\"/><float name=\"extIOR\" value=\"1.000277\"/>"
    "<color name=\"kd\" value=\"0.1, 0.2, 0.15\"/></bsdf>";

NoriTestReport RunString(const std::string& xml, const NoriTestOptions& options = {}) {
  StatusOr<NoriTestFile> file = LoadNoriTestFileFromString(xml, "", "mem.xml");
  EXPECT_TRUE(file.ok()) << file.status().message();
  if (!file.ok()) return {};
  return RunNoriTestFile(*file, options);
}

TEST(NoriTestRunner, DiffuseAlbedoIsTheLuminanceOfItsColor) {
  // Cosine sampling gives every sample the weight albedo: a constant estimator. Nori averages
  // luminance (0.212671 r + 0.715160 g + 0.072169 b), not the channel mean.
  const std::string bsdf =
      "<bsdf type=\"diffuse\"><color name=\"albedo\" value=\"0.2, 0.6, 0.9\"/>"
      "</bsdf>";
  const double luminance = 0.212671 * 0.2 + 0.715160 * 0.6 + 0.072169 * 0.9;
  char refs[64];
  std::snprintf(refs, sizeof refs, "%.7f, %.7f", luminance, luminance);
  NoriTestReport r = RunString(
      "<test type=\"ttest\"><string name=\"angles\" value=\"0, 70\"/>"
      "<string name=\"references\" value=\"" +
      std::string(refs) + "\"/>" + bsdf + "</test>");
  ASSERT_EQ(r.cases.size(), 2u);
  for (const NoriTestCase& c : r.cases) {
    EXPECT_EQ(c.verdict, NoriVerdict::kPass) << FormatNoriTestCase(c, true);
    EXPECT_NEAR(c.estimate, luminance, 1e-6);
    EXPECT_EQ(c.samples, 100000);
  }
  // The channel mean (0.5667) is rejected.
  r = RunString(
      "<test type=\"ttest\"><string name=\"angles\" value=\"0\"/>"
      "<string name=\"references\" value=\"0.5666667\"/>" +
      bsdf + "</test>");
  ASSERT_EQ(r.cases.size(), 1u);
  EXPECT_EQ(r.cases[0].verdict, NoriVerdict::kFail);
}

TEST(NoriTestRunner, WrongMicrofacetReferenceFails) {
  // ttest-microfacet.xml's references with the 60° one off by 2 %: only that test fails.
  const NoriTestReport r = RunString(
      "<test type=\"ttest\"><string name=\"angles\" value=\"0, 45, 60, 80, 85\"/>"
      "<string name=\"references\" value=\"0.207067, 0.215733, 0.2528417, 0.430936, "
      "0.519016\"/>" +
      kMicrofacet + "</test>");
  ASSERT_EQ(r.cases.size(), 5u);
  EXPECT_EQ(r.test_count, 5);
  for (size_t i = 0; i < r.cases.size(); ++i)
    EXPECT_EQ(r.cases[i].verdict, i == 2 ? NoriVerdict::kFail : NoriVerdict::kPass)
        << FormatNoriTestCase(r.cases[i], true);
  EXPECT_EQ(r.Verdict(), NoriVerdict::kFail);
  EXPECT_NE(FormatNoriTestCase(r.cases[2]).find("FAIL"), std::string::npos);
}

TEST(NoriTestRunner, DielectricRadianceScaling) {
  // Leaving glass (η 1.5) at normal incidence: R + T (1.5)² ≈ 2.199 with Nori's radiance
  // scaling, exactly 1 without it.
  const std::string xml =
      "<test type=\"ttest\"><string name=\"angles\" value=\"180\"/>"
      "<string name=\"references\" value=\"2.19888\"/><bsdf type=\"dielectric\">"
      "<float name=\"intIOR\" value=\"1.5\"/><float name=\"extIOR\" value=\"1.000277\"/></bsdf>"
      "</test>";
  NoriTestOptions options;
  NoriTestReport r = RunString(xml, options);
  ASSERT_EQ(r.cases.size(), 1u);
  EXPECT_EQ(r.cases[0].verdict, NoriVerdict::kPass) << FormatNoriTestCase(r.cases[0], true);
  options.dielectric_scale_radiance = false;
  r = RunString(xml, options);
  ASSERT_EQ(r.cases.size(), 1u);
  EXPECT_EQ(r.cases[0].estimate, 1.0);
  EXPECT_EQ(r.cases[0].verdict, NoriVerdict::kFail);
}

TEST(NoriTestRunner, ChiSquareOfDiffuseAndSkippedDeltaBsdf) {
  NoriTestOptions options;
  options.sample_count_override = 200000;
  const NoriTestReport r = RunString(
      "<test type=\"chi2test\"><integer name=\"testCount\" value=\"2\"/>"
      "<bsdf type=\"diffuse\"/><bsdf type=\"mirror\"/></test>",
      options);
  ASSERT_EQ(r.cases.size(), 4u);
  EXPECT_EQ(r.test_count, 4);
  EXPECT_EQ(r.cases[0].verdict, NoriVerdict::kPass) << FormatNoriTestCase(r.cases[0], true);
  EXPECT_EQ(r.cases[1].verdict, NoriVerdict::kPass) << FormatNoriTestCase(r.cases[1], true);
  EXPECT_EQ(r.cases[0].samples, 200000);
  EXPECT_NEAR(r.cases[0].alpha, SidakAlpha(0.01f, 4), 1e-15);  // Nori's float significance
  EXPECT_EQ(r.cases[2].verdict, NoriVerdict::kSkip);
  EXPECT_EQ(r.Verdict(), NoriVerdict::kSkip);
}

TEST(NoriTestRunner, ResultsDoNotDependOnThreads) {
  const std::string dir = test_data::Path("nori/epfl/scenes/pa5/tests");
  PTLAB_REQUIRE_DATA(dir + "/test-furnace.xml");
  StatusOr<NoriTestFile> file = LoadNoriTestFile(dir + "/test-furnace.xml");
  ASSERT_TRUE(file.ok()) << file.status().message();
  file->scenes.resize(1);
  file->properties.references.resize(1);
  NoriTestOptions options;
  options.sample_count_override = 10000;
  const NoriTestReport one = RunNoriTestFile(*file, options);
  options.threads = 3;
  const NoriTestReport three = RunNoriTestFile(*file, options);
  ASSERT_EQ(one.cases.size(), 1u);
  ASSERT_EQ(three.cases.size(), 1u);
  EXPECT_EQ(one.cases[0].estimate, three.cases[0].estimate);
  EXPECT_EQ(one.cases[0].variance, three.cases[0].variance);
}

// Writes `text` to a fresh file under the build directory and returns its path.
std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::string dir = PTLAB_BINARY_DIR "/nori_tests_tmp";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(NoriTestRunner, CommandExitStatus) {
  const std::string pass =
      WriteTemp("pass.xml",
                "<test type=\"ttest\"><string name=\"angles\" value=\"0\"/>"
                "<string name=\"references\" value=\"0.5\"/><bsdf type=\"diffuse\"/></test>");
  const std::string fail =
      WriteTemp("fail.xml",
                "<test type=\"ttest\"><string name=\"angles\" value=\"0\"/>"
                "<string name=\"references\" value=\"0.51\"/><bsdf type=\"diffuse\"/></test>");
  const std::string skip =
      WriteTemp("skip.xml",
                "<test type=\"ttest\"><string name=\"references\" value=\"1\"/><scene>"
                "<integrator type=\"direct_ems\"/><camera type=\"perspective\"/>"
                "<emitter type=\"spot\"/></scene></test>");
  const std::string bad = WriteTemp(
      "bad.xml", "<test type=\"ttest\"><string name=\"reference\" value=\"0.5\"/></test>");
  EXPECT_EQ(RunNoriTestCommand(pass, false), 0);
  EXPECT_EQ(RunNoriTestCommand(fail, true), 1);
  EXPECT_EQ(RunNoriTestCommand(skip, false), 4);  // tools/common/exit_codes.h: skipped
  EXPECT_EQ(RunNoriTestCommand(bad, false), 2);   // bad input
  EXPECT_EQ(RunNoriTestCommand(pass + ".missing", false), 2);
  const StatusOr<NoriTestReport> skipped = RunNoriTest(skip, {});
  ASSERT_TRUE(skipped.ok());
  EXPECT_NE(skipped->skip_reason.find("not supported yet"), std::string::npos);
  EXPECT_EQ(skipped->Verdict(), NoriVerdict::kSkip);
  EXPECT_FALSE(RunNoriTest(bad, {}).ok());
}

// ---------------------------------------------------------------------------------------------
// Nori's own files, at the files' sample counts

const char* const kNoriTestFiles[] = {
    "epfl/scenes/pa4/tests/test-mesh.xml",
    "epfl/scenes/pa4/tests/test-mesh-furnace.xml",
    "epfl/scenes/pa5/tests/chi2test-microfacet.xml",
    "epfl/scenes/pa5/tests/ttest-microfacet.xml",
    "epfl/scenes/pa5/tests/test-direct.xml",
    "epfl/scenes/pa5/tests/test-furnace.xml",
    "eth2015/scenes/pa3/tests/chi2test-microfacet.xml",
    "eth2015/scenes/pa3/tests/ttest-microfacet.xml",
    "eth2015/scenes/pa3/tests/test-mesh.xml",
    "eth2015/scenes/pa3/tests/test-mesh-furnace.xml",
    "eth2015/scenes/pa3/tests/test-distant.xml",
    "eth2015/scenes/pa4/tests/test-direct.xml",
    "eth2015/scenes/pa4/tests/test-furnace.xml",
    "eth-cg/scenes/pa3/tests/test-mesh-ems.xml",
    "eth-cg/scenes/pa3/tests/test-mesh-mats.xml",
    "eth-cg/scenes/pa3/tests/test-mesh-mis.xml",
    "eth-cg/scenes/pa3/tests/test-pointlight.xml",
    "eth-cg/scenes/pa4/tests/test-direct-mats.xml",
    "eth-cg/scenes/pa4/tests/test-direct-mis.xml",
    "eth-cg/scenes/pa4/tests/test-furnace-mats.xml",
    "eth-cg/scenes/pa4/tests/test-furnace-mis.xml",
    "eth-cg/scenes/pa4/tests/ttest-dielectric.xml",
};

std::string FileTestName(const ::testing::TestParamInfo<const char*>& info) {
  std::string name = info.param;
  const size_t scenes = name.find("/scenes/");
  if (scenes != std::string::npos) name.erase(scenes, 7);  // "epfl/pa5/tests/..."
  name.erase(name.size() - 4);                             // ".xml"
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

class StatNoriTests : public ::testing::TestWithParam<const char*> {};

// The file, as `ptlab test FILE.xml` runs it: every test at the file's sampleCount and
// significance (Šidák over the file's tests), fixed seed. Skipped when the data is absent or the
// file needs a feature that is not supported yet.
TEST_P(StatNoriTests, PassesAsWritten) {
  const std::string path = test_data::Path("nori/" + std::string(GetParam()));
  PTLAB_REQUIRE_DATA(path);
  NoriTestOptions options;
  options.threads = int(std::max(1u, std::thread::hardware_concurrency()));
  options.chi2_report_dir = PTLAB_BINARY_DIR "/chi2_failures";
  const StatusOr<NoriTestReport> report = RunNoriTest(path, options);
  ASSERT_TRUE(report.ok()) << report.status().message();
  if (!report->skip_reason.empty()) GTEST_SKIP() << report->skip_reason;
  ASSERT_EQ(int(report->cases.size()), report->test_count);
  std::string skipped;
  for (const NoriTestCase& c : report->cases) {
    if (c.verdict == NoriVerdict::kFail) ADD_FAILURE() << FormatNoriTestCase(c, true);
    if (c.verdict == NoriVerdict::kSkip) skipped += "\n" + FormatNoriTestCase(c, true);
  }
  if (!skipped.empty() && !HasFailure()) GTEST_SKIP() << "not supported yet:" << skipped;
}

INSTANTIATE_TEST_SUITE_P(Nori, StatNoriTests, ::testing::ValuesIn(kNoriTestFiles), FileTestName);

}  // namespace
}  // namespace ptlab
