// Camera: Nori's projection conventions and the thin lens.
#include "engine/render/camera.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include <gtest/gtest.h>

#include "engine/core/rng.h"

namespace ptlab {
namespace {

CameraDesc MakeDesc(float fov, int w, int h) {
  CameraDesc d;
  d.fov_deg = fov;
  d.width = w;
  d.height = h;
  return d;
}

TEST(Camera, CentreRayLooksAlongZ) {
  const Camera cam(MakeDesc(40, 64, 32));
  const Ray r = cam.GenerateRay(32, 16, {0.5f, 0.5f});
  EXPECT_NEAR(r.d.x, 0, 1e-6);
  EXPECT_NEAR(r.d.y, 0, 1e-6);
  EXPECT_NEAR(r.d.z, 1, 1e-6);
  EXPECT_FLOAT_EQ(r.t_min, 1e-4f);
}

TEST(Camera, FovIsHorizontalAndImageLeftIsCameraPlusX) {
  const float fov = 50;
  const Camera cam(MakeDesc(fov, 200, 100));
  const Ray left = cam.GenerateRay(0, 50, {0.5f, 0.5f});
  const Ray right = cam.GenerateRay(200, 50, {0.5f, 0.5f});
  const Ray top = cam.GenerateRay(100, 0, {0.5f, 0.5f});
  EXPECT_GT(left.d.x, 0);   // Nori: +x in camera space is image left
  EXPECT_LT(right.d.x, 0);
  EXPECT_GT(top.d.y, 0);    // row 0 is the top
  const float half = std::atan2(left.d.x, left.d.z) * 180.0f / kPi;
  EXPECT_NEAR(half, fov / 2, 1e-4);
  // Vertical half-angle follows the aspect ratio: tan(v) = tan(h) / aspect.
  EXPECT_NEAR(top.d.y / top.d.z, std::tan(Radians(fov / 2)) / 2.0f, 1e-6);
}

TEST(Camera, ThinLensWithZeroRadiusIsThePinhole) {
  CameraDesc d = MakeDesc(30, 64, 64);
  d.camera_to_world = Transform::Translate({1, 2, 3}) * Transform::Rotate({0, 1, 0}, 30);
  CameraDesc lens = d;
  lens.aperture_radius = 0.0f;
  lens.focus_distance = 5.0f;
  const Camera a(d), b(lens);
  for (float u : {0.0f, 0.3f, 0.999f}) {
    const Ray ra = a.GenerateRay(10.5f, 40.25f, {u, 1 - u});
    const Ray rb = b.GenerateRay(10.5f, 40.25f, {u, 1 - u});
    EXPECT_EQ(ra.o, rb.o);
    EXPECT_EQ(ra.d, rb.d);
  }
}

TEST(Camera, ThinLensRaysMeetOnThePlaneOfFocus) {
  CameraDesc d = MakeDesc(30, 64, 64);
  d.aperture_radius = 0.2f;
  d.focus_distance = 4.0f;
  const Camera cam(d);
  const Ray centre = cam.GenerateRay(20.5f, 10.5f, {0.5f, 0.5f});
  const Vec3f focus = centre.o + centre.d * (4.0f / centre.d.z);
  for (float u : {0.05f, 0.4f, 0.95f}) {
    const Ray r = cam.GenerateRay(20.5f, 10.5f, {u, 0.7f});
    EXPECT_LE(std::hypot(r.o.x, r.o.y), 0.2f + 1e-6f);
    const Vec3f p = r.o + r.d * ((4.0f - r.o.z) / r.d.z);
    EXPECT_NEAR(p.x, focus.x, 1e-4);
    EXPECT_NEAR(p.y, focus.y, 1e-4);
  }
}

// Mitsuba's orthographic camera: the film spans x in [-1, 1] and y in [-1/aspect, 1/aspect] of
// camera space (image left = +x, top = +y) on the plane z = near_clip, mapped by the transform
// (whose scale sets the extent); rays go along its +z, from t = 0 to far - near.
TEST(Camera, OrthographicRaysAreParallelFromTheNearPlane) {
  CameraDesc d = MakeDesc(30, 200, 100);
  d.projection = CameraDesc::Projection::kOrthographic;
  d.near_clip = 2.0f, d.far_clip = 50.0f;
  d.camera_to_world = Transform::Translate({1, 2, 3}) * Transform::Scale({3, 3, 1});
  const Camera cam(d);
  const Ray centre = cam.GenerateRay(100, 50, {0.5f, 0.5f});
  EXPECT_NEAR(centre.o.x, 1.0f, 1e-6f);
  EXPECT_NEAR(centre.o.y, 2.0f, 1e-6f);
  EXPECT_NEAR(centre.o.z, 5.0f, 1e-6f);  // 3 + near_clip
  EXPECT_EQ(centre.d, (Vec3f{0, 0, 1}));
  EXPECT_EQ(centre.t_min, 0.0f);
  EXPECT_EQ(centre.t_max, 48.0f);
  const Ray top_left = cam.GenerateRay(0, 0, {0.5f, 0.5f});
  EXPECT_NEAR(top_left.o.x, 1.0f + 3.0f, 1e-6f);
  EXPECT_NEAR(top_left.o.y, 2.0f + 3.0f / 2.0f, 1e-6f);
  const Ray bottom_right = cam.GenerateRay(200, 100, {0.5f, 0.5f});
  EXPECT_NEAR(bottom_right.o.x, 1.0f - 3.0f, 1e-6f);
  EXPECT_NEAR(bottom_right.o.y, 2.0f - 3.0f / 2.0f, 1e-6f);
  EXPECT_EQ(bottom_right.d, centre.d);
  // A rotated camera: the direction is the unit image of +z.
  d.camera_to_world = Transform::Rotate({0, 1, 0}, 90) * Transform::Scale({2, 2, 4});
  const Ray turned = Camera(d).GenerateRay(10, 20, {0.5f, 0.5f});
  EXPECT_NEAR(turned.d.x, 1.0f, 1e-6f);
  EXPECT_NEAR(Length(turned.d), 1.0f, 1e-6f);
}

// GenerateRay8 against GenerateRay, bit for bit, lane by lane: pinhole and orthographic (the
// vectorised loops) and thin lens, scaled and rotated transforms, film positions at the edges,
// centre, outside the film and random, lens numbers at 0 and just under 1.
TEST(Camera, GenerateRay8IsGenerateRayPerLane) {
  const auto bits = [](float v) { return std::bit_cast<uint32_t>(v); };
  Pcg32 rng(11, 3);
  for (float aperture : {0.0f, 0.15f, -1.0f}) {  // -1: orthographic
    for (int t = 0; t < 3; ++t) {
      CameraDesc d = MakeDesc(t == 2 ? 120.0f : 35.0f, 97, 61);
      if (aperture < 0) d.projection = CameraDesc::Projection::kOrthographic;
      if (t >= 1)
        d.camera_to_world = Transform::Translate({-3, 0.5f, 7}) *
                            Transform::Rotate({0.2f, 1, -0.4f}, 71) *
                            Transform::Scale({1, t == 2 ? -2.0f : 1.0f, 1});
      d.aperture_radius = std::max(aperture, 0.0f);
      d.focus_distance = 4.0f;
      d.near_clip = 1e-3f, d.far_clip = 1e3f;
      const Camera cam(d);
      const float edges[] = {0.0f, 97.0f, 61.0f, 48.5f, 30.5f, -1.0f, 1e-7f, 96.99999f};
      for (int round = 0; round < 200; ++round) {
        float px[8], py[8];
        Vec2f lens[8];
        for (int j = 0; j < 8; ++j) {
          const bool edge = round < 8;
          px[j] = edge ? edges[(j + round) % 8] : 97.0f * rng.NextFloat();
          py[j] = edge ? edges[(j * 3 + round) % 8] : 61.0f * rng.NextFloat();
          lens[j] = edge ? Vec2f{j % 2 ? 0.99999994f : 0.0f, j % 3 ? 0.5f : 0.99999994f}
                         : Vec2f{rng.NextFloat(), rng.NextFloat()};
        }
        RayPacket8 packet;
        cam.GenerateRay8(px, py, lens, &packet);
        for (int j = 0; j < 8; ++j) {
          const Ray r = cam.GenerateRay(px[j], py[j], lens[j]);
          const Ray g = GetLaneRay(packet, j);
          ASSERT_EQ(bits(g.o.x), bits(r.o.x)) << j;
          ASSERT_EQ(bits(g.o.y), bits(r.o.y)) << j;
          ASSERT_EQ(bits(g.o.z), bits(r.o.z)) << j;
          ASSERT_EQ(bits(g.d.x), bits(r.d.x)) << j;
          ASSERT_EQ(bits(g.d.y), bits(r.d.y)) << j;
          ASSERT_EQ(bits(g.d.z), bits(r.d.z)) << j;
          ASSERT_EQ(bits(g.t_min), bits(r.t_min)) << j;
          ASSERT_EQ(bits(g.t_max), bits(r.t_max)) << j;
        }
      }
    }
  }
}

}  // namespace
}  // namespace ptlab
