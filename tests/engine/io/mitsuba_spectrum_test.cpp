// Spectra to RGB as Mitsuba's rgb variant converts them, .spd files, named IORs, and named
// conductors checked against an independent integration (an analytic CIE fit, another rule).
#include "engine/io/mitsuba_spectrum.h"

#include <gtest/gtest.h>

#include "tests/test_data.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "engine/io/mitsuba_loader.h"

namespace ptlab {
namespace {

const std::string kIorDir = ptlab::test_data::Path("mitsuba3/ior/");

TEST(MitsubaSpectrum, NamedIors) {
  float ior = 0;
  ASSERT_TRUE(LookupNamedIor("bk7", &ior));
  EXPECT_FLOAT_EQ(ior, 1.5046f);
  ASSERT_TRUE(LookupNamedIor("Air", &ior));  // case-insensitive, as Mitsuba
  EXPECT_FLOAT_EQ(ior, 1.000277f);
  ASSERT_TRUE(LookupNamedIor("water", &ior));
  EXPECT_FLOAT_EQ(ior, 1.333f);
  ASSERT_TRUE(LookupNamedIor("diamond", &ior));
  EXPECT_FLOAT_EQ(ior, 2.419f);
  EXPECT_FALSE(LookupNamedIor("unobtainium", &ior));
  EXPECT_NE(NamedIorList().find("fused quartz"), std::string::npos);
}

// A flat spectrum over the whole CIE range: as emission it has Y = 1 (the normalisation), so
// its sRGB is the row sums of the XYZ -> sRGB matrix; as a reflectance (D65-weighted) it is
// grey, within the 0.11 % that Mitsuba's D65 constant differs from this quadrature's.
TEST(MitsubaSpectrum, FlatSpectra) {
  const std::vector<double> w = {360, 830}, one = {1, 1};
  const Color3f e = SpectrumToRgb(w, one, SpectrumUse::kEmission);
  EXPECT_NEAR(e.r, 3.240479 - 1.537150 - 0.498535, 2e-3);
  EXPECT_NEAR(e.g, -0.969256 + 1.875991 + 0.041556, 2e-3);
  EXPECT_NEAR(e.b, 0.055648 - 0.204043 + 1.057311, 2e-3);
  const Color3f r = SpectrumToRgb(w, {0.5, 0.5}, SpectrumUse::kReflectance);
  for (const float c : {r.r, r.g, r.b}) EXPECT_NEAR(c, 0.5, 0.5 * 0.01);
  // Reflectances are clamped to [0, 1], emission only below.
  const Color3f big = SpectrumToRgb(w, {3, 3}, SpectrumUse::kReflectance);
  EXPECT_EQ(big.r, 1.0f);
  const Color3f red = SpectrumToRgb({600, 700}, {1, 1}, SpectrumUse::kEmission);
  EXPECT_GT(red.r, 0.0f);
  EXPECT_EQ(red.b, 0.0f);  // negative blue clamped to 0
}

// Wyman, Sloan & Shirley (2013)'s multi-lobe Gaussian fit of the CIE 1931 observer, integrated
// with a 0.5 nm rectangle rule: an independent route to the same numbers (the fit is within a
// few per cent of the tabulated observer).
double Lobe(double l, double mu, double s1, double s2) {
  const double t = (l - mu) / (l < mu ? s1 : s2);
  return std::exp(-0.5 * t * t);
}
Color3f IndependentRgb(const std::vector<double>& w, const std::vector<double>& v) {
  double X = 0, Y = 0, Z = 0, norm = 0;
  for (double l = 360; l <= 830; l += 0.5) {
    const double x = 1.056 * Lobe(l, 599.8, 37.9, 31.0) + 0.362 * Lobe(l, 442.0, 16.0, 26.7) -
                     0.065 * Lobe(l, 501.1, 20.4, 26.2);
    const double y = 0.821 * Lobe(l, 568.8, 46.9, 40.5) + 0.286 * Lobe(l, 530.9, 16.3, 31.1);
    const double z = 1.217 * Lobe(l, 437.0, 11.8, 36.0) + 0.681 * Lobe(l, 459.0, 26.0, 13.8);
    norm += y;
    if (l < w.front() || l > w.back()) continue;
    size_t i = 0;
    while (i + 2 < w.size() && w[i + 1] < l) ++i;
    const double s = v[i] + (v[i + 1] - v[i]) * (l - w[i]) / (w[i + 1] - w[i]);
    X += x * s, Y += y * s, Z += z * s;
  }
  X /= norm, Y /= norm, Z /= norm;
  return {float(3.240479 * X - 1.537150 * Y - 0.498535 * Z),
          float(-0.969256 * X + 1.875991 * Y + 0.041556 * Z),
          float(0.055648 * X - 0.204043 * Y + 1.057311 * Z)};
}

void ExpectClose(const Color3f& a, const Color3f& b, double rel, const std::string& what) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(a[c], b[c], rel * std::fabs(b[c])) << what << " channel " << c;
}

class MitsubaConductor : public ::testing::TestWithParam<const char*> {};

// η and k of gold and copper through LookupMitsubaConductor (the loader's path: .spd files
// found beside a search path) against the independent integration, within 3 %.
TEST_P(MitsubaConductor, MatchesIndependentIntegration) {
  const std::string name = GetParam();
  PTLAB_REQUIRE_DATA(kIorDir + name + ".eta.spd");
  Color3f eta, k;
  // The ior/ folder is found from the parent of a search path (common/ beside ior/).
  const std::string common = ptlab::test_data::Path("mitsuba3/common");
  const Status s = LookupMitsubaConductor({common}, name, &eta, &k);
  ASSERT_TRUE(s.ok()) << s.message();
  std::vector<double> w, v;
  ASSERT_TRUE(ReadSpdFile(kIorDir + name + ".eta.spd", &w, &v).ok());
  ExpectClose(eta, IndependentRgb(w, v), 0.03, name + " eta");
  ASSERT_TRUE(ReadSpdFile(kIorDir + name + ".k.spd", &w, &v).ok());
  ExpectClose(k, IndependentRgb(w, v), 0.03, name + " k");
  // Gold reflects red more than blue: η small in red, large in blue.
  if (name == "Au") {
    EXPECT_LT(eta.r, eta.b);
  }
}

INSTANTIATE_TEST_SUITE_P(Metals, MitsubaConductor, ::testing::Values("Au", "Cu"));

TEST(MitsubaSpectrum, ConductorErrors) {
  Color3f eta, k;
  EXPECT_FALSE(LookupMitsubaConductor({"/nonexistent"}, "Au", &eta, &k).ok());
  EXPECT_FALSE(LookupMitsubaConductor({"/tmp"}, "../etc/passwd", &eta, &k).ok());
  ASSERT_TRUE(LookupMitsubaConductor({}, "none", &eta, &k).ok());
  EXPECT_EQ(k.r, 1.0f);
}

TEST(MitsubaSpectrum, SpdFileErrorsNameTheLine) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "ptlab_mitsuba_bad.spd").string();
  std::ofstream(path) << "# comment\n400 1.0\n500 x\n";
  std::vector<double> w, v;
  const Status s = ReadSpdFile(path, &w, &v);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find(path + ":3:"), std::string::npos) << s.message();
  std::ofstream(path) << "500 1\n400 2\n";
  const Status order = ReadSpdFile(path, &w, &v);
  ASSERT_FALSE(order.ok());
  EXPECT_NE(order.message().find(":2: wavelengths must increase"), std::string::npos);
  std::ofstream(path) << "400 1 # trailing comment\n\n700 2\n";
  ASSERT_TRUE(ReadSpdFile(path, &w, &v).ok());
  EXPECT_EQ(w.size(), 2u);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace ptlab
