// CS184 camera settings files (`pathtracer -c`): the numbers Camera::dump_settings writes
// become ptlab's camera; malformed files are errors naming file:line.
#include "engine/io/cs184_camera_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace ptlab {
namespace {

// As CS184's dump_settings writes them: hFov vFov ar nClip fClip / pos targetPos /
// phi theta r minR maxR / c2w row-major / screenW screenH screenDist / focalDistance lensRadius.
// This camera sits at (2, 1, 5) and looks along +x: right (0, 0, 1), up (0, 1, 0), back (-1, 0, 0).
const std::string kLookingAlongX =
    "50 35 1.5 0.01 100\n"
    "2 1 5 7 1 5 \n"
    "0 0 5 0.5 50\n"
    "0 0 -1 0 1 0 1 0 0 \n"
    "960 640 1\n"
    "3.5 0.25\n";

void ExpectNear(const Vec3f& a, const Vec3f& b) {
  EXPECT_NEAR(a.x, b.x, 1e-6f);
  EXPECT_NEAR(a.y, b.y, 1e-6f);
  EXPECT_NEAR(a.z, b.z, 1e-6f);
}

CameraDesc Film480x320() {
  CameraDesc c;
  c.width = 480, c.height = 320;
  return c;
}

TEST(Cs184CameraFile, PoseFieldOfViewClipAndLens) {
  CameraDesc c = Film480x320();
  ASSERT_TRUE(ApplyCs184CameraSettings(kLookingAlongX, "t.cam", &c).ok());
  ExpectNear(c.camera_to_world.ApplyPoint({0, 0, 0}), {2, 1, 5});
  ExpectNear(c.camera_to_world.ApplyVector({0, 0, 1}), {1, 0, 0});   // the view: -back
  ExpectNear(c.camera_to_world.ApplyVector({0, 1, 0}), {0, 1, 0});   // up
  ExpectNear(c.camera_to_world.ApplyVector({1, 0, 0}), {0, 0, -1});  // ptlab's +x: the left
  // vFov 35° is kept; the horizontal field follows the 3:2 film.
  const double tan_h = std::tan(17.5 * std::numbers::pi / 180) * 1.5;
  EXPECT_NEAR(std::tan(c.fov_deg * std::numbers::pi / 360), tan_h, 1e-6);
  EXPECT_TRUE(c.keep_vertical_fov);
  EXPECT_EQ(c.near_clip, 0.01f);
  EXPECT_EQ(c.far_clip, 100.0f);
  EXPECT_EQ(c.focus_distance, 3.5f);
  EXPECT_EQ(c.aperture_radius, 0.25f);
  EXPECT_EQ(c.width, 480);
  // Without the lens line (older CS184 versions) the camera keeps its lens.
  CameraDesc d = Film480x320();
  d.focus_distance = 4.7f;
  ASSERT_TRUE(
      ApplyCs184CameraSettings(kLookingAlongX.substr(0, kLookingAlongX.rfind("3.5")), "t.cam", &d)
          .ok());
  EXPECT_EQ(d.focus_distance, 4.7f);
  EXPECT_EQ(d.aperture_radius, 0.0f);
}

void ExpectError(const std::string& text, int line, const std::string& words) {
  CameraDesc c = Film480x320();
  const Status s = ApplyCs184CameraSettings(text, "t.cam", &c);
  ASSERT_FALSE(s.ok()) << text;
  EXPECT_NE(s.message().find("t.cam:" + std::to_string(line) + ": "), std::string::npos)
      << s.message();
  EXPECT_NE(s.message().find(words), std::string::npos) << s.message();
}

// kLookingAlongX with the n-th number (from 0) replaced by `value`.
std::string With(size_t n, const std::string& value) {
  std::string text = kLookingAlongX;
  size_t at = 0;
  for (size_t i = 0;; ++i) {
    at = text.find_first_not_of(" \n", at);
    const size_t end = text.find_first_of(" \n", at);
    if (i == n) return text.replace(at, end - at, value);
    at = end;
  }
}

TEST(Cs184CameraFile, BadFilesNameFileAndLine) {
  ExpectError(With(6, "x"), 2, "'x' is not a number");
  ExpectError(With(3, "nan"), 1, "'nan' is not a finite number");
  ExpectError(kLookingAlongX.substr(0, kLookingAlongX.rfind(" 0.25")), 6, "holds 29 numbers");
  ExpectError("50 35 1.5 0.01 100\n2 1 5\n", 2, "holds 8 numbers");
  ExpectError("", 1, "holds 0 numbers");
  ExpectError(kLookingAlongX + "7\n", 7, "more than 30");
  ExpectError(With(0, "0"), 1, "hFov");
  ExpectError(With(1, "180"), 1, "vFov");
  ExpectError(With(2, "-1.5"), 1, "ar -1.5 is out of range [1e-3, 1e3]");
  ExpectError(With(4, "0.001"), 1, "0 < nClip < fClip");
  ExpectError(With(18, "0"), 4, "zero third column");  // back (0, 0, 0)
  ExpectError(With(20, "0"), 4, "up axis");            // up (0, 0, 0)
  ExpectError(With(28, "0"), 6, "focalDistance");
  ExpectError(With(29, "-0.5"), 6, "lensRadius");
}

}  // namespace
}  // namespace ptlab
