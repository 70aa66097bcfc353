// Tests of the XML loader's infinite emitters: envmap and distantdisk, and their errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/image/image_io.h"
#include "engine/io/xml_loader.h"
#include "engine/light/distant_disk.h"
#include "engine/light/environment_map.h"
#include "tests/test_data.h"

namespace ptlab {
namespace {

std::string SharedData() { return test_data::Path(""); }

// A directory holding small maps: sky.exr (4x2), nan.exr (a NaN pixel), and sub/sky.exr.
std::string MapDir() {
  static const std::string dir = [] {
    const std::string d = PTLAB_BINARY_DIR "/light_test_tmp/loader";
    std::filesystem::create_directories(d + "/sub");
    Image sky(4, 2);
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 4; ++i) sky.Set(i, j, {float(i + 1), float(j + 1), 0.25f});
    EXPECT_TRUE(WriteExr(d + "/sky.exr", sky).ok());
    EXPECT_TRUE(WriteExr(d + "/sub/sky.exr", sky).ok());
    Image nan = sky;
    nan.Set(2, 1, {0.5f, std::nanf(""), 0.5f});
    EXPECT_TRUE(WriteExr(d + "/nan.exr", nan).ok());
    return d;
  }();
  return dir;
}

// Camera and integrator on lines 2-3; `body` starts on line 4.
std::string Wrap(const std::string& body) {
  return "<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\"/>\n" + body +
         "</scene>\n";
}

StatusOr<Scene> Parse(const std::string& body) {
  return LoadSceneFromString(Wrap(body), MapDir(), "env.xml");
}

void ExpectParseError(const std::string& body, int line, const std::vector<std::string>& words) {
  SCOPED_TRACE(body);
  const StatusOr<Scene> result = Parse(body);
  ASSERT_FALSE(result.ok()) << "expected an error";
  const std::string& message = result.status().message();
  const std::string prefix = "env.xml:" + std::to_string(line) + ":";
  EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
  for (const std::string& w : words)
    EXPECT_NE(message.find(w), std::string::npos) << "'" << w << "' missing from: " << message;
}

TEST(SceneLoaderInfiniteLights, LoadsAnEnvmapRelativeToTheSceneFile) {
  const StatusOr<Scene> scene = Parse(
      "<emitter type=\"envmap\">\n"
      "  <string name=\"filename\" value=\"sub/../sky.exr\"/>\n"
      "  <float name=\"scale\" value=\"2\"/>\n"
      "</emitter>\n");
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  const EnvironmentMapTable& t = scene->environment_maps;
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t.width[0], 4);
  EXPECT_EQ(t.height[0], 2);
  EXPECT_EQ(t.sampling[0], EnvironmentSampling::kImportance);
  ASSERT_EQ(scene->emitters.size(), 1u);
  EXPECT_EQ(scene->emitters[0], EmitterRef::Make(EmitterTag::kEnvironment, 0));
  // Pixel (2, 1) = (3, 2, 0.25), times the scale, at its centre.
  const Color3f c = EnvironmentRadiance(t, 0, EnvironmentUvToDirection({2.5f / 4, 1.5f / 2}));
  EXPECT_NEAR(c.r, 6.0f, 1e-4f);
  EXPECT_NEAR(c.g, 4.0f, 1e-4f);
  EXPECT_TRUE(scene->area_lights.size() == 0 && scene->distant_disks.size() == 0);
}

TEST(SceneLoaderInfiniteLights, EnvmapTakesSamplingAndARotation) {
  const StatusOr<Scene> scene = Parse(
      "<emitter type=\"envmap\">\n"
      "  <string name=\"filename\" value=\"sky.exr\"/>\n"
      "  <string name=\"sampling\" value=\"uniform\"/>\n"
      "  <transform name=\"toWorld\"><rotate axis=\"1,0,0\" angle=\"90\"/>"
      "<translate value=\"5,6,7\"/></transform>\n"
      "</emitter>\n"
      "<emitter type=\"envmap\"><string name=\"filename\" value=\"" +
      MapDir() + "/sky.exr\"/></emitter>\n");
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  const EnvironmentMapTable& t = scene->environment_maps;
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.sampling[0], EnvironmentSampling::kUniform);
  EXPECT_EQ(t.sampling[1], EnvironmentSampling::kImportance);
  // rotate x 90: the map's up (+y) points along world +z; the translation is ignored.
  EXPECT_NEAR(t.to_world[0].t.z, 1.0f, 1e-6f);
  EXPECT_NEAR(t.to_world[0].n.y, -1.0f, 1e-6f);
  EXPECT_EQ(scene->emitters[1], EmitterRef::Make(EmitterTag::kEnvironment, 1));
}

TEST(SceneLoaderInfiniteLights, LoadsTheNoriSphereScenes) {
  const std::string dir = SharedData() + "nori/eth2015/scenes/pa3/sphere";
  PTLAB_REQUIRE_DATA(dir);
  for (const char* variant : {"ao", "side"}) {
    for (const char* integrator : {"ems", "mats", "mis"}) {
      const std::string path = dir + "/sphere_" + variant + "_" + integrator + ".xml";
      SCOPED_TRACE(path);
      const StatusOr<Scene> scene = LoadScene(path, {LookatConvention::kNori2015});
      ASSERT_TRUE(scene.ok()) << scene.status().message();
      const DistantDiskTable& d = scene->distant_disks;
      ASSERT_EQ(d.size(), 1u);
      ASSERT_EQ(scene->emitters.size(), 1u);
      EXPECT_EQ(scene->emitters[0], EmitterRef::Make(EmitterTag::kDistantDisk, 0));
      EXPECT_EQ(scene->area_lights.size(), 0u);
      if (std::string(variant) == "ao") {
        EXPECT_EQ(d.max_chord2[0], INFINITY);
        EXPECT_FLOAT_EQ(d.radiance[0].g, 0.6f);
      } else {
        EXPECT_FLOAT_EQ(d.max_chord2[0], float(2 * (1 - std::cos(10 * 3.14159265358979 / 180))));
        EXPECT_FLOAT_EQ(d.radiance[0].r, 30.0f);
        const float h = std::sqrt(0.5f);
        EXPECT_NEAR(d.to_world[0].n.y, -h, 1e-6f);
        EXPECT_NEAR(d.to_world[0].n.z, h, 1e-6f);
      }
    }
  }
}

TEST(SceneLoaderInfiniteLights, LoadsThePolyHavenMaps) {
  for (const char* name :
       {"venice_sunset_1k.exr", "venice_sunset_1k.hdr", "pedestrian_overpass_1k.exr"}) {
    const std::string path = SharedData() + "envmaps/" + name;
    PTLAB_REQUIRE_DATA(path);
    const StatusOr<Scene> scene = Parse(
        "<emitter type=\"envmap\"><string name=\"filename\" value=\"" + path + "\"/></emitter>\n");
    ASSERT_TRUE(scene.ok()) << scene.status().message();
    EXPECT_EQ(scene->environment_maps.width[0], 1024) << name;
    EXPECT_EQ(scene->environment_maps.height[0], 512) << name;
  }
}

TEST(SceneLoaderInfiniteLights, DistantDiskWithoutToWorldPointsUp) {
  const StatusOr<Scene> scene = Parse(
      "<emitter type=\"distantdisk\"><color name=\"radiance\" value=\"1 2 3\"/>"
      "<float name=\"thetaA\" value=\"180\"/></emitter>\n");
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  EXPECT_EQ(scene->distant_disks.to_world[0].n, (Vec3f{0, 0, 1}));
  EXPECT_FLOAT_EQ(DistantDiskRadiance(scene->distant_disks, 0, {0, 0, -1}).b, 3.0f);
}

TEST(SceneLoaderInfiniteLights, PointLightsJoinTheEmitterList) {
  const StatusOr<Scene> scene = Parse(
      "<emitter type=\"point\"><point name=\"position\" value=\"-5,-5,5\"/>"
      "<color name=\"power\" value=\"500,250,250\"/></emitter>\n"
      "<emitter type=\"point\"><color name=\"power\" value=\"1,2,3\"/>"
      "<point name=\"position\" value=\"0,1,0\"/></emitter>\n");
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  ASSERT_EQ(scene->point_lights.size(), 2u);
  ASSERT_EQ(scene->emitters.size(), 2u);
  EXPECT_EQ(scene->emitters[1], EmitterRef::Make(EmitterTag::kPoint, 1));
  EXPECT_EQ(scene->point_lights.position[0], (Vec3f{-5, -5, 5}));
  EXPECT_EQ(scene->point_lights.power[1].b, 3.0f);
}

TEST(SceneLoaderInfiniteLights, EnvmapErrors) {
  ExpectParseError("\n<emitter type=\"envmap\"/>\n", 5,
                   {"missing the required property <string name=\"filename\">"});
  ExpectParseError(
      "<emitter type=\"envmap\"><string name=\"filename\" value=\"sky.exr\"/>\n"
      "<float name=\"gamma\" value=\"2.2\"/></emitter>\n",
      5, {"unknown property 'gamma'", "filename, scale, toWorld, sampling"});
  ExpectParseError(
      "<emitter type=\"envmap\"><string name=\"filename\" value=\"sky.exr\"/>\n"
      "<string name=\"sampling\" value=\"cosine\"/></emitter>\n",
      5, {"unknown sampling 'cosine'", "importance or uniform"});
  ExpectParseError(
      "<emitter type=\"envmap\"><string name=\"filename\" value=\"sky.exr\"/>\n"
      "<float name=\"scale\" value=\"-1\"/></emitter>\n",
      5, {"scale = -1 is out of range"});
  ExpectParseError(
      "<emitter type=\"envmap\"><string name=\"filename\" value=\"sky.exr\"/>\n"
      "<integer name=\"scale\" value=\"2\"/></emitter>\n",
      5, {"wrong type <integer>", "<float>"});
  ExpectParseError(
      "<emitter type=\"envmap\"><string name=\"filename\" value=\"sky.exr\"/>\n"
      "<transform name=\"toWorld\"><scale value=\"2,2,2\"/></transform></emitter>\n",
      5, {"not a rotation"});
  ExpectParseError(
      "\n<emitter type=\"envmap\"><string name=\"filename\" value=\"missing.exr\"/>"
      "</emitter>\n",
      5, {"cannot load the image", "missing.exr"});
  ExpectParseError(
      "\n<emitter type=\"envmap\"><string name=\"filename\" value=\"nan.exr\"/></emitter>\n", 5,
      {"nan.exr", "pixel (2, 1)", "NaN", "not clamped"});
  ExpectParseError(
      "<shape type=\"cube\">\n<emitter type=\"envmap\"><string name=\"filename\" "
      "value=\"sky.exr\"/></emitter></shape>\n",
      5, {"cannot be attached to a shape"});
  ExpectParseError("\n<emitter type=\"envmap\" id=\"x\"/>\n", 5, {"unknown attribute 'id'"});
}

TEST(SceneLoaderInfiniteLights, DistantDiskErrors) {
  ExpectParseError(
      "\n<emitter type=\"distantdisk\"><float name=\"thetaA\" value=\"5\"/>"
      "</emitter>\n",
      5, {"missing the required property <color name=\"radiance\">"});
  ExpectParseError(
      "\n<emitter type=\"distantdisk\"><color name=\"radiance\" value=\"1,1,1\"/>"
      "</emitter>\n",
      5, {"missing the required property <float name=\"thetaA\">"});
  for (const char* theta : {"0", "-3", "180.5"})
    ExpectParseError(
        "<emitter type=\"distantdisk\"><color name=\"radiance\" value=\"1,1,1\"/>\n"
        "<float name=\"thetaA\" value=\"" +
            std::string(theta) + "\"/></emitter>\n",
        5, {"thetaA = " + std::string(theta) + " is out of range", "(0, 180]"});
  ExpectParseError(
      "<emitter type=\"distantdisk\"><float name=\"thetaA\" value=\"5\"/>\n"
      "<color name=\"radiance\" value=\"1,-1,1\"/></emitter>\n",
      5, {"'radiance'", "out of range"});
  ExpectParseError(
      "<emitter type=\"distantdisk\"><float name=\"thetaA\" value=\"5\"/>\n"
      "<color name=\"radiance\" value=\"1,1,1\"/><float name=\"scale\" value=\"1\"/>\n"
      "</emitter>\n",
      5, {"unknown property 'scale'", "radiance, thetaA, toWorld"});
  ExpectParseError(
      "<emitter type=\"distantdisk\"><float name=\"thetaA\" value=\"5\"/>"
      "<color name=\"radiance\" value=\"1,1,1\"/>\n"
      "<transform name=\"toWorld\"><matrix value=\"1 0 0 0 0 1 0.5 0 0 0 1 0 0 0 0 1\"/>"
      "</transform></emitter>\n",
      5, {"not a rotation"});
  ExpectParseError("<shape type=\"cube\">\n<emitter type=\"distantdisk\"/></shape>\n", 5,
                   {"cannot be attached to a shape"});
  ExpectParseError("\n<emitter type=\"spot\"/>\n", 5,
                   {"emitter type 'spot' is not supported yet"});
  ExpectParseError("\n<emitter type=\"laser\"/>\n", 5,
                   {"unknown emitter type 'laser'", "envmap, distantdisk, constant or point"});
  // Point lights: position and power are required, power is non-negative.
  ExpectParseError("\n<emitter type=\"point\"><color name=\"power\" value=\"1,1,1\"/></emitter>\n",
                   5, {"position"});
  ExpectParseError("<emitter type=\"point\"><point name=\"position\" value=\"0,0,0\"/>\n"
                   "<color name=\"power\" value=\"1,-1,1\"/></emitter>\n",
                   5, {"power"});
  ExpectParseError("<emitter type=\"point\"><point name=\"position\" value=\"0,0,0\"/>\n"
                   "<color name=\"power\" value=\"1,1,1\"/><float name=\"radius\" value=\"1\"/>"
                   "</emitter>\n",
                   5, {"radius"});
}

}  // namespace
}  // namespace ptlab
