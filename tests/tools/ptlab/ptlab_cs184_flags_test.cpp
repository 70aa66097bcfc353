// CS184's pathtracer flags on `ptlab render`: each value reaches the render (EXR header, image),
// each bad value is a clear error with exit code 2 (usage) or 1 (input), and nothing is written.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "engine/image/image_io.h"
#include "tests/test_data.h"
#include "tests/tools/command_test_util.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;
using test_util::ReadFile;
using test_util::RunShell;
using test_util::TempDir;

const std::string kPtlab = std::string(PTLAB_BINARY_DIR) + "/bin/ptlab";
const std::string kData = test_data::Dir();
const std::string kLambertian = kData + "cs184/dae/sky/CBspheres_lambertian.dae";
const std::string kUnlit = kData + "cs184/dae/sky/bunny_unlit.dae";
const std::string kVenice = kData + "envmaps/venice_sunset_1k.exr";

class PtlabCs184Flags : public ::testing::Test {
 protected:
  void SetUp() override {
    PTLAB_REQUIRE_DATA(kLambertian);
    PTLAB_REQUIRE_DATA(kUnlit);
    PTLAB_REQUIRE_DATA(kVenice);
    dir_ = TempDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
  }

  // Exit status of `ptlab render <args>` (a small, quiet render by default).
  int Render(const std::string& args) {
    return RunShell(kPtlab + " render " + args + " -q", dir_ / "log");
  }
  std::string Log() { return ReadFile(dir_ / "log"); }

  std::map<std::string, std::string> Header(const fs::path& exr) {
    std::map<std::string, std::string> h;
    auto attrs = ReadExrStringAttributes(exr.string());
    EXPECT_TRUE(attrs.ok()) << exr;
    if (attrs.ok())
      for (const auto& [k, v] : *attrs) h[k] = v;
    return h;
  }
  double Mean(const fs::path& exr) {
    StatusOr<Image> im = ReadImage(exr.string());
    EXPECT_TRUE(im.ok());
    if (!im.ok()) return -1;
    double sum = 0;
    for (float v : im->rgb) sum += v;
    return sum / double(im->rgb.size());
  }
  // A usage error: exit 2, the log names the flag, no output file.
  void ExpectUsageError(const std::string& args, const std::string& words) {
    SCOPED_TRACE(args);
    EXPECT_EQ(Render(args), 2) << Log();
    EXPECT_NE(Log().find(words), std::string::npos) << Log();
    EXPECT_FALSE(fs::exists(dir_ / "bad.exr"));
    EXPECT_FALSE(fs::exists(dir_ / "bad.png"));
  }
  std::string Out(const std::string& name) { return (dir_ / name).string(); }

  fs::path dir_;
};

// A .dae without flags gets CS184's estimator and defaults.
TEST_F(PtlabCs184Flags, DaeDefaults) {
  ASSERT_EQ(Render(kLambertian + " -r 16 12 -o " + Out("d.exr")), 0) << Log();
  auto h = Header(dir_ / "d.exr");
  EXPECT_EQ(h["ptlab:integrator"], "path_ems");
  EXPECT_EQ(h["ptlab:spp"], "1");
  EXPECT_EQ(h["ptlab:max_depth"], "1");
  EXPECT_EQ(h["ptlab:light_samples"], "1");
  EXPECT_EQ(h["ptlab:lens_radius"], "0.000000");
  EXPECT_EQ(h["ptlab:focal_distance"], "4.700000");
  EXPECT_EQ(h["ptlab:adaptive"], "off");
}

TEST_F(PtlabCs184Flags, SamplesAndThreads) {
  ASSERT_EQ(Render(kLambertian + " -r 16 12 -s 3 -t 1 -o " + Out("s.exr")), 0) << Log();
  auto h = Header(dir_ / "s.exr");
  EXPECT_EQ(h["ptlab:spp"], "3");
  EXPECT_EQ(h["ptlab:threads"], "1");
  ExpectUsageError(kLambertian + " -s 0 -o " + Out("bad.exr"), "-s");
  ExpectUsageError(kLambertian + " -s many -o " + Out("bad.exr"), "-s");
  ExpectUsageError(kLambertian + " -t 0 -o " + Out("bad.exr"), "-t");
}

TEST_F(PtlabCs184Flags, LightSamples) {
  ASSERT_EQ(Render(kLambertian + " -r 16 12 -l 3 -o " + Out("l.exr")), 0) << Log();
  EXPECT_EQ(Header(dir_ / "l.exr")["ptlab:light_samples"], "3");
  ExpectUsageError(kLambertian + " -l 0 -o " + Out("bad.exr"), "-l");
  ExpectUsageError(kLambertian + " -l 1.5 -o " + Out("bad.exr"), "-l");
}

// -m 0 is emitted light only (just the light seen directly), -m 3 adds three bounces.
TEST_F(PtlabCs184Flags, MaxDepth) {
  ASSERT_EQ(Render(kLambertian + " -r 32 24 -s 4 -m 0 -o " + Out("m0.exr")), 0) << Log();
  ASSERT_EQ(Render(kLambertian + " -r 32 24 -s 4 -m 3 -o " + Out("m3.exr")), 0) << Log();
  EXPECT_EQ(Header(dir_ / "m0.exr")["ptlab:max_depth"], "0");
  EXPECT_EQ(Header(dir_ / "m3.exr")["ptlab:max_depth"], "3");
  EXPECT_LT(Mean(dir_ / "m0.exr"), 0.5 * Mean(dir_ / "m3.exr"));
  ExpectUsageError(kLambertian + " -m -2 -o " + Out("bad.exr"), "-m");
  ExpectUsageError(kLambertian + " -m deep -o " + Out("bad.exr"), "-m");
}

// The unlit bunny is black without -e and lit by the map with it.
TEST_F(PtlabCs184Flags, EnvironmentMap) {
  ASSERT_EQ(Render(kUnlit + " -r 16 12 -s 2 -o " + Out("dark.exr")), 0) << Log();
  ASSERT_EQ(Render(kUnlit + " -r 16 12 -s 2 -e " + kVenice + " -o " + Out("lit.exr")), 0) << Log();
  EXPECT_EQ(Mean(dir_ / "dark.exr"), 0.0);
  EXPECT_GT(Mean(dir_ / "lit.exr"), 0.1);
  EXPECT_EQ(Header(dir_ / "lit.exr")["ptlab:environment_maps"], "1");
  ExpectUsageError(kUnlit + " -e " + Out("missing.exr") + " -o " + Out("bad.exr"), "-e");
  // A file that is not an image: an input error (exit 1) naming the flag.
  EXPECT_EQ(Render(kUnlit + " -e " + kUnlit + " -o " + Out("bad.exr")), 2) << Log();
  EXPECT_NE(Log().find("-e: "), std::string::npos) << Log();
  EXPECT_FALSE(fs::exists(dir_ / "bad.exr"));
}

// -b 0 is the pinhole (the same image as without it); -b 0.2 blurs it.
TEST_F(PtlabCs184Flags, LensRadiusAndFocalDistance) {
  ASSERT_EQ(Render(kLambertian + " -r 32 24 -s 2 -o " + Out("pin.exr")), 0) << Log();
  ASSERT_EQ(Render(kLambertian + " -r 32 24 -s 2 -b 0 -o " + Out("b0.exr")), 0) << Log();
  ASSERT_EQ(Render(kLambertian + " -r 32 24 -s 2 -b 0.2 -d 3.5 -o " + Out("lens.exr")), 0)
      << Log();
  StatusOr<Image> pin = ReadImage(Out("pin.exr")), b0 = ReadImage(Out("b0.exr")),
                  lens = ReadImage(Out("lens.exr"));
  ASSERT_TRUE(pin.ok() && b0.ok() && lens.ok());
  EXPECT_EQ(pin->rgb, b0->rgb);
  EXPECT_NE(pin->rgb, lens->rgb);
  auto h = Header(dir_ / "lens.exr");
  EXPECT_EQ(h["ptlab:lens_radius"], "0.200000");
  EXPECT_EQ(h["ptlab:focal_distance"], "3.500000");
  ExpectUsageError(kLambertian + " -b -0.1 -o " + Out("bad.exr"), "--lens-radius");
  ExpectUsageError(kLambertian + " -b nan -o " + Out("bad.exr"), "--lens-radius");
  ExpectUsageError(kLambertian + " -d 0 -o " + Out("bad.exr"), "--focal-distance");
}

TEST_F(PtlabCs184Flags, Resolution) {
  ASSERT_EQ(Render(kLambertian + " -r 40 30 -o " + Out("r.exr")), 0) << Log();
  StatusOr<Image> im = ReadImage(Out("r.exr"));
  ASSERT_TRUE(im.ok());
  EXPECT_EQ(im->width, 40);
  EXPECT_EQ(im->height, 30);
  ExpectUsageError(kLambertian + " -r 40 -o " + Out("bad.exr"), "-r");
  ExpectUsageError(kLambertian + " -r 0 30 -o " + Out("bad.exr"), "-r");
  ExpectUsageError(kLambertian + " -r 40 30 --width 20 -o " + Out("bad.exr"), "excludes");
}

// -c FILE: a CS184 camera settings file moves the camera (another image; the lens line is
// used, -d on the command line wins); a bad file is exit 2 naming -c and file:line.
TEST_F(PtlabCs184Flags, CameraFile) {
  // In front of the Cornell box's open side (ptlab z = -1), looking into it along +z: right
  // (-1, 0, 0), up (0, 1, 0), back (0, 0, -1); vFov 40.
  const std::string camera =
      "60 40 1.33333 0.01 100\n0 0.75 -3 0 0.75 0 \n0 0 3 0.5 50\n-1 0 0 0 1 0 0 0 -1 \n"
      "640 480 1\n4.5 0\n";
  std::FILE* f = std::fopen(Out("cam.txt").c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs(camera.c_str(), f);
  std::fclose(f);
  ASSERT_EQ(Render(kLambertian + " -r 32 24 -s 2 -o " + Out("file.exr")), 0) << Log();
  ASSERT_EQ(Render(kLambertian + " -r 32 24 -s 2 -c " + Out("cam.txt") + " -o " + Out("c.exr")),
            0)
      << Log();
  ASSERT_EQ(Render(kLambertian + " -r 32 24 -s 2 -c " + Out("cam.txt") + " -d 2 -o " +
                   Out("cd.exr")),
            0)
      << Log();
  StatusOr<Image> file = ReadImage(Out("file.exr")), c = ReadImage(Out("c.exr"));
  ASSERT_TRUE(file.ok() && c.ok());
  EXPECT_NE(file->rgb, c->rgb);
  EXPECT_GT(Mean(Out("c.exr")), 0.01);
  EXPECT_EQ(Header(dir_ / "c.exr")["ptlab:focal_distance"], "4.500000");
  EXPECT_EQ(Header(dir_ / "cd.exr")["ptlab:focal_distance"], "2.000000");
  f = std::fopen(Out("bad.txt").c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs("60 40 1.33333 0.01 100\n0 1 x\n", f);
  std::fclose(f);
  ExpectUsageError(kLambertian + " -c " + Out("bad.txt") + " -o " + Out("bad.exr"),
                   "-c: " + Out("bad.txt") + ":2: 'x' is not a number");
  ExpectUsageError(kLambertian + " -c " + Out("nothere.txt") + " -o " + Out("bad.exr"),
                   "--camera-file");
}

// -f names the PNG and the EXR goes beside it.
TEST_F(PtlabCs184Flags, OutputFile) {
  ASSERT_EQ(Render(kLambertian + " -r 16 12 -f " + Out("out.png")), 0) << Log();
  EXPECT_TRUE(fs::exists(dir_ / "out.png"));
  EXPECT_TRUE(fs::exists(dir_ / "out.exr"));
  EXPECT_EQ(Render(kLambertian + " -r 16 12 -f " + Out("bad.txt")), 2) << Log();
  EXPECT_NE(Log().find("must end in .png"), std::string::npos) << Log();
  EXPECT_FALSE(fs::exists(dir_ / "bad.txt"));
  ExpectUsageError(kLambertian + " -f " + Out("bad.png") + " -o " + Out("bad.exr"), "excludes");
}

// -a batch tolerance: a loose tolerance stops pixels early, so fewer samples are taken.
TEST_F(PtlabCs184Flags, AdaptiveSampling) {
  ASSERT_EQ(Render(kLambertian + " -r 16 12 -s 64 -a 8 0.5 -o " + Out("a.exr")), 0) << Log();
  auto h = Header(dir_ / "a.exr");
  EXPECT_EQ(h["ptlab:adaptive"], "8 0.500000");
  EXPECT_LT(std::stoull(h["ptlab:samples_taken"]), 64ull * 16 * 12);
  ExpectUsageError(kLambertian + " -a 0 0.5 -o " + Out("bad.exr"), "-a: batch");
  ExpectUsageError(kLambertian + " -a 8 nan -o " + Out("bad.exr"), "-a: tolerance");
  ExpectUsageError(kLambertian + " -a 8 -o " + Out("bad.exr"), "-a");
}

}  // namespace
}  // namespace ptlab
