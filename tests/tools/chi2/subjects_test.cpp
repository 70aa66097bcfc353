// Every registered subject of the chi-square lab behaves as registered: warps pass, broken fail.
#include "tools/chi2/subjects.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tools/chi2/chi2.h"
#include "tools/chi2/power.h"
#include "tools/chi2/report.h"

namespace ptlab {
namespace {

const Chi2Registry& Registry() {
  static const Chi2Registry registry = DefaultChi2Registry();
  return registry;
}

std::vector<std::string> Names(Chi2Expect expect) {
  std::vector<std::string> names;
  for (const Chi2Subject& s : Registry().subjects())
    if (s.expect == expect) names.push_back(s.name);
  return names;
}

std::string TestName(const ::testing::TestParamInfo<std::string>& info) {
  return Chi2FileStem(info.param);
}

class StatChi2Subject : public ::testing::TestWithParam<std::string> {};

// Default options (10^6 samples, 51x51 / 102x51 cells, fixed seed); Šidák over the whole
// registry, as `chi2 --all` runs it.
TEST_P(StatChi2Subject, BehavesAsRegistered) {
  const Chi2Subject* subject = Registry().Find(GetParam());
  ASSERT_NE(subject, nullptr);
  Chi2Options options;
  options.test_count = int(Registry().subjects().size());
  const Chi2Result result = RunChi2Test(*subject, options);
  if (!Chi2AsExpected(*subject, result)) {
    const std::string dir = PTLAB_BINARY_DIR "/chi2_failures";
    const Status written = WriteChi2Report(dir, result);
    ADD_FAILURE() << FormatChi2Result(*subject, result) << "\n  report: "
                  << (written.ok() ? dir + "/" + Chi2FileStem(result.name) + ".png"
                                   : written.message());
  }
  // The lab itself rejects an integral off by more than 1e-3. The analytic warps must do ten
  // times better; environment maps with a 1/sinθ pdf at the poles are only held to the lab's
  // bound, as Simpson integration does not resolve the spike closer than a few 1e-4.
  if (subject->expect == Chi2Expect::kPass && subject->name.rfind("warp/", 0) == 0) {
    EXPECT_NEAR(result.pdf_integral, subject->albedo, 1e-4);
  }
  // The lab's power target: every real subject catches a 2 % smooth error of its pdf (each shape
  // of Chi2SmoothPerturbations) with probability >= 95 % at its sample count (docs/chi2-power.md).
  if (subject->expect == Chi2Expect::kPass) {
    for (const Chi2Perturbation& p : Chi2SmoothPerturbations(result)) {
      EXPECT_GE(Chi2AnalyticPower(result, subject->defective(), options, p, 0.02), 0.95)
          << p.shape << ": " << FormatChi2Power(EstimateChi2Power(result, subject->defective(),
                                                                 options));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(StatChi2Warps, StatChi2Subject,
                         ::testing::ValuesIn(Names(Chi2Expect::kPass)), TestName);
INSTANTIATE_TEST_SUITE_P(StatChi2Broken, StatChi2Subject,
                         ::testing::ValuesIn(Names(Chi2Expect::kFail)), TestName);

TEST(Chi2Registry, HoldsEveryWarpAndBrokenVariant) {
  for (const char* name : {"warp/uniform_square", "warp/tent", "warp/uniform_disk",
                           "warp/concentric_disk", "warp/uniform_triangle", "warp/uniform_sphere",
                           "warp/uniform_hemisphere", "warp/cosine_hemisphere"}) {
    const Chi2Subject* s = Registry().Find(name);
    ASSERT_NE(s, nullptr) << name;
    EXPECT_EQ(s->expect, Chi2Expect::kPass) << name;
  }
  int broken = 0;
  for (const Chi2Subject& s : Registry().subjects()) {
    EXPECT_EQ(s.name.rfind("broken/", 0) == 0, s.expect == Chi2Expect::kFail) << s.name;
    broken += s.expect == Chi2Expect::kFail;
  }
  EXPECT_GE(broken, 4);
  EXPECT_EQ(Registry().Find("warp/no_such_warp"), nullptr);
}

TEST(Chi2Registry, RegistersLambdasInOneLine) {
  Chi2Registry registry;
  const float scale = 2.0f;  // a captured parameter
  registry.Add(PlanarWarpSubject(
      "test/scaled_square", Chi2Domain::Box(0, 0, 2, 2),
      [scale](const Vec2f& u) {
        return Vec2f{scale * u.x, scale * u.y};
      },
      [scale](const Vec2f&) { return 1.0f / (scale * scale); }));
  ASSERT_EQ(registry.subjects().size(), 1u);
  Chi2Point p;
  ASSERT_TRUE(registry.subjects()[0].sample(0.0f, {0.5f, 0.25f}, &p));
  EXPECT_EQ(p.x, 1.0f);
  EXPECT_EQ(p.y, 0.5f);
  EXPECT_EQ(registry.subjects()[0].pdf(p), 0.25);
}

}  // namespace
}  // namespace ptlab
