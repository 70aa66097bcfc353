// Tests of Mitsuba 3's Z test in tools/imgdiff: known z, the clamp, the Šidák level, the 99.75 %
// rule, XYZ conversion, noisy unbiased and biased images, and the `imgdiff --ztest` CLI.
#include "tools/imgdiff/ztest.h"

#include <gtest/gtest.h>

#include "tests/test_data.h"
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <string>

#include "engine/core/rng.h"
#include "engine/image/image_io.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;

// An image whose every pixel holds `xyz` once converted to XYZ (stored as RGB, as files are).
Image UniformFromXyz(int w, int h, Color3f xyz) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.Set(x, y, xyz);
  return XyzToRgb(img);
}

// Standard normal variates by Box–Muller from a fixed PCG32 stream.
class Normal {
 public:
  explicit Normal(uint64_t seed) : rng_(seed, 7) {}
  double Next() {
    const double u1 = (double(rng_.NextUint()) + 0.5) * 0x1p-32;
    const double u2 = double(rng_.NextUint()) * 0x1p-32;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

 private:
  Pcg32 rng_;
};

// Two-sided p of z, computed as 2 (1 - Φ(z)) with Φ from erf (not the erfc of the library).
double TwoSidedP(double z) { return 2.0 * (1.0 - 0.5 * (1.0 + std::erf(z / std::sqrt(2.0)))); }

TEST(ZTest, KnownZGivesKnownP) {
  // XYZ reference 0.5, image 0.5 + d, variance v, spp n: z = d sqrt(n / v).
  const int w = 8, h = 4;
  const Image ref = UniformFromXyz(w, h, {0.5f, 0.5f, 0.5f});
  const Image var = UniformFromXyz(w, h, {0.0025f, 0.01f, 0.04f});
  const Image img = UniformFromXyz(w, h, {0.51f, 0.48f, 0.53f});
  ZTestOptions o;
  o.spp = 100;
  const ZTestResult r = ZTest(img, ref, var, o);
  const double z[3] = {0.01 * std::sqrt(100 / 0.0025), 0.02 * std::sqrt(100 / 0.01),
                       0.03 * std::sqrt(100 / 0.04)};  // 2, 2, 1.5
  for (int c = 0; c < 3; ++c) {
    const double p = r.p_value.rgb[size_t(3 * (w + 1) + c)];
    EXPECT_NEAR(p, TwoSidedP(z[c]), 2e-4 * TwoSidedP(z[c])) << "channel " << c;
  }
  EXPECT_NEAR(r.p_value.rgb[0], 0.0455003, 1e-5);  // tables: P(|Z| > 2)
  EXPECT_TRUE(r.pass);
  EXPECT_EQ(r.channels, 3 * w * h);
  EXPECT_EQ(r.channels_passed, r.channels);
}

TEST(ZTest, VarianceIsClampedBelowAt1e4) {
  const int w = 4, h = 4;
  const Image ref = UniformFromXyz(w, h, {0.5f, 0.5f, 0.5f});
  const Image img = UniformFromXyz(w, h, {0.51f, 0.51f, 0.51f});
  ZTestOptions o;
  o.spp = 1;
  // Variances 0, 1e-8 and exactly 1e-4 all act as 1e-4: z = 0.01 / 0.01 = 1.
  const ZTestResult r = ZTest(img, ref, UniformFromXyz(w, h, {0.0f, 1e-8f, 1e-4f}), o);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.p_value.rgb[size_t(c)], TwoSidedP(1.0), 1e-4);
  // Above the floor it is used as is: variance 4e-4 gives z = 0.5.
  const ZTestResult r2 = ZTest(img, ref, UniformFromXyz(w, h, {4e-4f, 4e-4f, 4e-4f}), o);
  EXPECT_NEAR(r2.p_value.rgb[0], TwoSidedP(0.5), 1e-4);
  // A NaN variance (or mean) never passes.
  Image nan_var = UniformFromXyz(w, h, {1e-2f, 1e-2f, 1e-2f});
  nan_var.rgb[0] = std::numeric_limits<float>::quiet_NaN();
  const ZTestResult r3 = ZTest(img, ref, nan_var, o);
  EXPECT_TRUE(std::isnan(r3.p_value.rgb[0]));
  EXPECT_LT(r3.channels_passed, r3.channels);  // NaN R mixes into X, Y and Z
  EXPECT_EQ(r3.min_p, 0.0);
}

TEST(ZTest, SidakLevel) {
  for (const auto& [w, h] : {std::pair{48, 48}, std::pair{64, 64}, std::pair{1, 1}}) {
    const Image ref = UniformFromXyz(w, h, {0.5f, 0.5f, 0.5f});
    ZTestOptions o;
    o.spp = 16;
    const ZTestResult r = ZTest(ref, ref, ref, o);
    const long double expected = 1.0L - std::pow(0.99L, 1.0L / (long double)(w * h));
    EXPECT_NEAR(r.alpha, double(expected), 1e-12 * double(expected)) << w << "x" << h;
    EXPECT_EQ(r.min_p, 1.0);
    EXPECT_TRUE(r.pass);
  }
  // 64 x 64: 1 - 0.99^(1/4096) = 2.45372e-6 (by hand: ln(0.99) / 4096 = -2.45373e-6).
  const Image ref = UniformFromXyz(64, 64, {0.5f, 0.5f, 0.5f});
  ZTestOptions o;
  o.spp = 16;
  EXPECT_NEAR(ZTest(ref, ref, ref, o).alpha, 2.45372e-6, 1e-10);
}

TEST(ZTest, ChannelsJustAboveAndBelowAlphaAndThe99_75Rule) {
  // 40 x 40 pixels = 4800 channels: 0.25 % = 12 may fail.
  const int w = 40, h = 40;
  const Image ref = UniformFromXyz(w, h, {0.5f, 0.5f, 0.5f});
  const Image var = UniformFromXyz(w, h, {1.0f, 1.0f, 1.0f});
  ZTestOptions o;
  o.spp = 1;
  const double alpha = double(1.0L - std::pow(0.99L, 1.0L / 1600.0L));
  // z with p = q alpha, by bisection on the erf-based p.
  const auto z_for_p = [](double p) {
    double lo = 0, hi = 40;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
    }
    return lo;
  };
  for (int failing : {12, 13}) {
    Image xyz(w, h);
    for (float& v : xyz.rgb) v = 0.5f;
    // The first `failing` pixels fail in X only (p = 0.9 alpha); the next one passes narrowly
    // in X (p = 1.1 alpha).
    for (int k = 0; k < failing; ++k) xyz.rgb[size_t(3 * k)] += float(z_for_p(0.9 * alpha));
    xyz.rgb[size_t(3 * failing)] += float(z_for_p(1.1 * alpha));
    const ZTestResult r = ZTest(XyzToRgb(xyz), ref, var, o);
    EXPECT_EQ(r.channels - r.channels_passed, failing);
    EXPECT_EQ(r.pass, failing <= 12) << failing;
    EXPECT_EQ(r.failed_pixels.rgb[0], 1.0f);
    EXPECT_NEAR(r.failed_pixels.rgb[1], 0.02f * XyzToRgb(xyz).rgb[1], 1e-6f);
    EXPECT_EQ(r.min_p_channel, 0);
  }
}

TEST(ZTest, XyzConversionMatchesPrimariesAndWhitePoint) {
  // Independently: the RGB -> XYZ matrix of Rec. 709 primaries and white D65 (x, y chromaticities
  // 0.64/0.33, 0.30/0.60, 0.15/0.06, white 0.3127/0.3290), columns scaled so that RGB (1,1,1) is
  // the white of luminance Y = 1.
  const double px[3] = {0.64, 0.30, 0.15}, py[3] = {0.33, 0.60, 0.06};
  const double wx = 0.3127, wy = 0.3290;
  double p[3][3];  // columns: XYZ of each primary with Y = 1
  for (int c = 0; c < 3; ++c) {
    p[0][c] = px[c] / py[c];
    p[1][c] = 1.0;
    p[2][c] = (1.0 - px[c] - py[c]) / py[c];
  }
  const double white[3] = {wx / wy, 1.0, (1.0 - wx - wy) / wy};
  // Solve p s = white by Cramer's rule.
  const auto det = [](const double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double d = det(p);
  double s[3];
  for (int c = 0; c < 3; ++c) {
    double m[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = j == c ? white[i] : p[i][j];
    s[c] = det(m) / d;
  }
  // Within 5e-4: Mitsuba's 6-digit matrix implies the white (0.312727, 0.329033) (its row sums
  // 0.950456, 1, 1.088754), not exactly 0.3127/0.3290; a transposed matrix or other primaries
  // would be off by more than 0.1.
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(kRgbToXyz[i][j], p[i][j] * s[j], 5e-4) << i << j;
  // The images: a pixel goes through the matrix, and back.
  Image img(2, 1);
  img.Set(0, 0, {1.0f, 1.0f, 1.0f});
  img.Set(1, 0, {0.25f, 2.0f, 0.5f});
  const Image xyz = RgbToXyz(img);
  EXPECT_NEAR(xyz.rgb[0], 0.950456, 1e-6);
  EXPECT_NEAR(xyz.rgb[1], 1.0, 1e-6);
  EXPECT_NEAR(xyz.rgb[2], 1.088754, 1e-6);
  EXPECT_NEAR(xyz.rgb[4], 0.212671 * 0.25 + 0.715160 * 2.0 + 0.072169 * 0.5, 1e-6);
  const Image back = XyzToRgb(xyz);
  for (size_t i = 0; i < img.rgb.size(); ++i) EXPECT_NEAR(back.rgb[i], img.rgb[i], 1e-5);
}

// Mitsuba's _var.exr holds an XYZ variance stored through the XYZ->RGB matrix: read as RGB it
// has negative values, converted back to XYZ (as ZTest does) none (floating_sphere's reference).
TEST(ZTest, MitsubaVarianceFilesAreXyzVariances) {
  const std::string path = ptlab::test_data::Path("mitsuba3/tests/scenes/floating_sphere/refs/test_directional_ref_rgb_var.exr");
  PTLAB_REQUIRE_DATA(path);
  const StatusOr<Image> var = ReadImage(path);
  ASSERT_TRUE(var.ok()) << var.status().message();
  int negative_rgb = 0, negative_xyz = 0;
  for (float v : var->rgb) negative_rgb += v < 0;
  for (float v : RgbToXyz(*var).rgb) negative_xyz += v < -1e-6f;
  EXPECT_GT(negative_rgb, 100);  // 146
  EXPECT_EQ(negative_xyz, 0);
}

// A mean of spp samples per pixel channel with per-sample standard deviation sigma (in XYZ),
// drawn from the normal the CLT gives, around `truth` times `scale`.
Image NoisyMean(const Image& truth_xyz, double sigma, uint32_t spp, double scale, uint64_t seed) {
  Normal normal(seed);
  Image xyz = truth_xyz;
  for (float& v : xyz.rgb) v = float(scale * v + sigma / std::sqrt(double(spp)) * normal.Next());
  return XyzToRgb(xyz);
}

TEST(ZTest, UnbiasedNoisyImagePassesAndBiasedFails) {
  const int w = 64, h = 64;
  Image truth(w, h);
  Pcg32 rng(3, 1);
  for (float& v : truth.rgb) v = 0.2f + 0.8f * rng.NextFloat();
  const Image ref = XyzToRgb(truth);
  const double sigma = 0.5;
  const Image var = UniformFromXyz(w, h, {0.25f, 0.25f, 0.25f});
  ZTestOptions o;
  o.spp = 1024;
  // Unbiased: every channel is N(0, 1) in z; with alpha = 2.45e-6 none is expected to fail.
  const ZTestResult good = ZTest(NoisyMean(truth, sigma, o.spp, 1.0, 42), ref, var, o);
  EXPECT_TRUE(good.pass) << FormatZTestTable(good);
  EXPECT_GE(good.pass_share, 0.9995);
  EXPECT_GT(good.min_p, 1e-7);
  // Biased by 10 %: z shifts by 0.1 · 0.6 / (0.5 / 32) ≈ 3.8 on average: far more than 0.25 %.
  const ZTestResult bad = ZTest(NoisyMean(truth, sigma, o.spp, 1.1, 42), ref, var, o);
  EXPECT_FALSE(bad.pass) << FormatZTestTable(bad);
  EXPECT_LT(bad.pass_share, 0.9);
  // Half the samples' variance claimed: the same unbiased image still passes at this size,
  // but a 4x smaller claimed variance (z doubled) fails.
  const ZTestResult tight = ZTest(NoisyMean(truth, sigma, o.spp, 1.0, 42), ref,
                                  UniformFromXyz(w, h, {0.0625f, 0.0625f, 0.0625f}), o);
  EXPECT_FALSE(tight.pass) << FormatZTestTable(tight);
}

// --- imgdiff --ztest ---

class ImgdiffZTestCli : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(kBinary)) << kBinary << " is missing: build the imgdiff target";
    dir_ = fs::path(::testing::TempDir()) /
           ("ptlab_imgdiff_ztest_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  int Run(std::initializer_list<std::string> args) {
    std::string cmd(1, '\'');
    cmd.append(kBinary).append("'");
    for (const std::string& a : args) cmd.append(" '").append(a).append("'");
    cmd.append(" > '").append(Path("out.txt")).append("' 2>&1");
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string Output() const {
    std::ifstream in(Path("out.txt"));
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  static constexpr const char* kBinary = PTLAB_BINARY_DIR "/bin/imgdiff";
  fs::path dir_;
};

TEST_F(ImgdiffZTestCli, PassFailOutputsAndUsage) {
  const int w = 32, h = 32;
  Image truth(w, h);
  Pcg32 rng(5, 1);
  for (float& v : truth.rgb) v = 0.2f + 0.8f * rng.NextFloat();
  ASSERT_TRUE(WriteExr(Path("ref.exr"), XyzToRgb(truth)).ok());
  ASSERT_TRUE(WriteExr(Path("var.exr"), UniformFromXyz(w, h, {0.25f, 0.25f, 0.25f})).ok());
  ASSERT_TRUE(WriteExr(Path("good.exr"), NoisyMean(truth, 0.5, 1024, 1.0, 9)).ok());
  ASSERT_TRUE(WriteExr(Path("bad.exr"), NoisyMean(truth, 0.5, 1024, 1.2, 9)).ok());
  ASSERT_TRUE(WriteExr(Path("small.exr"), Image(16, 32)).ok());
  const std::string ref = Path("ref.exr"), var = Path("var.exr");
  EXPECT_EQ(Run({"--ztest", ref, var, Path("good.exr"), "--spp", "1024"}), 0) << Output();
  EXPECT_NE(Output().find("result: PASS"), std::string::npos) << Output();
  EXPECT_FALSE(fs::exists(Path("good_pvalue.exr")));
  EXPECT_FALSE(fs::exists(Path("good_failed.exr")));
  EXPECT_EQ(Run({"--ztest", ref, var, Path("bad.exr"), "--spp", "1024"}), 1) << Output();
  EXPECT_NE(Output().find("result: FAIL"), std::string::npos) << Output();
  StatusOr<Image> p = ReadImage(Path("bad_pvalue.exr"));
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_EQ(p->width, w);
  ASSERT_TRUE(ReadImage(Path("bad_failed.exr")).ok());
  EXPECT_EQ(Run({"--ztest", ref, var, Path("bad.exr"), "--spp", "1024", "--json", "--ztest-out",
                 Path("custom")}),
            1);
  EXPECT_EQ(Output().front(), '{') << Output();
  EXPECT_NE(Output().find("\"pass\": false}"), std::string::npos) << Output();
  EXPECT_TRUE(fs::exists(Path("custom_pvalue.exr")));
  // Exit codes of tools/common/exit_codes.h: another size is a failed verdict (1), bad usage or
  // an unreadable image is 2.
  EXPECT_EQ(Run({"--ztest", ref, var, Path("small.exr"), "--spp", "4"}), 1) << Output();
  EXPECT_EQ(Run({"--ztest", ref, var, Path("missing.exr"), "--spp", "4"}), 2) << Output();
  EXPECT_EQ(Run({"--ztest", ref, var, Path("good.exr")}), 2) << Output();  // no --spp
  EXPECT_EQ(Run({"--ztest", ref, var, Path("good.exr"), "--spp", "0"}), 2) << Output();
  EXPECT_EQ(Run({"--ztest", ref, var}), 2) << Output();
  EXPECT_EQ(Run({ref, "--ztest", ref, var, Path("good.exr"), "--spp", "4"}), 2) << Output();
  // The p-value image may not replace an input.
  fs::copy_file(Path("bad.exr"), Path("x_pvalue.exr"));
  EXPECT_EQ(Run({"--ztest", ref, var, Path("x_pvalue.exr"), "--spp", "1024", "--ztest-out",
                 Path("x")}),
            2)
      << Output();
  EXPECT_FALSE(fs::exists(Path("x_failed.exr")));
  // An unwritable output prefix is exit code 3.
  EXPECT_EQ(
      Run({"--ztest", ref, var, Path("bad.exr"), "--spp", "1024", "--ztest-out", Path("no/dir/x")}),
      3);
}

}  // namespace
}  // namespace ptlab
