// Delta emitters of Mitsuba scenes: the spot's intensity profile (full beam, linear falloff in
// angle, cutoff) and the projector's frustum and irradiance, against values computed here.
#include "engine/light/delta_light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/io/mitsuba_loader.h"
#include "engine/light/emission.h"
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
  EXPECT_TRUE(
      ProjectorRadianceAt(scene.projectors, scene.textures, 0, {0.99f * t, 0.99f * t, 1}, &c));
  EXPECT_FALSE(ProjectorRadianceAt(scene.projectors, scene.textures, 0, {1.01f * t, 0, 1}, &c));
  EXPECT_FALSE(ProjectorRadianceAt(scene.projectors, scene.textures, 0, {0, -1.01f * t, 1}, &c));
}

// A textured spot multiplies its intensity by the texture at uv = 0.5 + 0.5 (x, y) / (z tan
// cutoff) in its own frame (Mitsuba 3's spot). A checkerboard scaled ×2 in uv changes colour at
// u = 0.75, i.e. x / (z tan cutoff) = 0.5, and at u = 0.5 (x = 0): the lookup's scale and its
// orientation (local x = lookat's left = world +y here, local y = world +z) are both seen.
TEST(DeltaLight, TexturedSpotProjectsItsTextureInItsFrame) {
  const Scene scene = LoadScene(
      "<emitter type=\"spot\"><rgb name=\"intensity\" value=\"2\"/>"
      "<float name=\"cutoff_angle\" value=\"30\"/><float name=\"beam_width\" value=\"30\"/>"
      "<texture name=\"texture\" type=\"checkerboard\"><rgb name=\"color0\" value=\"1, 0, 0\"/>"
      "<rgb name=\"color1\" value=\"0, 0, 1\"/><transform name=\"to_uv\"><scale value=\"2\"/>"
      "</transform></texture>"
      "<transform name=\"to_world\"><lookat origin=\"1, 2, 3\" target=\"5, 2, 3\" up=\"0, 0, 1\"/>"
      "</transform></emitter>");
  ASSERT_EQ(scene.spot_lights.texture.size(), 1u);
  const EmitterRef e = scene.emitters[0];
  const double tan_c = std::tan(30 * kPiD / 180);
  struct Case {
    double tx, ty;  // x / (z tan cutoff), y / (z tan cutoff)
    bool color0;    // (frac 2u > ½) == (frac 2v > ½)
  };
  // ty = 0.1: v = 0.55, frac 2v = 0.1 (not > ½).
  for (const Case c : {Case{0.4, 0.1, true}, Case{0.6, 0.1, false}, Case{-0.4, 0.1, false},
                       Case{-0.6, 0.1, true}, Case{0.1, 0.6, false}, Case{0.1, -0.4, false}}) {
    const double z = 2.0;
    const Vec3f p{1 + float(z), 2 + float(c.tx * z * tan_c), 3 + float(c.ty * z * tan_c)};
    DeltaLightSample s;
    ASSERT_TRUE(SampleDeltaLight(scene, e, p, &s)) << c.tx << " " << c.ty;
    const Vec3f d = p - Vec3f{1, 2, 3};
    const float dist2 = Dot(d, d);
    EXPECT_NEAR(s.radiance.r * dist2, c.color0 ? 2.0f : 0.0f, 1e-4f) << c.tx << " " << c.ty;
    EXPECT_NEAR(s.radiance.b * dist2, c.color0 ? 0.0f : 2.0f, 1e-4f) << c.tx << " " << c.ty;
    // The light subpaths' intensity is the same function.
    const Color3f intensity = DeltaLightIntensity(scene, e, -s.wi);
    EXPECT_NEAR(intensity.r, s.radiance.r * dist2, 1e-4f);
    EXPECT_NEAR(intensity.b, s.radiance.b * dist2, 1e-4f);
  }
}

// A textured projector shows its image at uv = (0.5 - x / (2 z tan), 0.5 - y / (2 z tan)) in
// its frame: looking down -z with up +y, its local x is world -x, so the checkerboard's colour0
// quadrants (u > ½) == (v > ½) are world x > 0, y < 0 and x < 0, y > 0. Its selection power
// uses the image's mean.
TEST(DeltaLight, TexturedProjectorShowsItsImage) {
  const Scene scene = LoadScene(
      "<emitter type=\"projector\"><float name=\"fov\" value=\"90\"/>"
      "<float name=\"scale\" value=\"2\"/><texture name=\"irradiance\" type=\"checkerboard\">"
      "<rgb name=\"color0\" value=\"1, 0, 0\"/><rgb name=\"color1\" value=\"0, 0, 3\"/>"
      "</texture><transform name=\"to_world\"><lookat origin=\"0, 0, 1\" target=\"0, 0, 0\" "
      "up=\"0, 1, 0\"/></transform></emitter>");
  ASSERT_EQ(scene.projectors.texture.size(), 1u);
  const EmitterRef e = scene.emitters[0];
  for (const float x : {-0.6f, 0.3f}) {
    for (const float y : {-0.2f, 0.7f}) {
      DeltaLightSample s;
      ASSERT_TRUE(SampleDeltaLight(scene, e, {x, y, 0}, &s));
      const bool color0 = (x > 0) == (y < 0);
      const double irradiance_r = double(s.radiance.r) * double(s.wi.z);
      const double irradiance_b = double(s.radiance.b) * double(s.wi.z);
      EXPECT_NEAR(irradiance_r, color0 ? kPiD * 2 : 0.0, 1e-4) << x << " " << y;
      EXPECT_NEAR(irradiance_b, color0 ? 0.0 : kPiD * 2 * 3, 3e-4) << x << " " << y;
    }
  }
  const double mean_luminance = 0.5 * (0.212671 * 1 + 0.072169 * 3);
  EXPECT_NEAR(scene.emitter_selection.power[0], kPiD * 2 * mean_luminance * 4, 1e-4);
}

// Light subpaths from a projector (SampleEmission / EmissionPdf): the intensity a sampled
// direction carries is what SampleDeltaLight sends a point along it (I / r²), its density is
// EmissionPdf's, and E[1 / pdf] over the samples is the frustum's solid angle
// 4 atan(tx ty / sqrt(1 + tx² + ty²)).
TEST(DeltaLight, ProjectorEmissionSamplingCoversItsFrustum) {
  const Scene scene = LoadScene(
      "<emitter type=\"projector\"><float name=\"fov\" value=\"70\"/>"
      "<float name=\"scale\" value=\"2\"/><texture name=\"irradiance\" type=\"checkerboard\">"
      "<rgb name=\"color0\" value=\"1, 0.5, 0.25\"/><rgb name=\"color1\" value=\"0.2, 1, 1\"/>"
      "</texture><transform name=\"to_world\"><lookat origin=\"1, 2, 3\" target=\"2, 0, 1\" "
      "up=\"0, 0, 1\"/></transform></emitter>");
  const EmitterRef e = scene.emitters[0];
  const SceneSphere sphere = BoundingSphereOf(scene);
  const double tx = scene.projectors.tan_half_x[0], ty = scene.projectors.tan_half_y[0];
  const double solid_angle = 4.0 * std::atan(tx * ty / std::sqrt(1.0 + tx * tx + ty * ty));
  double sum = 0;
  const int n = 64;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      EmissionSample es;
      const Vec2f u{(float(i) + 0.5f) / n, (float(j) + 0.5f) / n};
      ASSERT_TRUE(SampleEmission(scene, sphere, e, {0.5f, 0.5f}, u, &es));
      EXPECT_TRUE(es.delta_position);
      float pdf_pos, pdf_dir;
      EmissionPdf(scene, sphere, e, es.n, es.w, &pdf_pos, &pdf_dir);
      EXPECT_NEAR(pdf_dir, es.pdf_dir, 1e-5f * es.pdf_dir);
      sum += 1.0 / double(es.pdf_dir);
      DeltaLightSample s;
      const Vec3f p = es.p + es.w * 2.0f;
      ASSERT_TRUE(SampleDeltaLight(scene, e, p, &s)) << i << " " << j;
      EXPECT_NEAR(s.radiance.r * 4.0f, es.radiance.r, 2e-4f * es.radiance.r) << i << " " << j;
      EXPECT_NEAR(s.radiance.g * 4.0f, es.radiance.g, 2e-4f * es.radiance.g) << i << " " << j;
    }
  }
  EXPECT_NEAR(sum / (n * n), solid_angle, 1e-3 * solid_angle);
  // Outside the frustum: no density, no light.
  float pdf_pos, pdf_dir;
  const Vec3f behind = -scene.projectors.to_world[0].n;
  EmissionPdf(scene, sphere, e, behind, behind, &pdf_pos, &pdf_dir);
  EXPECT_EQ(pdf_dir, 0.0f);
  EXPECT_TRUE(IsBlack(DeltaLightIntensity(scene, e, behind)));
}

// An emitter reads a texture at its own uv, never at a mesh's triangle: a mesh_attribute
// texture is refused.
TEST(DeltaLight, EmitterRefusesMeshAttributeTexture) {
  const std::string xml =
      "<scene version=\"3.0.0\"><emitter type=\"spot\"><texture name=\"texture\" "
      "type=\"mesh_attribute\"><string name=\"name\" value=\"vertex_color\"/></texture>"
      "</emitter></scene>";
  StatusOr<Scene> s = LoadMitsubaSceneFromString(xml, ".", "delta.xml", LoadOptions{});
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.status().message().find("unsupported"), std::string::npos) << s.status().message();
}

}  // namespace
}  // namespace ptlab
