// Delta emitters of Mitsuba scenes: the spot's intensity profile (full beam, linear falloff in
// angle, cutoff) and the projector's frustum and irradiance, against values computed here.
#include "engine/light/delta_light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/io/mitsuba_loader.h"
#include "engine/light/light_selection.h"

namespace ptlab {
namespace {

constexpr double kPiD = 3.14159265358979323846;

Scene LoadScene(const std::string& emitters) {
  const std::string xml =
      "<scene version=\"3.0.0\"><sensor type=\"perspective\"><film type=\"hdrfilm\">"
      "<integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/></film>"
      "</sensor>" +
      emitters + "</scene>";
  StatusOr<Scene> s = LoadMitsubaSceneFromString(xml, ".", "delta.xml", LoadOptions{});
  EXPECT_TRUE(s.ok()) << s.status().message();
  return s.ok() ? std::move(*s) : Scene{};
}

// A point at angle theta (radians) off the spot's axis and distance r, in the plane of the axis
// and `side` (both world, unit, orthogonal).
Vec3f PointAt(const Vec3f& origin, const Vec3f& axis, const Vec3f& side, double theta, double r) {
  return origin + axis * float(r * std::cos(theta)) + side * float(r * std::sin(theta));
}

// Mitsuba 3's spot profile computed independently: 1 inside the beam, (cutoff - θ) / (cutoff -
// beam) between beam and cutoff, 0 outside.
double SpotProfile(double theta, double beam, double cutoff) {
  if (theta <= beam) return 1.0;
  if (theta >= cutoff) return 0.0;
  return (cutoff - theta) / (cutoff - beam);
}

TEST(DeltaLight, MitsubaSpotFollowsItsLinearFalloff) {
  // At (1, 2, 3), looking along +x (lookat to (5, 2, 3)), cutoff 30°, beam 12°.
  const Scene scene = LoadScene(
      "<emitter type=\"spot\"><rgb name=\"intensity\" value=\"2, 3, 4\"/>"
      "<float name=\"cutoff_angle\" value=\"30\"/><float name=\"beam_width\" value=\"12\"/>"
      "<transform name=\"to_world\"><lookat origin=\"1, 2, 3\" target=\"5, 2, 3\" up=\"0, 0, 1\"/>"
      "</transform></emitter>");
  ASSERT_EQ(scene.emitters.size(), 1u);
  const EmitterRef e = scene.emitters[0];
  ASSERT_EQ(e.tag(), EmitterTag::kSpot);
  ASSERT_TRUE(IsDeltaLight(e));
  const Vec3f origin{1, 2, 3}, axis{1, 0, 0};
  const double deg = kPiD / 180.0, beam = 12 * deg, cutoff = 30 * deg;
  for (const Vec3f side : {Vec3f{0, 1, 0}, Vec3f{0, 0, -1}, Vec3f{0, 0.6f, 0.8f}}) {
    for (double theta_deg :
         {0.0, 5.0, 11.9, 12.1, 15.0, 20.0, 25.0, 29.0, 29.9, 30.1, 45.0, 120.0}) {
      const double theta = theta_deg * deg, r = 2.5;
      const Vec3f p = PointAt(origin, axis, side, theta, r);
      DeltaLightSample s;
      const bool lit = SampleDeltaLight(scene, e, p, &s);
      const double f = SpotProfile(theta, beam, cutoff);
      if (f == 0.0) {
        EXPECT_FALSE(lit) << theta_deg;
        continue;
      }
      ASSERT_TRUE(lit) << theta_deg;
      EXPECT_NEAR(s.position.x, 1.0f, 1e-6f);
      EXPECT_NEAR(Dot(s.wi, Normalize(origin - p)), 1.0f, 1e-6f);
      // The rgb intensity as given, times the profile, over r².
      const double expected_g = 3.0 * f / (r * r);
      EXPECT_NEAR(s.radiance.g, expected_g, 2e-5 * 3.0 / (r * r)) << theta_deg;
      EXPECT_NEAR(s.radiance.r / s.radiance.b, 0.5, 1e-6) << theta_deg;
    }
  }
  // Its power for the selection table: 2π I ∫ profile sin θ dθ, integrated numerically here.
  double integral = 0;
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    const double theta = (k + 0.5) * kPiD / n;
    integral += SpotProfile(theta, beam, cutoff) * std::sin(theta) * kPiD / n;
  }
  const double luminance = 0.212671 * 2 + 0.715160 * 3 + 0.072169 * 4;
  EXPECT_NEAR(scene.emitter_selection.power[0], 2 * kPiD * integral * luminance,
              1e-4 * 2 * kPiD * integral * luminance);
}

TEST(DeltaLight, MitsubaSpotDefaultsAndErrors) {
  // beam_width defaults to 3/4 of cutoff_angle (20° → 15°).
  const Scene scene = LoadScene("<emitter type=\"spot\"/>");
  ASSERT_EQ(scene.spot_lights.size(), 1u);
  EXPECT_NEAR(scene.spot_lights.cos_half_angle[0], std::cos(20 * kPiD / 180), 1e-7);
  EXPECT_NEAR(scene.spot_lights.cos_beam[0], std::cos(15 * kPiD / 180), 1e-7);
  EXPECT_NEAR(scene.spot_lights.inv_transition[0], 1.0 / (5 * kPiD / 180), 1e-3);
  EXPECT_EQ(scene.spot_lights.exponent[0], 0.0f);
  // The spot shines along its local +z.
  EXPECT_NEAR(scene.spot_lights.axis[0].z, 1.0f, 1e-7f);
}

// The projector's image on a plane facing it at distance 1 is exactly π · scale · irradiance
// (what Mitsuba 3 defines), for every point inside the frustum; nothing outside or behind.
TEST(DeltaLight, ProjectorLightsItsFrustumWithTheImage) {
  // At (0, 0, 1) looking down -z (up +y), fov 90° (x; aspect 1), scale 2, irradiance (1, 2, 3).
  const Scene scene = LoadScene(
      "<emitter type=\"projector\"><float name=\"fov\" value=\"90\"/>"
      "<float name=\"scale\" value=\"2\"/><rgb name=\"irradiance\" value=\"1, 2, 3\"/>"
      "<transform name=\"to_world\"><lookat origin=\"0, 0, 1\" target=\"0, 0, 0\" "
      "up=\"0, 1, 0\"/></transform></emitter>");
  ASSERT_EQ(scene.emitters.size(), 1u);
  const EmitterRef e = scene.emitters[0];
  ASSERT_EQ(e.tag(), EmitterTag::kProjector);
  ASSERT_TRUE(IsDeltaLight(e));
  // The plane z = 0 is at distance 1 along the projector's axis; the frustum there is
  // |x|, |y| <= tan 45° = 1.
  for (const float x : {0.0f, 0.3f, -0.7f, 0.99f}) {
    for (const float y : {0.0f, -0.5f, 0.95f}) {
      const Vec3f p{x, y, 0};
      DeltaLightSample s;
      ASSERT_TRUE(SampleDeltaLight(scene, e, p, &s)) << x << " " << y;
      const double cos_theta = double(s.wi.z);  // the plane's normal is +z, facing the light
      const double r2 = double(x) * x + double(y) * y + 1.0;
      EXPECT_NEAR(cos_theta, 1.0 / std::sqrt(r2), 1e-6);
      // Irradiance on the plane = radiance factor · cos θ.
      EXPECT_NEAR(s.radiance.r * cos_theta, kPiD * 2 * 1, 1e-4) << x << " " << y;
      EXPECT_NEAR(s.radiance.b * cos_theta, kPiD * 2 * 3, 3e-4) << x << " " << y;
    }
  }
  // On the plane z = -1 (distance 2 along the axis) the frustum is twice as wide and the
  // irradiance a quarter: E π s / z² with z the distance along the axis.
  DeltaLightSample s;
  ASSERT_TRUE(SampleDeltaLight(scene, e, {1.5f, -1.9f, -1}, &s));
  EXPECT_NEAR(s.radiance.g * s.wi.z, kPiD * 2 * 2 / 4, 1e-4);
  // Outside the frustum, behind the pinhole, at it.
  EXPECT_FALSE(SampleDeltaLight(scene, e, {1.01f, 0, 0}, &s));
  EXPECT_FALSE(SampleDeltaLight(scene, e, {0, -1.01f, 0}, &s));
  EXPECT_FALSE(SampleDeltaLight(scene, e, {0, 0, 2}, &s));
  EXPECT_FALSE(SampleDeltaLight(scene, e, {0, 0, 1}, &s));
  // The selection table's power: π s E over the window (2 tan 45°)² at z = 1.
  const double luminance = 0.212671 * 1 + 0.715160 * 2 + 0.072169 * 3;
  EXPECT_NEAR(scene.emitter_selection.power[0], kPiD * 2 * luminance * 4, 1e-4);
}

TEST(DeltaLight, ProjectorImageUvFollowsTheCameraFilm) {
  // A 60° projector at the origin looking along +z (identity to_world): image left (u = 0) is
  // the local +x side, the top row (v = 0) the local +y side, as a perspective camera's film.
  const Scene scene = LoadScene(
      "<emitter type=\"projector\"><float name=\"fov\" value=\"60\"/>"
      "<rgb name=\"irradiance\" value=\"1\"/></emitter>");
  ASSERT_EQ(scene.projectors.size(), 1u);
  const float t = std::tan(float(30 * kPiD / 180));
  EXPECT_NEAR(scene.projectors.tan_half_x[0], t, 1e-6f);
  EXPECT_NEAR(scene.projectors.tan_half_y[0], t, 1e-6f);
  Color3f c;
  EXPECT_TRUE(ProjectorRadianceAt(scene.projectors, 0, {0.99f * t, 0.99f * t, 1}, &c));
  EXPECT_FALSE(ProjectorRadianceAt(scene.projectors, 0, {1.01f * t, 0, 1}, &c));
  EXPECT_FALSE(ProjectorRadianceAt(scene.projectors, 0, {0, -1.01f * t, 1}, &c));
}

}  // namespace
}  // namespace ptlab
