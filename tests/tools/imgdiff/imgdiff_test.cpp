// Tests of tools/imgdiff: known-answer metrics, blocks, CheckParity, heat map, CLI exit codes.
#include "tools/imgdiff/imgdiff.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
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
constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();
constexpr float kInff = std::numeric_limits<float>::infinity();

// Values k/1024 in [lo, hi): exact in float, so offsets of 1/8 stay exact.
Image DyadicImage(int w, int h, float lo, float hi, uint64_t seed) {
  Pcg32 rng(seed, 3);
  Image img(w, h);
  for (float& v : img.rgb) v = std::floor((lo + (hi - lo) * rng.NextFloat()) * 1024.0f) / 1024.0f;
  return img;
}

// DyadicImage plus a left-to-right ramp of 0..2, so that a left-right mirror changes block means.
Image RampImage(int w, int h, uint64_t seed) {
  Image img = DyadicImage(w, h, 0.05f, 0.5f, seed);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const float ramp = float(x * 2048 / w) / 1024.0f;
      img.Set(x, y, img.At(x, y) + Color3f{ramp, ramp, ramp});
    }
  }
  return img;
}

Image Scaled(const Image& img, float s) {
  Image out = img;
  for (float& v : out.rgb) v *= s;
  return out;
}

// Multiplies the pixels of [x0, x1) x [y0, y1) by s.
void ScaleRect(Image* img, int x0, int y0, int x1, int y1, float s) {
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) img->Set(x, y, img->At(x, y) * s);
  }
}

TEST(ImgdiffMetrics, ConstantOffsetGivesKnownErrors) {
  const Image b = DyadicImage(48, 40, 0.25f, 1.0f, 1);
  Image a = b;
  for (float& v : a.rgb) v += 0.125f;
  const ImageDiff d = CompareImages(a, b, {});
  EXPECT_EQ(d.compared_pixels, 48 * 40);
  double rel = 0, max_b = 0, mean_b[3] = {0, 0, 0};
  for (size_t i = 0; i < b.rgb.size(); ++i) {
    rel += 0.015625 / (double(b.rgb[i]) * b.rgb[i] + 1e-2);
    max_b = std::max(max_b, double(b.rgb[i]));
    mean_b[i % 3] += b.rgb[i] / (48.0 * 40.0);
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_DOUBLE_EQ(d.mae[c], 0.125);
    EXPECT_DOUBLE_EQ(d.mse[c], 0.015625);
    EXPECT_DOUBLE_EQ(d.rmse[c], 0.125);
    EXPECT_NEAR(d.mean_b[c], mean_b[c], 1e-12);
    EXPECT_NEAR(d.mean_a[c], mean_b[c] + 0.125, 1e-12);
    EXPECT_NEAR(d.mean_rel_diff[c], 0.125 / mean_b[c], 1e-12);
  }
  EXPECT_DOUBLE_EQ(d.rmse_all, 0.125);
  EXPECT_DOUBLE_EQ(d.mae_all, 0.125);
  EXPECT_NEAR(d.rel_mse_all, rel / double(b.rgb.size()), 1e-12);
  EXPECT_DOUBLE_EQ(d.max_abs_error, 0.125);
  EXPECT_DOUBLE_EQ(d.psnr_peak, max_b);
  EXPECT_NEAR(d.psnr_db, 10 * std::log10(max_b * max_b / 0.015625), 1e-9);
  EXPECT_EQ(d.nonfinite_a.total(), 0);

  ImageDiffOptions ldr;
  ldr.psnr_peak = 1.0;
  EXPECT_NEAR(CompareImages(a, b, ldr).psnr_db, 10 * std::log10(1 / 0.015625), 1e-9);
}

TEST(ImgdiffMetrics, OffsetInOneChannel) {
  const Image b = DyadicImage(16, 16, 0.25f, 1.0f, 2);
  Image a = b;
  for (size_t i = 1; i < a.rgb.size(); i += 3) a.rgb[i] += 0.5f;
  const ImageDiff d = CompareImages(a, b, {});
  EXPECT_EQ(d.rmse[0], 0.0);
  EXPECT_DOUBLE_EQ(d.rmse[1], 0.5);
  EXPECT_EQ(d.rmse[2], 0.0);
  EXPECT_DOUBLE_EQ(d.rmse_all, 0.5 / std::sqrt(3.0));
  EXPECT_EQ(d.max_abs_channel, 1);
  EXPECT_EQ(d.mean_rel_diff[0], 0.0);
  EXPECT_GT(d.mean_rel_diff[1], 0.0);
  EXPECT_DOUBLE_EQ(d.max_abs_mean_rel, d.mean_rel_diff[1]);
}

TEST(ImgdiffMetrics, MaxAbsErrorIsLocated) {
  const Image b = DyadicImage(20, 10, 0.25f, 1.0f, 3);
  Image a = b;
  a.rgb[(3 * 20 + 5) * 3 + 2] += 0.75f;  // pixel (5, 3), channel B
  a.rgb[(7 * 20 + 1) * 3 + 0] -= 0.5f;
  const ImageDiff d = CompareImages(a, b, {});
  EXPECT_DOUBLE_EQ(d.max_abs_error, 0.75);
  EXPECT_EQ(d.max_abs_x, 5);
  EXPECT_EQ(d.max_abs_y, 3);
  EXPECT_EQ(d.max_abs_channel, 2);
}

TEST(ImgdiffMetrics, NonFinitePixelsAreCountedAndSkipped) {
  const Image b = DyadicImage(10, 10, 0.25f, 1.0f, 4);
  Image a = b;
  a.rgb[(2 * 10 + 3) * 3 + 1] = kNaNf;   // one NaN pixel
  a.rgb[(5 * 10 + 5) * 3 + 0] = kInff;   // one +Inf pixel
  a.rgb[(5 * 10 + 6) * 3 + 2] = -kInff;  // one -Inf pixel
  Image b2 = b;
  b2.rgb[0] = kNaNf;
  b2.rgb[3] = kNaNf;  // two NaN pixels in B
  const ImageDiff d = CompareImages(a, b2, {});
  EXPECT_EQ(d.nonfinite_a.nan_pixels, 1);
  EXPECT_EQ(d.nonfinite_a.inf_pixels, 2);
  EXPECT_EQ(d.nonfinite_b.nan_pixels, 2);
  EXPECT_EQ(d.nonfinite_b.inf_pixels, 0);
  EXPECT_EQ(d.compared_pixels, 100 - 5);
  EXPECT_EQ(d.rmse_all, 0.0);  // A equals B wherever both are finite
  EXPECT_TRUE(std::isfinite(d.mean_a[0]));
  const NonFiniteCounts n = CountNonFinite(a);
  EXPECT_EQ(n.nan_pixels, 1);
  EXPECT_EQ(n.inf_pixels, 2);
}

TEST(ImgdiffMetrics, FlipXMirrorsA) {
  const Image b = DyadicImage(9, 4, 0.0f, 1.0f, 5);
  const Image a = FlipX(b);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 9; ++x) {
      EXPECT_EQ(a.At(x, y).r, b.At(8 - x, y).r);
      EXPECT_EQ(a.At(x, y).b, b.At(8 - x, y).b);
    }
  }
  EXPECT_GT(CompareImages(a, b, {}).rmse_all, 0.1);
  ImageDiffOptions flip;
  flip.flip_x = true;
  const ImageDiff d = CompareImages(a, b, flip);
  EXPECT_EQ(d.rmse_all, 0.0);
  EXPECT_TRUE(d.flip_x);
  EXPECT_EQ(d.blocks.share, 1.0);
}

TEST(ImgdiffBlocks, ShareCountsBlocksWithinTolerance) {
  Image b(64, 64);
  for (float& v : b.rgb) v = 0.5f;
  Image a = b;
  ScaleRect(&a, 32, 0, 64, 32, 1.06f);  // block (1, 0): 6 % off
  ScaleRect(&a, 0, 32, 32, 64, 1.04f);  // block (0, 1): 4 % off, within 5 %
  const BlockComparison r = CompareBlocks(a, b, 32, 0.05, 0.01);
  EXPECT_EQ(r.blocks_x, 2);
  EXPECT_EQ(r.blocks_y, 2);
  EXPECT_EQ(r.eligible, 4);
  EXPECT_EQ(r.within, 3);
  EXPECT_DOUBLE_EQ(r.share, 0.75);
  EXPECT_EQ(r.worst_x, 32);
  EXPECT_EQ(r.worst_y, 0);
  EXPECT_NEAR(r.worst_rel, 0.06, 1e-6);
  EXPECT_EQ(CompareBlocks(a, b, 32, 0.07, 0.01).within, 4);
}

TEST(ImgdiffBlocks, FloorExcludesDarkBlocks) {
  Image b(64, 64);
  for (float& v : b.rgb) v = 0.5f;
  ScaleRect(&b, 0, 0, 32, 32, 0.01f);  // block mean 0.005 < 0.01
  Image a = b;
  ScaleRect(&a, 0, 0, 32, 32, 3.0f);
  const BlockComparison r = CompareBlocks(a, b, 32, 0.05, 0.01);
  EXPECT_EQ(r.eligible, 3);
  EXPECT_EQ(r.within, 3);
  EXPECT_EQ(r.share, 1.0);
  EXPECT_EQ(CompareBlocks(a, b, 32, 0.05, 0.001).within, 3);  // now eligible, and off
  EXPECT_EQ(CompareBlocks(a, b, 32, 0.05, 0.001).eligible, 4);
}

TEST(ImgdiffBlocks, PartialEdgeBlocksAreIncluded) {
  Image b(40, 40);
  for (float& v : b.rgb) v = 0.5f;
  Image a = b;
  ScaleRect(&a, 32, 0, 40, 40, 1.1f);  // only the right-hand partial blocks
  const BlockComparison r = CompareBlocks(a, b, 32, 0.05, 0.01);
  EXPECT_EQ(r.blocks_x, 2);
  EXPECT_EQ(r.blocks_y, 2);
  EXPECT_EQ(r.eligible, 4);
  EXPECT_EQ(r.within, 2);
}

TEST(ImgdiffBlocks, NonFiniteBlockInANeverPasses) {
  Image b(64, 32);
  for (float& v : b.rgb) v = 0.5f;
  Image a = b;
  a.rgb[0] = kNaNf;
  const BlockComparison r = CompareBlocks(a, b, 32, 0.05, 0.01);
  EXPECT_EQ(r.eligible, 2);
  EXPECT_EQ(r.within, 1);
  EXPECT_EQ(r.worst_x, 0);
}

TEST(ImgdiffParity, IdenticalImagesPass) {
  const Image ref = DyadicImage(96, 64, 0.05f, 1.5f, 6);
  const ParityResult p = CheckParity(ref, ref, 0.97, false);
  EXPECT_TRUE(p.pass) << p.summary;
  EXPECT_TRUE(p.means_ok && p.finite_ok && p.blocks_ok && p.size_ok);
  EXPECT_EQ(p.blocks.share, 1.0);
  EXPECT_EQ(p.blocks.eligible, 6);
  EXPECT_EQ(p.summary.rfind("PASS", 0), 0u) << p.summary;
}

TEST(ImgdiffParity, OnePercentMeanBiasFails) {
  // Integers around 100 keep every sum exact: reference mean 100, render mean 101, exactly 1 %.
  Image ref(64, 64);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const float v = 100.0f + float((x % 2 ? 1 : -1) * (y % 5));
      ref.Set(x, y, {v, v, v});
    }
  }
  Image render = ref;
  for (float& v : render.rgb) v += 1.0f;
  const ParityResult p = CheckParity(render, ref, 0.97, false);
  EXPECT_DOUBLE_EQ(p.mean_reference[0], 100.0);
  EXPECT_DOUBLE_EQ(p.mean_render[0], 101.0);
  EXPECT_FALSE(p.means_ok);
  EXPECT_TRUE(p.blocks_ok);  // every block is 1 % off, within 5 %
  EXPECT_FALSE(p.pass) << p.summary;
  EXPECT_EQ(p.summary.rfind("FAIL", 0), 0u) << p.summary;

  const Image noisy = DyadicImage(64, 64, 0.2f, 1.2f, 7);
  EXPECT_FALSE(CheckParity(Scaled(noisy, 1.012f), noisy, 0.97, false).pass);
  EXPECT_FALSE(CheckParity(Scaled(noisy, 0.988f), noisy, 0.97, false).pass);
  EXPECT_TRUE(CheckParity(Scaled(noisy, 1.008f), noisy, 0.97, false).pass);
}

TEST(ImgdiffParity, BlockOffBySixPercentLowersTheShare) {
  const Image ref = DyadicImage(128, 128, 0.5f, 1.5f, 8);
  Image render = ref;
  ScaleRect(&render, 32, 64, 64, 96, 1.06f);
  const ParityResult p = CheckParity(render, ref, 0.97, false);
  EXPECT_TRUE(p.means_ok);  // 6 % on 1/16 of the image shifts the mean by ~0.4 %
  EXPECT_TRUE(p.finite_ok);
  EXPECT_EQ(p.blocks.eligible, 16);
  EXPECT_EQ(p.blocks.within, 15);
  EXPECT_DOUBLE_EQ(p.blocks.share, 15.0 / 16.0);
  EXPECT_FALSE(p.blocks_ok);
  EXPECT_FALSE(p.pass);
  EXPECT_EQ(p.blocks.worst_x, 32);
  EXPECT_EQ(p.blocks.worst_y, 64);
  EXPECT_TRUE(CheckParity(render, ref, 0.93, false).pass);
}

TEST(ImgdiffParity, NaNOrInfFails) {
  const Image ref = DyadicImage(64, 64, 0.2f, 1.2f, 9);
  Image render = ref;
  render.rgb[100] = kNaNf;
  ParityResult p = CheckParity(render, ref, 0.5, false);
  EXPECT_FALSE(p.finite_ok);
  EXPECT_EQ(p.nonfinite_render.nan_pixels, 1);
  EXPECT_FALSE(p.pass) << p.summary;
  render.rgb[100] = kInff;
  p = CheckParity(render, ref, 0.5, false);
  EXPECT_EQ(p.nonfinite_render.inf_pixels, 1);
  EXPECT_FALSE(p.pass) << p.summary;
}

TEST(ImgdiffParity, SizeMismatchFails) {
  const ParityResult p = CheckParity(Image(32, 32), Image(32, 64), 0.5, false);
  EXPECT_FALSE(p.size_ok);
  EXPECT_FALSE(p.pass);
  EXPECT_NE(p.summary.find("32x32"), std::string::npos) << p.summary;
}

TEST(ImgdiffParity, FlipXForMirroredReferences) {
  const Image ref = RampImage(128, 64, 10);
  const Image mirrored = FlipX(ref);
  EXPECT_FALSE(CheckParity(mirrored, ref, 0.97, false).pass);
  const ParityResult p = CheckParity(mirrored, ref, 0.97, true);
  EXPECT_TRUE(p.pass) << p.summary;
  EXPECT_NE(p.summary.find("flip-x"), std::string::npos);
}

TEST(ImgdiffHeatmap, BlueWhiteRed) {
  Image b(3, 1);
  for (float& v : b.rgb) v = 1.0f;
  Image a = b;
  a.Set(0, 0, {0.0f, 0.0f, 0.0f});  // far below: blue
  a.Set(2, 0, {9.0f, 9.0f, 9.0f});  // far above: red
  const Image h = RelativeErrorHeatmap(a, b, 0.5);
  EXPECT_EQ(h.At(0, 0).r, 0.0f);
  EXPECT_EQ(h.At(0, 0).b, 1.0f);
  EXPECT_EQ(h.At(1, 0).r, 1.0f);
  EXPECT_EQ(h.At(1, 0).g, 1.0f);
  EXPECT_EQ(h.At(1, 0).b, 1.0f);
  EXPECT_EQ(h.At(2, 0).r, 1.0f);
  EXPECT_EQ(h.At(2, 0).g, 0.0f);
  a.rgb[4] = kNaNf;
  const Image g = RelativeErrorHeatmap(a, b, 0.5);
  EXPECT_EQ(g.At(1, 0).r, 0.0f);
  EXPECT_EQ(g.At(1, 0).g, 1.0f);
}

TEST(ImgdiffThresholds, EachThresholdCanFail) {
  const Image b = DyadicImage(64, 64, 0.25f, 1.0f, 11);
  Image a = b;
  for (float& v : a.rgb) v += 0.125f;
  const ImageDiff d = CompareImages(a, b, {});
  DiffThresholds t;
  EXPECT_TRUE(CheckThresholds(d, t).empty());
  t.rmse = 0.125;
  EXPECT_TRUE(CheckThresholds(d, t).empty());
  t.rmse = 0.124;
  EXPECT_EQ(CheckThresholds(d, t).size(), 1u);
  t = {};
  t.rel_mse = d.rel_mse_all * 0.99;
  EXPECT_EQ(CheckThresholds(d, t).size(), 1u);
  t = {};
  t.mean_rel = 0.01;
  EXPECT_EQ(CheckThresholds(d, t).size(), 1u);
  t = {};
  t.block_share = 0.5;  // every block is > 5 % off
  EXPECT_EQ(d.blocks.share, 0.0);
  EXPECT_EQ(CheckThresholds(d, t).size(), 1u);
  // NaN in A fails any threshold even if the metrics (which skip it) pass.
  Image n = b;
  n.rgb[5] = kNaNf;
  t = {};
  t.rmse = 1.0;
  EXPECT_EQ(CheckThresholds(CompareImages(n, b, {}), t).size(), 1u);
}

TEST(ImgdiffJson, HasTheFieldsAndNullForInfinity) {
  const Image b = DyadicImage(8, 8, 0.25f, 1.0f, 12);
  const ImageDiff d = CompareImages(b, b, {});
  const ParityResult p = CheckParity(b, b, 0.97, false);
  const std::string j = FormatDiffJson("a\"x.exr", "b.exr", d, &p, {});
  EXPECT_EQ(j.front(), '{');
  EXPECT_EQ(j.back(), '}');
  EXPECT_NE(j.find("\"a\": \"a\\\"x.exr\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"psnr_db\": null"), std::string::npos) << j;
  EXPECT_NE(j.find("\"rel_mse_epsilon\": 0.01"), std::string::npos) << j;
  EXPECT_NE(j.find("\"pass\": true}"), std::string::npos) << j;
  EXPECT_EQ(std::count(j.begin(), j.end(), '{'), std::count(j.begin(), j.end(), '}'));
}

// --- the imgdiff binary ---

class ImgdiffCli : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(kBinary)) << kBinary << " is missing: build the imgdiff target";
    dir_ = fs::path(::testing::TempDir()) /
           ("ptlab_imgdiff_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  // Runs imgdiff with `args` (each single-quoted for the shell); returns its exit code;
  // stdout and stderr go to Output().
  int Run(std::initializer_list<std::string> args) {
    std::string cmd = Quote(kBinary);
    for (const std::string& a : args) cmd.append(" ").append(Quote(a));
    cmd.append(" > ").append(Quote(Path("out.txt"))).append(" 2>&1");
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  static std::string Quote(const std::string& s) { return std::string("'").append(s).append("'"); }
  std::string Output() const {
    std::ifstream in(Path("out.txt"));
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  static constexpr const char* kBinary = PTLAB_BINARY_DIR "/bin/imgdiff";
  fs::path dir_;
};

TEST_F(ImgdiffCli, ExitCodes) {
  const Image ref_image = DyadicImage(64, 64, 0.2f, 1.2f, 13);
  ASSERT_TRUE(WriteExr(Path("ref.exr"), ref_image).ok());
  ASSERT_TRUE(WritePfm(Path("same.pfm"), ref_image).ok());
  ASSERT_TRUE(WriteExr(Path("biased.exr"), Scaled(ref_image, 1.02f)).ok());
  ASSERT_TRUE(WriteExr(Path("small.exr"), Image(32, 64)).ok());
  ASSERT_TRUE(WriteExr(Path("mirrored.exr"), FlipX(RampImage(64, 64, 15))).ok());
  ASSERT_TRUE(WriteExr(Path("ramp.exr"), RampImage(64, 64, 15)).ok());
  const std::string ref = Path("ref.exr"), same = Path("same.pfm"), biased = Path("biased.exr");
  EXPECT_EQ(Run({same, ref}), 0) << Output();
  EXPECT_NE(Output().find("result: PASS"), std::string::npos) << Output();
  EXPECT_EQ(Run({same, ref, "--parity", "0.97", "--fail-rmse", "0"}), 0) << Output();
  EXPECT_EQ(Run({biased, ref, "--parity", "0.97"}), 1) << Output();
  EXPECT_EQ(Run({biased, ref, "--fail-mean-rel", "0.01"}), 1) << Output();
  EXPECT_EQ(Run({biased, ref, "--fail-mean-rel", "0.03"}), 0) << Output();
  EXPECT_EQ(Run({biased, ref, "--fail-rmse", "0.001"}), 1) << Output();
  EXPECT_EQ(Run({biased, ref, "--fail-relmse", "1e-6"}), 1) << Output();
  EXPECT_EQ(Run({biased, ref, "--tol", "0.01", "--fail-block-share", "0.5"}), 1) << Output();
  EXPECT_EQ(Run({biased, ref, "--tol", "0.03", "--block", "16", "--fail-block-share", "0.99"}), 0)
      << Output();
  EXPECT_EQ(Run({Path("mirrored.exr"), Path("ramp.exr"), "--parity", "0.97"}), 1) << Output();
  EXPECT_EQ(Run({Path("mirrored.exr"), Path("ramp.exr"), "--parity", "0.97", "--flip-x"}), 0)
      << Output();
  EXPECT_EQ(Run({Path("small.exr"), ref}), 1) << Output();  // not the same image: a failure
  EXPECT_NE(Output().find("size mismatch"), std::string::npos) << Output();
  EXPECT_EQ(Run({Path("missing.exr"), ref}), 2) << Output();  // bad input
  EXPECT_NE(Output().find(Path("missing.exr")), std::string::npos) << Output();
  EXPECT_EQ(Run({same, ref, "--no-such-flag"}), 2) << Output();  // bad usage
  EXPECT_EQ(Run({same}), 2) << Output();
  EXPECT_EQ(Run({same, ref, "--block", "0"}), 2) << Output();
  EXPECT_EQ(Run({"--help"}), 0) << Output();
  EXPECT_NE(Output().find("1e-2"), std::string::npos) << Output();
  EXPECT_NE(Output().find("partial edge blocks are INCLUDED"), std::string::npos) << Output();
}

TEST_F(ImgdiffCli, JsonAndHeatmap) {
  const Image ref = DyadicImage(40, 24, 0.2f, 1.2f, 14);
  ASSERT_TRUE(WriteExr(Path("ref.exr"), ref).ok());
  ASSERT_TRUE(WriteExr(Path("biased.exr"), Scaled(ref, 1.02f)).ok());
  EXPECT_EQ(Run({Path("biased.exr"), Path("ref.exr"), "--json", "--parity", "0.9", "--heatmap",
                 Path("heat.png")}),
            1);
  const std::string out = Output();
  EXPECT_EQ(out.front(), '{') << out;
  EXPECT_NE(out.find("\"pass\": false}"), std::string::npos) << out;
  EXPECT_NE(out.find("\"means_ok\": false"), std::string::npos) << out;
  StatusOr<Image> heat = ReadImage(Path("heat.png"));
  ASSERT_TRUE(heat.ok()) << heat.status().message();
  EXPECT_EQ(heat->width, 40);
  EXPECT_EQ(heat->height, 24);
  EXPECT_EQ(heat->At(3, 3).r, 1.0f);  // A above B everywhere: red side
  EXPECT_LT(heat->At(3, 3).b, 1.0f);
  // A heat map whose folder is missing: the run cannot complete, exit code 3.
  EXPECT_EQ(Run({Path("ref.exr"), Path("ref.exr"), "--heatmap", Path("no/dir/heat.png")}), 3);
}

}  // namespace
}  // namespace ptlab
