// Tests of the XML scene loader: the Nori scenes, transforms, and one test per malformed input.
#include "engine/io/xml_loader.h"

#include "engine/bsdf/conductor_presets.h"
#include "tests/test_data.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace ptlab {
namespace {

std::string DataDir() { return PTLAB_SOURCE_DIR "/tests/data/scene"; }
std::string NoriDir() { return test_data::Path("nori"); }

#define PTLAB_SKIP_WITHOUT_NORI_DATA() PTLAB_REQUIRE_DATA(NoriDir())

// A scene with the required camera and integrator on lines 2-3; `body` starts on line 4.
std::string Wrap(const std::string& body) {
  return "<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\"/>\n" + body +
         "</scene>\n";
}

StatusOr<Scene> Parse(const std::string& xml) {
  return LoadSceneFromString(xml, DataDir(), "bad.xml");
}

// The error starts with "file:line:" and contains every word of `words`.
void ExpectError(const StatusOr<Scene>& result, const std::string& file, int line,
                 const std::vector<std::string>& words) {
  ASSERT_FALSE(result.ok()) << "expected an error";
  const std::string& message = result.status().message();
  const std::string prefix = file + ":" + std::to_string(line) + ":";
  EXPECT_EQ(message.rfind(prefix, 0), 0u)
      << "message does not start with '" << prefix << "': " << message;
  for (const std::string& w : words)
    EXPECT_NE(message.find(w), std::string::npos) << "'" << w << "' missing from: " << message;
}

void ExpectParseError(const std::string& body, int line, const std::vector<std::string>& words) {
  SCOPED_TRACE(body);
  ExpectError(Parse(Wrap(body)), "bad.xml", line, words);
}

void ExpectNear(const Vec3f& a, const Vec3f& b, float tolerance = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tolerance) << "x";
  EXPECT_NEAR(a.y, b.y, tolerance) << "y";
  EXPECT_NEAR(a.z, b.z, tolerance) << "z";
}

// Loads a scene with one rectangle under `transform_body`; returns its first triangle's vertices
// ((-1,-1,0), (1,-1,0), (1,1,0) in object space).
std::vector<Vec3f> TransformedRectangle(const std::string& transform_body) {
  const StatusOr<Scene> scene =
      Parse(Wrap("<shape type=\"rectangle\"><transform name=\"toWorld\">" + transform_body +
                 "</transform></shape>\n"));
  EXPECT_TRUE(scene.ok()) << scene.status().message();
  if (!scene.ok()) return {Vec3f(), Vec3f(), Vec3f()};
  return {scene->triangles.V0(0), scene->triangles.V1(0), scene->triangles.V2(0)};
}

Vec3f Column(const Transform& t, int c) {
  const auto& m = t.matrix().m;
  return {m[0][c], m[1][c], m[2][c]};
}

// ---------------------------------------------------------------------------------------------
// The Nori scenes

TEST(SceneLoader, AllSupportedNoriScenesLoad) {
  PTLAB_SKIP_WITHOUT_NORI_DATA();
  const char* const kScenes[] = {
      "epfl/scenes/pa1/bunny.xml",
      "epfl/scenes/pa4/cbox/cbox-distributed.xml",
      "epfl/scenes/pa4/cbox/cbox-whitted.xml",
      "epfl/scenes/pa4/motto/motto-diffuse.xml",
      "epfl/scenes/pa4/motto/motto-dielectric.xml",
      "epfl/scenes/pa5/cbox/cbox_ems.xml",
      "epfl/scenes/pa5/cbox/cbox_mats.xml",
      "epfl/scenes/pa5/cbox/cbox_mis.xml",
      "epfl/scenes/pa5/table/table_ems.xml",
      "epfl/scenes/pa5/table/table_mats.xml",
      "epfl/scenes/pa5/table/table_mis.xml",
      "epfl/scenes/pa5/veach_mi/veach_ems.xml",
      "epfl/scenes/pa5/veach_mi/veach_mats.xml",
      "epfl/scenes/pa5/veach_mi/veach_mis.xml",
      "eth2015/scenes/pa3/odyssey/odyssey_ems.xml",
      "eth2015/scenes/pa3/odyssey/odyssey_mats.xml",
      "eth2015/scenes/pa3/odyssey/odyssey_mis.xml",
  };
  for (const char* name : kScenes) {
    const StatusOr<Scene> scene = LoadScene(NoriDir() + "/" + name);
    ASSERT_TRUE(scene.ok()) << scene.status().message();
    EXPECT_GT(scene->triangles.size(), 0u) << name;
    EXPECT_EQ(scene->shading.size(), scene->triangles.size()) << name;
    EXPECT_EQ(scene->area_lights.triangle_cdf.size() > 0, scene->area_lights.size() > 0) << name;
  }
}

// eth2015/scenes/pa4/table/meshes is a symlink in the source repository; the shared copy may
// hold a plain file with the link text instead, which makes the scene unloadable.
TEST(SceneLoader, Eth2015TableScenesLoadWhenTheirMeshLinkIsADirectory) {
  PTLAB_SKIP_WITHOUT_NORI_DATA();
  const std::string dir = NoriDir() + "/eth2015/scenes/pa4/table";
  for (const char* name : {"table_path_mats.xml", "table_path_mis.xml"}) {
    const StatusOr<Scene> scene = LoadScene(dir + "/" + name);
    if (std::filesystem::is_directory(dir + "/meshes")) {
      ASSERT_TRUE(scene.ok()) << scene.status().message();
      EXPECT_EQ(scene->area_lights.size(), 2u);
    } else {
      ExpectError(scene, dir + "/" + name, 30, {"meshes/mesh_1.obj", "Not a directory"});
    }
  }
  if (!std::filesystem::is_directory(dir + "/meshes"))
    GTEST_SKIP() << dir << "/meshes is not a directory (a symlink stored as a file); the "
                 << "scenes fail with a clear error";
}

TEST(SceneLoader, UnsupportedNoriScenesFailClearly) {
  PTLAB_SKIP_WITHOUT_NORI_DATA();
  const std::string ttest = NoriDir() + "/epfl/scenes/pa5/tests/test-furnace.xml";
  ExpectError(LoadScene(ttest), ttest, 16, {"<test>", "not supported yet"});
}

TEST(SceneLoader, CboxDistributed) {
  PTLAB_SKIP_WITHOUT_NORI_DATA();
  const StatusOr<Scene> scene = LoadScene(NoriDir() + "/epfl/scenes/pa4/cbox/cbox-distributed.xml");
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  EXPECT_EQ(scene->meshes.size(), 6u);
  EXPECT_EQ(scene->triangles.size(), 6u + 2 + 2 + 3968 + 3968 + 2);
  ASSERT_EQ(scene->area_lights.size(), 1u);
  EXPECT_EQ(scene->area_lights.mesh[0], 5u);
  EXPECT_EQ(scene->area_lights.radiance[0].g, 40.0f);
  EXPECT_NEAR(scene->area_lights.area[0], 0.47f * 0.38f, 1e-5f);
  ASSERT_EQ(scene->emitters.size(), 1u);
  EXPECT_EQ(scene->meshes.emitter[5], scene->emitters[0]);
  EXPECT_EQ(scene->emitters[0].tag(), EmitterTag::kArea);
  // Meshes without a bsdf get Nori's diffuse 0.5: here the light.
  EXPECT_EQ(scene->materials.diffuse.size(), 6u);
  EXPECT_EQ(scene->materials.diffuse.Albedo(5).r, 0.5f);
  EXPECT_EQ(scene->materials.diffuse.Albedo(0).g, 0.71f);
  EXPECT_EQ(scene->camera.fov_deg, 27.7856f);
  EXPECT_EQ(scene->camera.width, 800);
  EXPECT_EQ(scene->camera.height, 600);
  EXPECT_EQ(scene->camera.aperture_radius, 0.0f);
  EXPECT_EQ(scene->sampler.sample_count, 512u);
  EXPECT_EQ(scene->integrator.type, IntegratorDesc::Type::kWhitted);
  EXPECT_EQ(scene->filter.type, FilterDesc::Type::kGaussian);
  EXPECT_EQ(scene->filter.radius, 2.0f);
  EXPECT_EQ(scene->filter.stddev, 0.5f);
  // lookat · scale(-1,1,1): lookat's left = up × dir = (-1,0,0) here, mirrored to (+1,0,0).
  ExpectNear(Column(scene->camera.camera_to_world, 0), {1, 0, 0});
  ExpectNear(Column(scene->camera.camera_to_world, 3), {0, 0.919769f, 5.41159f});
  EXPECT_TRUE(scene->camera.camera_to_world.FlipsHandedness());
}

TEST(SceneLoader, BunnyVeachTableMottoOdyssey) {
  PTLAB_SKIP_WITHOUT_NORI_DATA();
  {
    const StatusOr<Scene> s = LoadScene(NoriDir() + "/epfl/scenes/pa1/bunny.xml");
    ASSERT_TRUE(s.ok()) << s.status().message();
    EXPECT_EQ(s->triangles.size(), 2000u);
    EXPECT_EQ(s->meshes.has_normals[0], 1);
    EXPECT_EQ(s->camera.fov_deg, 16.0f);
    EXPECT_EQ(s->camera.width, 768);
    EXPECT_EQ(s->sampler.sample_count, 1u);
    EXPECT_EQ(s->integrator.type, IntegratorDesc::Type::kNormals);
  }
  {
    const StatusOr<Scene> s = LoadScene(NoriDir() + "/epfl/scenes/pa5/veach_mi/veach_mis.xml");
    ASSERT_TRUE(s.ok()) << s.status().message();
    EXPECT_EQ(s->meshes.size(), 10u);
    EXPECT_EQ(s->area_lights.size(), 5u);
    EXPECT_EQ(s->emitters.size(), 5u);
    ASSERT_EQ(s->materials.rough_plastic.size(), 4u);
    EXPECT_EQ(s->materials.rough_plastic.alpha[0], 0.005f);
    EXPECT_EQ(s->materials.rough_plastic.alpha[3], 0.1f);
    EXPECT_EQ(s->materials.rough_plastic.int_ior[0], 1.5046f);
    EXPECT_EQ(s->materials.rough_plastic.kd_b[2], 0.0325f);
    EXPECT_EQ(s->camera.height, 512);
    EXPECT_EQ(s->sampler.sample_count, 128u);
    EXPECT_EQ(s->integrator.type, IntegratorDesc::Type::kPathMis);
    EXPECT_EQ(s->area_lights.radiance[1].r, 901.803f);
  }
  {
    const StatusOr<Scene> s = LoadScene(NoriDir() + "/epfl/scenes/pa5/table/table_ems.xml");
    ASSERT_TRUE(s.ok()) << s.status().message();
    EXPECT_EQ(s->area_lights.size(), 2u);
    ASSERT_EQ(s->materials.dielectric.size(), 3u);
    EXPECT_EQ(s->materials.dielectric.int_ior[0], 1.33f);
    EXPECT_EQ(s->materials.dielectric.ext_ior[0], 1.0f);
    EXPECT_EQ(s->materials.dielectric.ext_ior[2], 1.5f);
    ASSERT_EQ(s->materials.rough_plastic.size(), 1u);
    EXPECT_EQ(s->materials.rough_plastic.alpha[0], 0.1f);
    EXPECT_EQ(s->materials.rough_plastic.kd_r[0], 0.0f);
    EXPECT_EQ(s->integrator.type, IntegratorDesc::Type::kPathEms);
  }
  {
    const StatusOr<Scene> s = LoadScene(NoriDir() + "/epfl/scenes/pa4/motto/motto-dielectric.xml");
    ASSERT_TRUE(s.ok()) << s.status().message();
    EXPECT_EQ(s->meshes.triangle_count[1], 138u);  // floor.obj: quads and two 36-gons
    EXPECT_EQ(s->materials.dielectric.int_ior[0], 1.5046f);
    EXPECT_EQ(s->materials.dielectric.ext_ior[0], 1.000277f);
    EXPECT_NEAR(s->camera.camera_to_world.matrix().m[0][3], 9.67120708926533f, 1e-5f);
    EXPECT_NEAR(s->camera.camera_to_world.matrix().m[2][0], 0.437626730902902f, 1e-7f);
  }
  {
    // Monolith: translate(0,0.5,0) then scale(1,9,4) of the unit cube [-0.5,0.5]³ → y in [0, 9].
    const StatusOr<Scene> s = LoadScene(NoriDir() + "/eth2015/scenes/pa3/odyssey/odyssey_mis.xml");
    ASSERT_TRUE(s.ok()) << s.status().message();
    float y_min = 1e30f, y_max = -1e30f, z_max = -1e30f;
    for (uint32_t t = 0; t < s->meshes.triangle_count[0]; ++t)
      for (const Vec3f& v : {s->triangles.V0(t), s->triangles.V1(t), s->triangles.V2(t)}) {
        y_min = std::min(y_min, v.y), y_max = std::max(y_max, v.y), z_max = std::max(z_max, v.z);
      }
    EXPECT_EQ(y_min, 0.0f);
    EXPECT_EQ(y_max, 9.0f);
    EXPECT_EQ(z_max, 2.0f);
    EXPECT_EQ(s->integrator.type, IntegratorDesc::Type::kDirectMis);
    EXPECT_EQ(s->sampler.sample_count, 32u);
  }
}

// ---------------------------------------------------------------------------------------------
// Our own scenes, shapes and transforms

TEST(SceneLoader, RelativeObjPathAndAreaLight) {
  const StatusOr<Scene> scene = LoadScene(DataDir() + "/minimal.xml");
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  EXPECT_EQ(scene->source_path, DataDir() + "/minimal.xml");
  EXPECT_EQ(scene->triangles.size(), 4u);
  EXPECT_EQ(scene->meshes.name[0], "meshes/fan.obj");
  ASSERT_EQ(scene->area_lights.size(), 1u);
  EXPECT_EQ(scene->area_lights.radiance[0].b, 3.0f);
  // Camera defaults (Nori): fov 30, 1280x720, clips 1e-4 / 1e4; sampler default 1 spp.
  EXPECT_EQ(scene->camera.fov_deg, 30.0f);
  EXPECT_EQ(scene->camera.width, 1280);
  EXPECT_EQ(scene->camera.height, 720);
  EXPECT_EQ(scene->camera.near_clip, 1e-4f);
  EXPECT_EQ(scene->camera.far_clip, 1e4f);
  EXPECT_EQ(scene->sampler.sample_count, 1u);
  EXPECT_EQ(scene->integrator.max_depth, -1);
  EXPECT_FALSE(scene->integrator.power_heuristic);
  // The diffuse default material, as Nori gives a mesh without a bsdf.
  EXPECT_EQ(scene->shading.material[0].tag(), MaterialTag::kDiffuse);
  EXPECT_EQ(scene->materials.diffuse.Albedo(0).g, 0.5f);
}

TEST(SceneLoader, ShapesMaterialsIntegratorAndFilter) {
  const std::string xml = R"(<scene>
  <integrator type="path_mis">
    <integer name="maxDepth" value="5"/>
    <integer name="lightSamples" value="4"/>
    <string name="heuristic" value="power"/>
  </integrator>
  <sampler type="independent"><integer name="sampleCount" value="16"/></sampler>
  <camera type="thinlens">
    <float name="apertureRadius" value="0.1"/>
    <float name="focusDistance" value="3"/>
    <rfilter type="tent"/>
  </camera>
  <shape type="sphere">
    <point name="center" value="1 2 3"/>
    <float name="radius" value="0.5"/>
    <bsdf type="roughconductor">
      <float name="alpha" value="0.2"/>
      <color name="eta" value="0.2, 0.9, 1.1"/>
      <color name="k" value="3.9, 2.4, 2.2"/>
    </bsdf>
  </shape>
  <shape type="cube"><bsdf type="mirror"/></shape>
  <shape type="disk"><bsdf type="microfacet"/></shape>
  <shape type="rectangle">
    <transform name="toWorld"><scale value="2, 3, 1"/></transform>
    <emitter type="area"><color name="radiance" value="1, 1, 1"/></emitter>
  </shape>
</scene>
)";
  const StatusOr<Scene> scene = Parse(xml);
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  EXPECT_EQ(scene->integrator.type, IntegratorDesc::Type::kPathMis);
  EXPECT_EQ(scene->integrator.max_depth, 5);
  EXPECT_EQ(scene->integrator.light_samples, 4);
  EXPECT_TRUE(scene->integrator.power_heuristic);
  EXPECT_EQ(scene->sampler.sample_count, 16u);
  EXPECT_EQ(scene->camera.aperture_radius, 0.1f);
  EXPECT_EQ(scene->camera.focus_distance, 3.0f);
  EXPECT_EQ(scene->filter.type, FilterDesc::Type::kTent);
  EXPECT_EQ(scene->filter.radius, 1.0f);
  ASSERT_EQ(scene->meshes.size(), 4u);
  EXPECT_EQ(scene->meshes.triangle_count[0], 3968u);
  EXPECT_EQ(scene->meshes.triangle_count[1], 12u);
  EXPECT_EQ(scene->meshes.triangle_count[2], 64u);
  EXPECT_EQ(scene->meshes.triangle_count[3], 2u);
  EXPECT_EQ(scene->meshes.name[0], "sphere");
  EXPECT_EQ(scene->meshes.material[0].tag(), MaterialTag::kConductor);
  EXPECT_EQ(scene->materials.conductor.eta_g[0], 0.9f);
  EXPECT_EQ(scene->materials.conductor.k_r[0], 3.9f);
  EXPECT_EQ(scene->materials.conductor.alpha[0], 0.2f);
  EXPECT_EQ(scene->meshes.material[1].tag(), MaterialTag::kMirror);
  EXPECT_EQ(scene->meshes.material[2].tag(), MaterialTag::kRoughPlastic);
  EXPECT_EQ(scene->materials.rough_plastic.kd_g[0], 0.5f);
  EXPECT_EQ(scene->materials.rough_plastic.ext_ior[0], 1.000277f);
  // The sphere's top pole is center + radius·z.
  EXPECT_EQ(scene->triangles.V0(0), (Vec3f{1, 2, 3.5f}));
  ASSERT_EQ(scene->area_lights.size(), 1u);
  EXPECT_EQ(scene->area_lights.mesh[0], 3u);
  EXPECT_FLOAT_EQ(scene->area_lights.area[0], 24.0f);
  EXPECT_EQ(scene->area_lights.triangle_cdf.size(), 2u);
  EXPECT_FLOAT_EQ(scene->area_lights.triangle_cdf[0], 0.5f);
}

TEST(SceneLoader, GaussianAndBoxFilters) {
  {
    const StatusOr<Scene> s =
        Parse(Wrap("<rfilter type=\"gaussian\"><float name=\"radius\" value=\"1.5\"/>"
                   "<float name=\"stddev\" value=\"0.25\"/></rfilter>\n"));
    ASSERT_TRUE(s.ok()) << s.status().message();
    EXPECT_EQ(s->filter.type, FilterDesc::Type::kGaussian);
    EXPECT_EQ(s->filter.radius, 1.5f);
    EXPECT_EQ(s->filter.stddev, 0.25f);
  }
  {
    const StatusOr<Scene> s = Parse(Wrap("<rfilter type=\"box\"/>\n"));
    ASSERT_TRUE(s.ok()) << s.status().message();
    EXPECT_EQ(s->filter.type, FilterDesc::Type::kBox);
    EXPECT_EQ(s->filter.radius, 0.5f);
  }
}

TEST(SceneLoader, TransformStepsApplyInOrderFromTheLeft) {
  // p' = scale · (translate · p).
  std::vector<Vec3f> v =
      TransformedRectangle("<translate value=\"1, 0, 0\"/><scale value=\"2 3 4\"/>");
  ExpectNear(v[0], {0, -3, 0});
  ExpectNear(v[1], {4, -3, 0});
  ExpectNear(v[2], {4, 3, 0});
  // The other order: p' = translate · (scale · p).
  v = TransformedRectangle("<scale value=\"2 3 4\"/><translate value=\"1, 0, 0\"/>");
  ExpectNear(v[0], {-1, -3, 0});
  ExpectNear(v[1], {3, -3, 0});
  // rotate 90° about +z (right-hand rule) after translating by +x: (1,-1,0)+(1,0,0) → (1,2,0).
  v = TransformedRectangle("<translate value=\"1,0,0\"/><rotate axis=\"0, 0, 2\" angle=\"90\"/>");
  ExpectNear(v[1], {1, 2, 0});
  ExpectNear(v[0], {1, 0, 0});
  // rotate about +x by 90°: y → z.
  v = TransformedRectangle("<rotate axis=\"1,0,0\" angle=\"90\"/>");
  ExpectNear(v[2], {1, 0, 1});
  // matrix is row-major: the last column is the translation; then a scale is applied after it.
  v = TransformedRectangle(
      "<matrix value=\"0 -1 0 5  1 0 0 6  0 0 1 7  0 0 0 1\"/><scale value=\"1,1,-1\"/>");
  ExpectNear(v[0], {1 + 5, -1 + 6, -7});  // (-1,-1,0) → (1,-1,0) + (5,6,7), then z mirrored
  ExpectNear(v[1], {1 + 5, 1 + 6, -7});   // (1,-1,0) → (1,1,0) + (5,6,7)
}

TEST(SceneLoader, LookatFrameIsLeftUpDirOrigin) {
  const auto camera_with = [](const std::string& lookat) {
    const std::string xml =
        "<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\">"
        "<transform name=\"toWorld\">" +
        lookat + "</transform></camera>\n</scene>\n";
    StatusOr<Scene> scene = Parse(xml);
    EXPECT_TRUE(scene.ok()) << scene.status().message();
    return scene.ok() ? scene->camera.camera_to_world : Transform();
  };
  // dir = +x, up = +z: left = up × dir = +y, newUp = dir × left = +z.
  Transform t = camera_with("<lookat origin=\"1,2,3\" target=\"5,2,3\" up=\"0,0,7\"/>");
  ExpectNear(Column(t, 0), {0, 1, 0});
  ExpectNear(Column(t, 1), {0, 0, 1});
  ExpectNear(Column(t, 2), {1, 0, 0});
  ExpectNear(Column(t, 3), {1, 2, 3});
  EXPECT_EQ(t.matrix().m[3][3], 1.0f);
  // A non-orthogonal up is re-orthogonalised: dir = +z, up = (0,1,1) → left = +x, newUp = +y.
  t = camera_with("<lookat origin=\"0,0,0\" target=\"0,0,2\" up=\"0,1,1\"/>");
  ExpectNear(Column(t, 0), {1, 0, 0});
  ExpectNear(Column(t, 1), {0, 1, 0});
  ExpectNear(Column(t, 2), {0, 0, 1});
  // A general frame: orthonormal, right-handed as (left, up, dir), dir towards the target.
  t = camera_with("<lookat origin=\"1,-2,0.5\" target=\"-3,4,2\" up=\"0.3,0.2,1\"/>");
  const Vec3f left = Column(t, 0), up = Column(t, 1), dir = Column(t, 2);
  ExpectNear(dir, Normalize(Vec3f{-4, 6, 1.5f}));
  ExpectNear(left, Normalize(Cross(Normalize(Vec3f{0.3f, 0.2f, 1}), dir)));
  EXPECT_NEAR(Dot(left, up), 0.0f, 1e-6f);
  ExpectNear(Cross(left, up), dir);
  // The inverse is kept consistent.
  ExpectNear(t.Inverted().ApplyPoint(Vec3f{1, -2, 0.5f}), {0, 0, 0});
}

// ---------------------------------------------------------------------------------------------
// Malformed input: one test per kind

TEST(SceneLoader, XmlSyntaxError) {
  const std::string path = DataDir() + "/bad_syntax.xml";
  ExpectError(LoadScene(path), path, 4, {"XML syntax error", "mismatch"});
}

TEST(SceneLoader, MissingSceneFile) {
  const std::string path = DataDir() + "/does_not_exist.xml";
  const StatusOr<Scene> scene = LoadScene(path);
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.status().message().rfind(path + ": cannot read scene file", 0), 0u)
      << scene.status().message();
}

TEST(SceneLoader, MissingObjFile) {
  const std::string path = DataDir() + "/missing_obj.xml";
  ExpectError(LoadScene(path), path, 5,
              {"cannot load the OBJ file", "meshes/does_not_exist.obj", "No such file"});
}

TEST(SceneLoader, ObjWithoutFaces) {
  const std::string path = DataDir() + "/faceless_obj.xml";
  ExpectError(LoadScene(path), path, 4, {"meshes/no_faces.obj:4:", "expected at least one 'f'"});
}

TEST(SceneLoader, MalformedObjReportsBothFiles) {
  ExpectParseError(
      "<mesh type=\"obj\"><string name=\"filename\" value=\"meshes/bad_number.obj\"/></mesh>\n", 4,
      {"bad_number.obj:3:", "malformed number '1.2.3'"});
}

TEST(SceneLoader, UnknownTag) {
  ExpectParseError("\n<meshh type=\"obj\"/>\n", 5, {"unknown tag <meshh>", "expected"});
  ExpectParseError("<shape type=\"cube\">\n  <colour name=\"albedo\" value=\"1 1 1\"/>\n</shape>\n",
                   5, {"unknown tag <colour>", "color"});
  ExpectParseError(
      "<shape type=\"cube\"><transform name=\"toWorld\">\n<shift value=\"1,1,1\"/>"
      "</transform></shape>\n",
      5, {"unknown transform step <shift>", "translate"});
  ExpectParseError("<shape type=\"cube\">\n<camera type=\"perspective\"/></shape>\n", 5,
                   {"<camera> is not allowed inside <shape type=\"cube\">", "bsdf, emitter"});
}

TEST(SceneLoader, UnknownAttribute) {
  ExpectParseError("<shape type=\"cube\" id=\"box\"/>\n", 4,
                   {"unknown attribute 'id' on <shape>", "expected type"});
  ExpectParseError(
      "<shape type=\"cube\">\n<bsdf type=\"diffuse\">\n"
      "<float name=\"x\" value=\"1\" units=\"m\"/></bsdf></shape>\n",
      6, {"unknown attribute 'units'", "expected name, value"});
  ExpectParseError("<shape type=\"cube\" type=\"disk\"/>\n", 4, {"duplicate attribute 'type'"});
}

TEST(SceneLoader, UnknownPropertyName) {
  ExpectError(Parse("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\">\n"
                    "  <float name=\"fovv\" value=\"30\"/>\n</camera>\n</scene>\n"),
              "bad.xml", 4,
              {"unknown property 'fovv' for <camera type=\"perspective\">", "one of: fov, width"});
  ExpectParseError(
      "<shape type=\"cube\">\n<bsdf type=\"diffuse\">\n"
      "<color name=\"reflectance\" value=\"1 1 1\"/></bsdf></shape>\n",
      6, {"unknown property 'reflectance'", "albedo"});
  ExpectParseError(
      "<shape type=\"cube\"><bsdf type=\"mirror\">\n"
      "<float name=\"intIOR\" value=\"1.5\"/></bsdf></shape>\n",
      5, {"unknown property 'intIOR'", "expected no properties"});
  ExpectError(Parse("<scene>\n<integrator type=\"path_mats\">\n"
                    "<integer name=\"lightSamples\" value=\"2\"/></integrator>\n"
                    "<camera type=\"perspective\"/></scene>\n"),
              "bad.xml", 3, {"unknown property 'lightSamples'", "one of: maxDepth"});
}

TEST(SceneLoader, MissingRequiredAttribute) {
  ExpectParseError("\n<shape/>\n", 5, {"<shape> is missing the attribute 'type'"});
  ExpectParseError(
      "<shape type=\"cube\">\n<bsdf type=\"diffuse\">\n"
      "<color value=\"1 1 1\"/></bsdf></shape>\n",
      6, {"<color> is missing the attribute 'name'"});
  ExpectParseError(
      "<shape type=\"cube\"><transform name=\"toWorld\">\n"
      "<rotate axis=\"0 1 0\"/></transform></shape>\n",
      5, {"<rotate> is missing the attribute 'angle'"});
  ExpectParseError(
      "<shape type=\"cube\"><transform name=\"toWorld\">\n"
      "<lookat origin=\"0 0 0\" target=\"0 0 1\"/></transform></shape>\n",
      5, {"missing the attribute 'up'"});
}

TEST(SceneLoader, MissingRequiredProperty) {
  ExpectParseError("\n<mesh type=\"obj\"/>\n", 5,
                   {"missing the required property <string name=\"filename\">"});
  ExpectParseError("<shape type=\"cube\">\n<emitter type=\"area\"/></shape>\n", 5,
                   {"missing the required property <color name=\"radiance\">"});
  ExpectError(Parse("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"thinlens\">\n"
                    "<float name=\"focusDistance\" value=\"2\"/></camera></scene>\n"),
              "bad.xml", 3, {"apertureRadius"});
}

TEST(SceneLoader, DuplicateProperty) {
  ExpectParseError(
      "<shape type=\"sphere\">\n<float name=\"radius\" value=\"1\"/>\n"
      "<float name=\"radius\" value=\"2\"/>\n</shape>\n",
      6, {"duplicate property 'radius'", "line 5"});
}

TEST(SceneLoader, WrongPropertyType) {
  ExpectError(Parse("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\">\n"
                    "<integer name=\"fov\" value=\"30\"/></camera></scene>\n"),
              "bad.xml", 4, {"property 'fov'", "wrong type <integer>; expected <float>"});
  ExpectParseError("<shape type=\"sphere\">\n<vector name=\"center\" value=\"0 0 0\"/></shape>\n",
                   5, {"wrong type <vector>; expected <point>"});
}

TEST(SceneLoader, MalformedNumber) {
  for (const char* bad :
       {"1.2.3", "abc", "nan", "NaN", "inf", "-inf", "30deg", "", " ", "1e999", "0x10", "1 2"}) {
    const std::string xml =
        "<scene>\n<integrator type=\"normals\"/>\n"
        "<camera type=\"perspective\">\n<float name=\"fov\" value=\"" +
        std::string(bad) + "\"/></camera></scene>\n";
    SCOPED_TRACE(bad);
    ExpectError(Parse(xml), "bad.xml", 4,
                {"malformed number", "expected one finite decimal number"});
  }
  ExpectParseError(
      "<shape type=\"cube\"><transform name=\"toWorld\">\n"
      "<translate value=\"1, nan, 2\"/></transform></shape>\n",
      5, {"malformed number 'nan'"});
  ExpectError(Parse("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\">\n"
                    "<integer name=\"width\" value=\"1.5\"/></camera></scene>\n"),
              "bad.xml", 4, {"integer '1.5' is not an integer", "[-2147483648, 2147483647]"});
  ExpectError(Parse("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\">\n"
                    "<integer name=\"width\" value=\"99999999999\"/></camera></scene>\n"),
              "bad.xml", 4, {"integer '99999999999' is out of range [-2147483648, 2147483647]"});
  ExpectParseError("\n<boolean name=\"x\" value=\"yes\"/>\n", 5,
                   {"malformed boolean 'yes'", "true or false"});
}

TEST(SceneLoader, WrongComponentCount) {
  ExpectParseError(
      "<shape type=\"cube\"><bsdf type=\"diffuse\">\n"
      "<color name=\"albedo\" value=\"0.5\"/></bsdf></shape>\n",
      5, {"wrong number of components", "found 1", "expected 3"});
  ExpectParseError("<shape type=\"sphere\">\n<point name=\"center\" value=\"1,2,3,4\"/></shape>\n",
                   5, {"found 4", "expected 3"});
  ExpectParseError(
      "<shape type=\"cube\"><transform name=\"toWorld\">\n"
      "<matrix value=\"1 0 0 0 0 1 0 0 0 0 1 0 0 0 0\"/></transform></shape>\n",
      5, {"found 15", "expected 16"});
  ExpectParseError(
      "<shape type=\"cube\"><transform name=\"toWorld\">\n"
      "<scale value=\"1,,2\"/></transform></shape>\n",
      5, {"malformed list", "empty item"});
}

TEST(SceneLoader, MoreThanOneCameraSamplerIntegratorOrFilter) {
  ExpectParseError("\n<camera type=\"perspective\"/>\n", 5,
                   {"a second <camera>", "at most one", "line 3"});
  ExpectParseError("<integrator type=\"whitted\"/>\n", 4, {"a second <integrator>", "line 2"});
  ExpectParseError("<sampler type=\"independent\"/>\n<sampler type=\"independent\"/>\n", 5,
                   {"a second <sampler>", "line 4"});
  ExpectError(Parse("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\">\n"
                    "<rfilter type=\"box\"/></camera>\n<rfilter type=\"tent\"/>\n</scene>\n"),
              "bad.xml", 5, {"a second <rfilter>", "line 4"});
  ExpectParseError(
      "<shape type=\"cube\">\n<bsdf type=\"mirror\"/>\n<bsdf type=\"mirror\"/>"
      "</shape>\n",
      6, {"a second <bsdf>", "line 5"});
}

TEST(SceneLoader, MissingCameraOrIntegrator) {
  ExpectError(Parse("\n<scene>\n<integrator type=\"normals\"/>\n</scene>\n"), "bad.xml", 2,
              {"no <camera>"});
  ExpectError(Parse("<scene>\n<camera type=\"perspective\"/>\n</scene>\n"), "bad.xml", 1,
              {"no <integrator>"});
  ExpectError(Parse("\n\n"), "bad.xml", 1, {"no root element", "expected a <scene>"});
}

TEST(SceneLoader, UnknownObjectType) {
  ExpectParseError("\n<shape type=\"ply\"/>\n", 5, {"unknown shape type 'ply'", "obj, sphere"});
  ExpectParseError("<shape type=\"cube\">\n<bsdf type=\"plastic\"/></shape>\n", 5,
                   {"unknown bsdf type 'plastic'", "microfacet"});
  ExpectError(Parse("<scene>\n<integrator type=\"path\"/>\n<camera type=\"perspective\"/></scene>"),
              "bad.xml", 2, {"unknown integrator type 'path'", "path_mis"});
  ExpectError(Parse("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"orthographic\"/>"
                    "</scene>"),
              "bad.xml", 3, {"unknown camera type 'orthographic'", "perspective or thinlens"});
  ExpectParseError("\n<sampler type=\"stratified\"/>\n", 5,
                   {"unknown sampler type", "independent"});
  ExpectParseError("\n<rfilter type=\"mitchell\"/>\n", 5, {"unknown rfilter type", "gaussian"});
  ExpectParseError("\n<emitter type=\"laser\"/>\n", 5, {"unknown emitter type 'laser'"});
  ExpectError(Parse("<camera type=\"perspective\"/>\n"), "bad.xml", 1, {"root element <camera>"});
}

TEST(SceneLoader, UnsupportedFeatures) {
  for (const char* type : {"spot", "directional"}) {
    SCOPED_TRACE(type);
    ExpectParseError("\n<emitter type=\"" + std::string(type) + "\"/>\n", 5,
                     {"emitter type '" + std::string(type) + "' is not supported yet"});
  }
  ExpectParseError("<shape type=\"cube\">\n<emitter type=\"spot\"/></shape>\n", 5,
                   {"emitter type 'spot' is not supported yet"});
  ExpectParseError("<shape type=\"cube\">\n<emitter type=\"point\"/></shape>\n", 5,
                   {"cannot be attached to a shape"});
  ExpectError(Parse("<test type=\"ttest\">\n<scene/></test>\n"), "bad.xml", 1,
              {"<test>", "not supported yet"});
  ExpectParseError(
      "<shape type=\"cube\"><bsdf type=\"roughconductor\">\n"
      "<string name=\"material\" value=\"Unobtainium\"/></bsdf></shape>\n",
      5, {"unknown conductor 'Unobtainium'", "Au"});
  ExpectParseError(
      "<shape type=\"cube\"><bsdf type=\"roughconductor\">\n"
      "<string name=\"material\" value=\"Au\"/><color name=\"eta\" value=\"1,1,1\"/>"
      "<color name=\"k\" value=\"1,1,1\"/></bsdf></shape>\n",
      5, {"either string 'material' or colors"});
  ExpectParseError("\n<bsdf type=\"diffuse\"/>\n", 5, {"<bsdf> is not allowed inside <scene>"});
  ExpectParseError("\n<test type=\"ttest\"/>\n", 5, {"<test>", "not supported yet"});
  ExpectParseError("\n<emitter type=\"area\"/>\n", 5, {"must be inside a <mesh> or <shape>"});
}

TEST(SceneLoader, OutOfRangeValues) {
  ExpectParseError("<shape type=\"sphere\">\n<float name=\"radius\" value=\"-1\"/></shape>\n", 5,
                   {"radius must be > 0"});
  ExpectError(Parse("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\">\n"
                    "<float name=\"fov\" value=\"180\"/></camera></scene>\n"),
              "bad.xml", 4, {"fov", "expected degrees in (0, 180)"});
  ExpectParseError(
      "<sampler type=\"independent\">\n<integer name=\"sampleCount\" value=\"0\"/>"
      "</sampler>\n",
      5, {"sampleCount 0 is out of range; expected 1..1048576"});
  ExpectParseError(
      "<sampler type=\"independent\">\n<integer name=\"sampleCount\" value=\"2000000000\"/>"
      "</sampler>\n",
      5, {"sampleCount 2000000000 is out of range; expected 1..1048576 (as -s)"});
  ExpectParseError(
      "<shape type=\"cube\"><bsdf type=\"diffuse\">\n"
      "<color name=\"albedo\" value=\"1.5 0 0\"/></bsdf></shape>\n",
      5, {"'albedo'", "expected components in [0, 1]"});
  ExpectParseError(
      "<shape type=\"cube\"><transform name=\"toWorld\">\n"
      "<matrix value=\"1 0 0 0 0 1 0 0 0 0 0 0 0 0 0 1\"/></transform></shape>\n",
      5, {"singular <matrix>"});
  ExpectParseError(
      "<shape type=\"cube\"><transform name=\"toWorld\">\n"
      "<scale value=\"1 0 1\"/></transform></shape>\n",
      5, {"singular <scale>"});
  ExpectParseError(
      "<shape type=\"cube\"><transform name=\"toWorld\">\n"
      "<lookat origin=\"0 0 0\" target=\"0 2 0\" up=\"0 1 0\"/></transform></shape>\n",
      5, {"degenerate <lookat>", "not parallel"});
  // A camera far outside the world (the direction's length overflows): the range, not "parallel".
  ExpectParseError(
      "<shape type=\"cube\"><transform name=\"toWorld\">\n"
      "<lookat origin=\"3e38 0 0\" target=\"0 0 0\" up=\"0 1 0\"/></transform></shape>\n",
      5, {"<lookat> origin (3e+38, 0, 0) is out of range", "within +-1e+12"});
  ExpectParseError(
      "<shape type=\"cube\"><transform name=\"toWorld\">\n"
      "<lookat origin=\"0 0 0\" target=\"0 0 2e12\" up=\"0 1 0\"/></transform></shape>\n",
      5, {"<lookat> target (0, 0, 2e+12) is out of range", "within +-1e+12"});
  ExpectParseError(
      "<shape type=\"cube\"><transform name=\"toWorld\">\n"
      "<lookat origin=\"0 0 0\" target=\"0 0 1\" up=\"0 3e19 0\"/></transform></shape>\n",
      5, {"<lookat> up (0, 3e+19, 0) is out of range", "within +-1e+18"});
  ExpectParseError(
      "<shape type=\"cube\"><transform name=\"toWorld\">\n"
      "<rotate axis=\"0 0 0\" angle=\"5\"/></transform></shape>\n",
      5, {"zero <rotate> axis"});
  ExpectParseError(
      "<shape type=\"cube\"><transform name=\"toWorld\">\n"
      "<scale value=\"1e-39 1 1\"/></transform></shape>\n",
      5, {"<scale> makes the transform (or its inverse) overflow"});
  ExpectParseError(
      "<shape type=\"sphere\">\n<float name=\"radius\" value=\"1e38\"/>\n"
      "<transform name=\"toWorld\"><scale value=\"10 10 10\"/></transform></shape>\n",
      4, {"world-space vertex (0, 0, inf)", "within +-1e+12"});
  // Issue 12, finding 2: finite coordinates whose bounds overflow (sums of two reach Inf).
  ExpectParseError("<shape type=\"sphere\">\n<float name=\"radius\" value=\"3e38\"/></shape>\n",
                   4, {"<shape type=\"sphere\">", "3e+38", "within +-1e+12"});
  ExpectError(Parse("<scene>\n<camera type=\"perspective\"/>\n<integrator type=\"path_mis\">\n"
                    "<string name=\"heuristic\" value=\"max\"/></integrator></scene>\n"),
              "bad.xml", 4, {"unknown heuristic 'max'", "balance or power"});
}

TEST(SceneLoader, TextInsideElements) {
  ExpectParseError("<shape type=\"cube\">\nhello</shape>\n", 4, {"unexpected text"});
  ExpectParseError(
      "<shape type=\"cube\"><bsdf type=\"diffuse\">\n"
      "<color name=\"albedo\" value=\"1 1 1\">0.5</color></bsdf></shape>\n",
      5, {"unexpected text inside <color>"});
}

}  // namespace
}  // namespace ptlab

namespace ptlab {
namespace {

// The 2015-16 Nori frame: mirrored (left = dir × up) and not normalised, so a non-perpendicular
// up shrinks both image axes by |up × dir| (what the eth2015 references show).
TEST(SceneLoaderLookat, Nori2015FrameIsMirroredAndUnnormalised) {
  const std::string xml = R"(<scene><integrator type="normals"/>
    <camera type="perspective"><transform name="toWorld">
      <lookat origin="20, 20, 50" target="0, 4, 0" up="0, 1, 0"/></transform></camera></scene>)";
  StatusOr<Scene> now = LoadSceneFromString(xml, ".", "a.xml");
  StatusOr<Scene> old = LoadSceneFromString(xml, ".", "a.xml", {LookatConvention::kNori2015});
  ASSERT_TRUE(now.ok() && old.ok());
  const Vec3f dir = Normalize(Vec3f{-20, -16, -50});
  const float k = Length(Cross(Vec3f{0, 1, 0}, dir));
  ASSERT_LT(k, 0.97f);
  const Vec3f left_now = now->camera.camera_to_world.ApplyVector({1, 0, 0});
  const Vec3f left_old = old->camera.camera_to_world.ApplyVector({1, 0, 0});
  const Vec3f up_now = now->camera.camera_to_world.ApplyVector({0, 1, 0});
  const Vec3f up_old = old->camera.camera_to_world.ApplyVector({0, 1, 0});
  const Vec3f z_old = old->camera.camera_to_world.ApplyVector({0, 0, 1});
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(left_old[i], -k * left_now[i], 1e-6);
    EXPECT_NEAR(up_old[i], k * up_now[i], 1e-6);
    EXPECT_NEAR(z_old[i], dir[i], 1e-6);
  }
}

}  // namespace
}  // namespace ptlab

namespace ptlab {
namespace {

TEST(SceneLoaderConductor, PresetsAndDefaults) {
  const auto load = [](const std::string& bsdf) {
    return LoadSceneFromString("<scene><integrator type=\"normals\"/><camera type=\"perspective\"/>"
                               "<shape type=\"cube\">" + bsdf + "</shape></scene>",
                               ".", "c.xml");
  };
  StatusOr<Scene> au = load("<bsdf type=\"roughconductor\"><string name=\"material\" value=\"Au\"/></bsdf>");
  StatusOr<Scene> cu = load("<bsdf type=\"roughconductor\"/>");
  ASSERT_TRUE(au.ok()) << au.status().message();
  ASSERT_TRUE(cu.ok()) << cu.status().message();
  Color3f eta, k;
  ASSERT_TRUE(LookupConductorPreset("Au", &eta, &k));
  EXPECT_EQ(au->materials.conductor.eta_r[0], eta.r);
  EXPECT_EQ(au->materials.conductor.k_b[0], k.b);
  ASSERT_TRUE(LookupConductorPreset("Cu", &eta, &k));  // Mitsuba's default material
  EXPECT_EQ(cu->materials.conductor.eta_g[0], eta.g);
  EXPECT_FLOAT_EQ(cu->materials.conductor.alpha[0], 0.1f);
}

}  // namespace
}  // namespace ptlab

namespace ptlab {
namespace {

TEST(SceneLoaderDielectric, SchlickAndRadianceScalingFlags) {
  StatusOr<Scene> s = LoadSceneFromString(
      "<scene><integrator type=\"normals\"/><camera type=\"perspective\"/>"
      "<shape type=\"cube\"><bsdf type=\"dielectric\"/></shape>"
      "<shape type=\"cube\"><bsdf type=\"dielectric\"><boolean name=\"schlick\" value=\"true\"/>"
      "<boolean name=\"scaleRadiance\" value=\"true\"/></bsdf></shape></scene>",
      ".", "d.xml");
  ASSERT_TRUE(s.ok()) << s.status().message();
  const DielectricTable& d = s->materials.dielectric;
  ASSERT_EQ(d.size(), 2u);
  ASSERT_EQ(d.flags.size(), 2u);
  EXPECT_EQ(d.flags[0], 0);
  EXPECT_EQ(d.flags[1], kDielectricSchlick | kDielectricScaleRadiance);
}

}  // namespace
}  // namespace ptlab
