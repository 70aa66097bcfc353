// The Mitsuba scene loader: parameters, includes, search paths, references, transforms, values,
// the plugins it maps to ptlab, and a file:line:col message for each error.
#include "engine/io/mitsuba_loader.h"

#include <gtest/gtest.h>

#include "tests/test_data.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "engine/io/mitsuba_document.h"
#include "engine/io/scene_file.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test with files written into it.
class MitsubaLoader : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("ptlab_mitsuba_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }
  // A scene of `body` with a sensor and an integrator unless the body brings its own.
  static std::string Scene(const std::string& body, const std::string& version = "3.0.0") {
    std::string s = "<scene version=\"" + version + "\">\n";
    if (body.find("<sensor") == std::string::npos)
      s += "<sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" "
           "value=\"8\"/><integer name=\"height\" value=\"8\"/></film></sensor>\n";
    return s + body + "\n</scene>\n";
  }
  StatusOr<ptlab::Scene> Load(const std::string& text, const LoadOptions& options = {}) {
    return LoadMitsubaScene(Write("scene.xml", text), options);
  }
  // The error of loading `text`, which must fail.
  std::string Error(const std::string& text, const LoadOptions& options = {}) {
    StatusOr<ptlab::Scene> s = Load(text, options);
    EXPECT_FALSE(s.ok());
    return s.ok() ? "" : s.status().message();
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

TEST_F(MitsubaLoader, DefaultsSubstitutionAndDefines) {
  const std::string text = Scene(
      "<default name=\"spp\" value=\"16\"/>\n"
      "<default name=\"spp\" value=\"99\"/>\n"  // the first <default> of a name wins
      "<default name=\"integrator\" value=\"path\"/>\n"
      "<integrator type=\"$integrator\"><integer name=\"max_depth\" value=\"$spp\"/></integrator>\n"
      "<sensor type=\"perspective\"><sampler type=\"independent\">"
      "<integer name=\"sample_count\" value=\"$spp\"/></sampler></sensor>");
  StatusOr<ptlab::Scene> s = Load(text);
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->sampler.sample_count, 16u);
  EXPECT_EQ(s->integrator.max_depth, 15);
  LoadOptions options;
  options.defines = {"spp=7", "integrator=direct"};
  const std::string error = Error(text, options);  // direct takes no max_depth
  EXPECT_NE(error.find("unknown property 'max_depth' for <integrator type=\"direct\">"),
            std::string::npos)
      << error;
  options.defines = {"spp=7"};
  s = Load(text, options);
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->sampler.sample_count, 7u);
}

TEST_F(MitsubaLoader, BadParameters) {
  const std::string text = Scene(
      "<integrator type=\"path\">\n  <integer name=\"max_depth\" "
      "value=\"$depth\"/></integrator>");
  EXPECT_EQ(Error(text), Path("scene.xml") +
                             ":4:3: unknown parameter '$depth' in '$depth'; expected a name set "
                             "by <default name=\"depth\" value=...> or -D depth=...");
  LoadOptions options;
  options.defines = {"novalue"};
  EXPECT_NE(Error(Scene(""), options).find("malformed parameter definition 'novalue' (-D)"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<default name=\"a b\" value=\"1\"/>")).find("malformed parameter name"),
            std::string::npos);
}

TEST_F(MitsubaLoader, IncludeAndSearchPaths) {
  Write("data/meshes/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  Write("fragments/shape.xml",
        "<scene version=\"3.0.0\">\n  <shape type=\"obj\"><string name=\"filename\" "
        "value=\"meshes/tri.obj\"/></shape>\n</scene>\n");
  StatusOr<ptlab::Scene> s =
      Load(Scene("<path value=\"data\"/>\n"
                 "<include filename=\"fragments/shape.xml\"/>"));
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->triangles.size(), 1u);
  // Without the <path>, the mesh is not found; the message says where it looked.
  const std::string error = Error(Scene("<include filename=\"fragments/shape.xml\"/>"));
  EXPECT_NE(error.find(Path("fragments/shape.xml") + ":2:21: file 'meshes/tri.obj' of <shape "
                                                     "type=\"obj\"> not found"),
            std::string::npos)
      << error;
  EXPECT_NE(Error(Scene("<path value=\"nowhere\"/>")).find(":3:1: <path>: folder"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<include filename=\"missing.xml\"/>"))
                .find(":3:1: <include>: file "
                      "'missing.xml' not found"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<shape type=\"cube\"><include filename=\"x.xml\"/></shape>"))
                .find("<include> is only allowed directly inside <scene>"),
            std::string::npos);
}

TEST_F(MitsubaLoader, IncludeCycleAndDepth) {
  Write("a.xml", "<scene version=\"3.0.0\">\n<include filename=\"b.xml\"/>\n</scene>\n");
  Write("b.xml", "<scene version=\"3.0.0\">\n\n  <include filename=\"a.xml\"/>\n</scene>\n");
  std::string error = Error(Scene("<include filename=\"a.xml\"/>"));
  EXPECT_NE(error.find(Path("b.xml") + ":3:3: <include> cycle"), std::string::npos) << error;
  // A chain deeper than the limit.
  const auto chain_file = [](int i) { return std::string("c").append(std::to_string(i)) + ".xml"; };
  for (int i = 0; i <= internal::kMaxMitsubaIncludeDepth + 1; ++i)
    Write(chain_file(i), std::string("<scene version=\"3.0.0\"><include filename=\"")
                             .append(chain_file(i + 1))
                             .append("\"/></scene>"));
  Write(chain_file(internal::kMaxMitsubaIncludeDepth + 2), "<scene version=\"3.0.0\"/>");
  error = Error(Scene("<include filename=\"c0.xml\"/>"));
  EXPECT_NE(error.find("<include> nesting deeper than 16 levels"), std::string::npos) << error;
  // An included file must be a Mitsuba scene too.
  Write("nori.xml", "<scene><integrator type=\"path_mis\"/></scene>");
  error = Error(Scene("<include filename=\"nori.xml\"/>"));
  EXPECT_NE(error.find(Path("nori.xml") + ":1:1: <scene> is missing the attribute 'version'"),
            std::string::npos)
      << error;
}

TEST_F(MitsubaLoader, ReferencesShareOneMaterialRow) {
  StatusOr<ptlab::Scene> s = Load(
      Scene("<bsdf type=\"diffuse\" id=\"white\"><rgb name=\"reflectance\" value=\"0.8\"/></bsdf>\n"
            "<shape type=\"rectangle\"><ref id=\"white\"/></shape>\n"
            "<shape type=\"cube\"><ref id=\"white\"/></shape>"));
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->materials.diffuse.size(), 1u);
  EXPECT_EQ(s->meshes.material[0], s->meshes.material[1]);
  EXPECT_FLOAT_EQ(s->materials.diffuse.albedo_g[0], 0.8f);
  EXPECT_EQ(Error(Scene("<shape type=\"cube\">\n  <ref id=\"nothing\"/></shape>")),
            Path("scene.xml") +
                ":4:3: <ref id=\"nothing\"> names no object; expected the id "
                "of an object in the scene");
  EXPECT_NE(Error(Scene("<bsdf type=\"diffuse\" id=\"a\"/>\n<bsdf type=\"diffuse\" id=\"a\"/>"))
                .find(":4:1: duplicate id 'a'"),
            std::string::npos);
}

// Steps apply in document order, each multiplied from the left: translate · rotate · scale
// for <scale/><rotate/><translate/>, and a different result in the other order.
TEST_F(MitsubaLoader, TransformStepsApplyInOrder) {
  const auto corner = [&](const std::string& steps) {
    StatusOr<ptlab::Scene> s =
        Load(Scene("<shape type=\"rectangle\"><transform name=\"to_world\">" + steps +
                   "</transform></shape>"));
    EXPECT_TRUE(s.ok()) << s.status().message();
    return s.ok() ? s->triangles.V1(0) : Vec3f{};  // object-space corner (1, -1, 0)
  };
  const Transform expected = Transform::Translate({1, 2, 3}) * Transform::Rotate({0, 0, 1}, 90) *
                             Transform::Scale({2, 1, 1});
  const Vec3f want = expected.ApplyPoint({1, -1, 0});
  const Vec3f got =
      corner("<scale x=\"2\"/><rotate z=\"1\" angle=\"90\"/><translate value=\"1, 2, 3\"/>");
  EXPECT_NEAR(got.x, want.x, 1e-5f);
  EXPECT_NEAR(got.y, want.y, 1e-5f);
  EXPECT_NEAR(got.z, want.z, 1e-5f);
  EXPECT_NEAR(want.x, 2.0f, 1e-5f);  // (2, -1) rotated a quarter turn: (1, 2), then + (1, 2)
  EXPECT_NEAR(want.y, 4.0f, 1e-5f);
  const Vec3f reversed =
      corner("<translate value=\"1, 2, 3\"/><rotate z=\"1\" angle=\"90\"/><scale x=\"2\"/>");
  EXPECT_GT(std::fabs(reversed.x - want.x) + std::fabs(reversed.y - want.y), 1.0f);
  // matrix (row-major, 9 or 16 numbers) and a uniform scale value.
  const Vec3f m =
      corner("<scale value=\"3\"/><matrix value=\"0 -1 0 0  1 0 0 0  0 0 1 5  0 0 0 1\"/>");
  EXPECT_NEAR(m.x, 3.0f, 1e-5f);
  EXPECT_NEAR(m.y, 3.0f, 1e-5f);
  EXPECT_NEAR(m.z, 5.0f, 1e-5f);
  EXPECT_NE(Error(Scene("<shape type=\"cube\"><transform name=\"to_world\">\n <rotate "
                        "angle=\"3\"/></transform></shape>"))
                .find(":4:2: zero <rotate> axis"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<shape type=\"cube\"><transform name=\"to_world\"><matrix value=\"1 2 "
                        "3\"/></transform></shape>"))
                .find("<matrix> has 3 numbers; expected 16 (4x4) or 9 (3x3)"),
            std::string::npos);
}

TEST_F(MitsubaLoader, LookatOutsideTheWorldNamesTheRange) {
  const auto lookat = [&](const std::string& attributes) {
    return Error(Scene("<sensor type=\"perspective\"><transform name=\"to_world\"><lookat " +
                       attributes + "/></transform></sensor>"));
  };
  std::string e = lookat("origin=\"3e38, 0, 0\" target=\"0, 0, 0\" up=\"0, 1, 0\"");
  EXPECT_NE(e.find("scene.xml:2:55: "), std::string::npos) << e;
  EXPECT_NE(e.find("<lookat> origin (3e+38, 0, 0) is out of range; expected components within "
                   "+-1e+12"),
            std::string::npos)
      << e;
  e = lookat("origin=\"0, 0, 0\" target=\"-5e12, 0, 0\" up=\"0, 1, 0\"");
  EXPECT_NE(e.find("<lookat> target (-5e+12, 0, 0) is out of range"), std::string::npos) << e;
  e = lookat("origin=\"0, 0, 0\" target=\"1, 0, 0\" up=\"0, 1e30, 0\"");
  EXPECT_NE(e.find("<lookat> up (0, 1e+30, 0) is out of range; expected components within "
                   "+-1e+18"),
            std::string::npos)
      << e;
  // Inside the range the step is accepted (a camera 1e12 away looking at the origin).
  EXPECT_TRUE(Load(Scene("<sensor type=\"perspective\"><transform name=\"to_world\"><lookat "
                         "origin=\"1e12, 0, 0\" target=\"0, 0, 0\" up=\"0, 1, 0\"/>"
                         "</transform></sensor>"))
                  .ok());
}

TEST_F(MitsubaLoader, SensorLookatFovAxesAndFilm) {
  const auto sensor = [&](const std::string& props, int w, int h) {
    return Load(Scene("<sensor type=\"perspective\">" + props +
                      "<transform name=\"to_world\"><lookat origin=\"0, -5, 1\" target=\"0, 0, "
                      "1\" up=\"0, 0, 1\"/></transform><film type=\"hdrfilm\"><integer "
                      "name=\"width\" value=\"" +
                      std::to_string(w) +
                      "\"/><integer "
                      "name=\"height\" value=\"" +
                      std::to_string(h) +
                      "\"/><rfilter "
                      "type=\"box\"/></film></sensor>"));
  };
  StatusOr<ptlab::Scene> s = sensor("<float name=\"fov\" value=\"40\"/>", 64, 32);
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_FLOAT_EQ(s->camera.fov_deg, 40.0f);
  EXPECT_EQ(s->camera.width, 64);
  EXPECT_EQ(s->filter.type, FilterDesc::Type::kBox);
  EXPECT_FLOAT_EQ(s->filter.radius, 0.5f);
  EXPECT_FLOAT_EQ(s->camera.near_clip, 1e-2f);  // Mitsuba's default
  // lookat: columns (left, up, dir, origin); looking along +y with +z up, left is -x.
  const Matrix4& m = s->camera.camera_to_world.matrix();
  EXPECT_NEAR(m.m[0][0], -1.0f, 1e-6f);
  EXPECT_NEAR(m.m[2][1], 1.0f, 1e-6f);
  EXPECT_NEAR(m.m[1][2], 1.0f, 1e-6f);
  EXPECT_NEAR(m.m[1][3], -5.0f, 1e-6f);
  const double deg = 180.0 / std::numbers::pi;
  const double half = std::tan(20.0 / deg);
  const auto fov_for = [&](const std::string& axis, int w, int h) {
    StatusOr<ptlab::Scene> r = sensor(
        "<float name=\"fov\" value=\"40\"/><string "
        "name=\"fov_axis\" value=\"" +
            axis + "\"/>",
        w, h);
    EXPECT_TRUE(r.ok()) << r.status().message();
    return r.ok() ? double(r->camera.fov_deg) : 0.0;
  };
  EXPECT_NEAR(fov_for("y", 64, 32), 2 * std::atan(half * 2) * deg, 1e-4);
  EXPECT_NEAR(fov_for("smaller", 64, 32), 2 * std::atan(half * 2) * deg, 1e-4);
  EXPECT_NEAR(fov_for("larger", 64, 32), 40.0, 1e-4);
  EXPECT_NEAR(fov_for("smaller", 32, 64), 40.0, 1e-4);
  EXPECT_NEAR(fov_for("diagonal", 64, 32), 2 * std::atan(half * 2 / std::sqrt(5.0)) * deg, 1e-4);
  // No fov: a 50 mm lens on 36 x 24 mm film, along the diagonal.
  s = sensor("", 48, 48);
  ASSERT_TRUE(s.ok());
  const double diag = std::sqrt(36.0 * 36 + 24 * 24) / 100.0;
  EXPECT_NEAR(s->camera.fov_deg, 2 * std::atan(diag / std::sqrt(2.0)) * deg, 1e-4);
  EXPECT_NE(Error(Scene("<sensor type=\"perspective\">\n<string name=\"fov_axis\" "
                        "value=\"z\"/><float name=\"fov\" value=\"30\"/></sensor>"))
                .find(":3:1: unknown fov_axis 'z'"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<sensor type=\"perspective\"><float name=\"principal_point_offset_x\" "
                        "value=\"0.1\"/></sensor>"))
                .find("unsupported: sensor \"perspective\" with principal_point_offset_x != 0"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<sensor type=\"perspective\"><transform name=\"to_world\"><scale "
                        "value=\"2\"/></transform></sensor>"))
                .find("the sensor's to_world scales or shears"),
            std::string::npos);
  // thinlens: aperture and focus distance (default: far_clip).
  s =
      Load(Scene("<sensor type=\"thinlens\"><float name=\"aperture_radius\" value=\"0.1\"/>"
                 "<float name=\"far_clip\" value=\"50\"/></sensor>"));
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_FLOAT_EQ(s->camera.aperture_radius, 0.1f);
  EXPECT_FLOAT_EQ(s->camera.focus_distance, 50.0f);
  EXPECT_NE(Error(Scene("<sensor type=\"thinlens\"/>"))
                .find("missing the required property "
                      "'aperture_radius'"),
            std::string::npos);
}

// orthographic: to_world keeps its scale (the view's extent); near and far clip; no fov.
TEST_F(MitsubaLoader, OrthographicSensor) {
  StatusOr<ptlab::Scene> s = Load(Scene(
      "<sensor type=\"orthographic\"><float name=\"near_clip\" value=\"1\"/>"
      "<float name=\"far_clip\" value=\"100\"/><transform name=\"to_world\"><scale x=\"1.5\" "
      "y=\"1.5\"/><lookat target=\"0, 0, 1\" origin=\"-5, 0, 3\" up=\"0, 0, 1\"/></transform>"
      "<film type=\"hdrfilm\"><integer name=\"width\" value=\"20\"/><integer name=\"height\" "
      "value=\"10\"/></film></sensor>"));
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->camera.projection, CameraDesc::Projection::kOrthographic);
  EXPECT_FLOAT_EQ(s->camera.near_clip, 1.0f);
  EXPECT_FLOAT_EQ(s->camera.far_clip, 100.0f);
  // The camera's x axis is scaled by 1.5 (the film spans 3 world units across).
  const Matrix4& m = s->camera.camera_to_world.matrix();
  const float x_len = std::sqrt(m.m[0][0] * m.m[0][0] + m.m[1][0] * m.m[1][0] +
                                m.m[2][0] * m.m[2][0]);
  EXPECT_NEAR(x_len, 1.5f, 1e-6f);
  EXPECT_NE(Error(Scene("<sensor type=\"orthographic\"><float name=\"fov\" value=\"30\"/>"
                        "</sensor>"))
                .find("fov"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<sensor type=\"orthographic\"><transform name=\"to_world\"><scale "
                        "x=\"0\"/></transform></sensor>"))
                .find("singular"),
            std::string::npos);
}

TEST_F(MitsubaLoader, FiltersSamplersAndFilm) {
  StatusOr<ptlab::Scene> s = Load(Scene(
      "<sensor type=\"perspective\"><sampler type=\"stratified\"><integer name=\"sample_count\" "
      "value=\"9\"/><integer name=\"seed\" value=\"3\"/></sampler><film type=\"hdrfilm\"><rfilter "
      "type=\"gaussian\"><float name=\"stddev\" value=\"0.25\"/></rfilter><string "
      "name=\"pixel_format\" value=\"rgb\"/></film></sensor>"));
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->sampler.type, SamplerType::kSobol);  // stratified: ptlab's best sampler
  EXPECT_EQ(s->sampler.sample_count, 9u);
  EXPECT_EQ(s->filter.type, FilterDesc::Type::kGaussian);
  EXPECT_FLOAT_EQ(s->filter.radius, 1.0f);  // 4 standard deviations, as Mitsuba
  EXPECT_EQ(s->camera.width, 768);          // Mitsuba's default film
  EXPECT_EQ(s->camera.height, 576);
  const std::string crop =
      Error(Scene("<sensor type=\"perspective\"><film type=\"hdrfilm\">\n"
                  "<integer name=\"crop_width\" value=\"4\"/></film>"
                  "</sensor>"));
  EXPECT_NE(crop.find(":3:1: unsupported: film \"hdrfilm\" property crop_width"), std::string::npos)
      << crop;
  EXPECT_NE(Error(Scene("<sensor type=\"perspective\"><film type=\"hdrfilm\">\n  <rfilter "
                        "type=\"lanczos\"/></film></sensor>"))
                .find(":3:3: unsupported: rfilter \"lanczos\""),
            std::string::npos);
}

TEST_F(MitsubaLoader, Integrators) {
  StatusOr<ptlab::Scene> s = Load(
      Scene("<integrator type=\"moment\"><integrator type=\"path\"><integer name=\"max_depth\" "
            "value=\"2\"/></integrator></integrator>"));
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->integrator.type, IntegratorDesc::Type::kPathMis);
  EXPECT_EQ(s->integrator.max_depth, 1);  // Mitsuba's 2 = direct light = ptlab's 1
  EXPECT_TRUE(s->integrator.power_heuristic);
  EXPECT_EQ(s->integrator.light_selection, LightSelection::kUniform);
  s = Load(Scene(""));  // no integrator: Mitsuba's path, unbounded
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->integrator.type, IntegratorDesc::Type::kPathMis);
  EXPECT_EQ(s->integrator.max_depth, -1);
  s =
      Load(Scene("<integrator type=\"direct\"><integer name=\"emitter_samples\" value=\"4\"/>"
                 "</integrator>"));
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->integrator.type, IntegratorDesc::Type::kDirectMis);
  EXPECT_EQ(s->integrator.light_samples, 4);
  s = Load(
      Scene("<integrator type=\"path\"><integer name=\"rr_depth\" value=\"3\"/></integrator>"));
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->load_warnings.size(), 1u);
  EXPECT_EQ(Error(Scene("<integrator type=\"volpath\"/>")),
            Path("scene.xml") + ":3:1: unsupported: integrator \"volpath\"");
  // ptracer: ptlab's particle tracer, max_depth counted as for path; hide_emitters only false.
  s = Load(Scene("<integrator type=\"ptracer\"><integer name=\"max_depth\" value=\"4\"/>"
                 "<integer name=\"samples_per_pass\" value=\"16\"/></integrator>"));
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->integrator.type, IntegratorDesc::Type::kPtracer);
  EXPECT_EQ(s->integrator.max_depth, 3);
  EXPECT_FALSE(Load(Scene("<integrator type=\"ptracer\"><integer name=\"max_depth\" "
                          "value=\"0\"/></integrator>"))
                   .ok());
  EXPECT_FALSE(Load(Scene("<integrator type=\"ptracer\"><boolean name=\"hide_emitters\" "
                          "value=\"true\"/></integrator>"))
                   .ok());
  // hide_emitters: kept for the integrators; refused with area emitters (Mitsuba's versions
  // differ there).
  s = Load(Scene("<integrator type=\"path\">\n  <boolean name=\"hide_emitters\" "
                 "value=\"true\"/></integrator><emitter type=\"constant\"/>"));
  ASSERT_TRUE(s.ok());
  EXPECT_TRUE(s->integrator.hide_emitters);
  EXPECT_NE(Error(Scene("<integrator type=\"direct\">\n  <boolean name=\"hide_emitters\" "
                        "value=\"true\"/></integrator><shape type=\"rectangle\"><emitter "
                        "type=\"area\"><rgb name=\"radiance\" value=\"1\"/></emitter></shape>"))
                .find(":3:1: unsupported: integrator \"direct\" (hide_emitters = true with "
                      "area emitters"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<integrator type=\"path\"><boolean name=\"strict_normals\" "
                        "value=\"true\"/></integrator>"))
                .find("unsupported: integrator \"path\" with strict_normals = true"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<integrator type=\"path\"><integer name=\"max_depth\" value=\"0\"/>"
                        "</integrator>"))
                .find("unsupported: integrator \"path\" with max_depth 0"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<integrator type=\"direct\"><integer name=\"emitter_samples\" "
                        "value=\"2\"/></integrator><emitter type=\"point\"/>"))
                .find(":3:1: unsupported: integrator \"direct\" (emitter_samples > 1 with point"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<integrator type=\"direct\"><integer name=\"bsdf_samples\" "
                        "value=\"2\"/></integrator>"))
                .find("unsupported: integrator \"direct\" with bsdf_samples != 1"),
            std::string::npos);
}

TEST_F(MitsubaLoader, Shapes) {
  Write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  StatusOr<ptlab::Scene> s = Load(Scene(
      "<shape type=\"rectangle\"/><shape type=\"cube\"/><shape type=\"disk\"/>"
      "<shape type=\"obj\"><string name=\"filename\" value=\"tri.obj\"/><boolean "
      "name=\"flip_normals\" value=\"true\"/></shape>"
      "<shape type=\"obj\"><string name=\"filename\" value=\"tri.obj\"/><boolean "
      "name=\"face_normals\" value=\"true\"/></shape>"
      "<shape type=\"sphere\"><float name=\"radius\" value=\"2\"/><transform name=\"to_world\">"
      "<scale value=\"0.5\"/><rotate x=\"1\" angle=\"30\"/><translate "
      "x=\"3\"/></transform></shape>"));
  ASSERT_TRUE(s.ok()) << s.status().message();
  ASSERT_EQ(s->meshes.size(), 5u);
  EXPECT_EQ(s->meshes.triangle_count[0], 2u);
  EXPECT_EQ(s->meshes.triangle_count[1], 12u);
  EXPECT_EQ(s->meshes.triangle_count[2], 1024u);  // the loader's fine disk
  EXPECT_TRUE(s->meshes.has_normals[3]);          // computed, as Mitsuba does for meshes without
  EXPECT_FALSE(s->meshes.has_normals[4]);         // face_normals: flat
  // flip_normals reverses the winding: the triangle's geometric normal is -z.
  const uint32_t t = s->meshes.first_triangle[3];
  const Vec3f n =
      Cross(s->triangles.V1(t) - s->triangles.V0(t), s->triangles.V2(t) - s->triangles.V0(t));
  EXPECT_LT(n.z, 0.0f);
  // The sphere stays analytic: centre (3, 0, 0), radius 1.
  ASSERT_EQ(s->spheres.size(), 1u);
  EXPECT_NEAR(s->spheres.radius[0], 1.0f, 1e-6f);
  EXPECT_NEAR(s->spheres.Center(0).x, 3.0f, 1e-6f);
  EXPECT_EQ(s->materials.diffuse.size(), 6u);  // Mitsuba's default diffuse for each
  EXPECT_EQ(
      Error(Scene("<shape type=\"sphere\"><transform name=\"to_world\"><scale x=\"2\"/>"
                  "</transform></shape>")),
      Path("scene.xml") +
          ":3:1: unsupported: shape \"sphere\" (a sphere under a non-uniform scale or shear)");
  EXPECT_EQ(Error(Scene("\n<shape type=\"bsplinecurve\"/>")),
            Path("scene.xml") + ":4:1: unsupported: shape \"bsplinecurve\"");
  // sdfgrid is read (tests/engine/io/mitsuba_sdf_grid_test.cpp); without a file it is an error.
  EXPECT_EQ(Error(Scene("\n<shape type=\"sdfgrid\"/>")),
            Path("scene.xml") +
                ":4:1: <shape type=\"sdfgrid\"> is missing the required property 'filename'");
  EXPECT_NE(Error(Scene("<shape type=\"ply\"><string name=\"filename\" value=\"a.ply\"/></shape>"))
                .find("a.ply"),
            std::string::npos);  // a missing mesh file is named
  EXPECT_NE(Error(Scene("<shape type=\"instance\"/>"))  // mitsuba_instances_test.cpp: more
                .find(":3:1: <shape type=\"instance\"> needs exactly one <ref id=...>"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<shape type=\"teapot\"/>")).find(":3:1: unknown shape type 'teapot'"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<shape type=\"cube\">\n  <float name=\"radius\" value=\"1\"/></shape>"))
                .find(":4:3: unknown property 'radius' for <shape type=\"cube\">; expected one "
                      "of: to_world, flip_normals"),
            std::string::npos);
}

TEST_F(MitsubaLoader, BsdfsAndValues) {
  StatusOr<ptlab::Scene> s = Load(Scene(
      "<shape type=\"cube\"><bsdf type=\"dielectric\"><string name=\"int_ior\" value=\"water\"/>"
      "<float name=\"ext_ior\" value=\"1.1\"/></bsdf></shape>"
      "<shape type=\"cube\"><bsdf type=\"diffuse\"><srgb name=\"reflectance\" value=\"#ff8000\"/>"
      "</bsdf></shape>"
      "<shape type=\"cube\"><bsdf type=\"diffuse\"><spectrum name=\"reflectance\" "
      "value=\"0.25\"/></bsdf></shape>"));
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_FLOAT_EQ(s->materials.dielectric.int_ior[0], 1.333f);
  EXPECT_FLOAT_EQ(s->materials.dielectric.ext_ior[0], 1.1f);
  EXPECT_EQ(s->materials.dielectric.Flags(0), kDielectricScaleRadiance);
  EXPECT_FLOAT_EQ(s->materials.diffuse.albedo_r[0], 1.0f);  // sRGB decoded
  EXPECT_NEAR(s->materials.diffuse.albedo_g[0], 0.2158605f, 1e-5f);
  EXPECT_FLOAT_EQ(s->materials.diffuse.albedo_b[0], 0.0f);
  EXPECT_FLOAT_EQ(s->materials.diffuse.albedo_g[1], 0.25f);  // uniform reflectance
  // roughplastic loads as a plastic row with a rough coating (its own tests:
  // tests/engine/io/mitsuba_coated_bsdfs_test.cpp).
  {
    const StatusOr<ptlab::Scene> rough =
        Load(Scene("<shape type=\"cube\">\n <bsdf type=\"roughplastic\"/></shape>"));
    ASSERT_TRUE(rough.ok()) << rough.status().message();
    EXPECT_EQ(rough->materials.plastic.size(), 1u);
  }
  // A diffuse reflectance may be a texture (docs/textures.md); other colours may not yet.
  EXPECT_NE(Error(Scene("<bsdf type=\"diffuse\">\n <texture name=\"reflectance\" "
                        "type=\"bitmap\"/></bsdf>"))
                .find(":4:2: <texture type=\"bitmap\"> is missing the required property "
                      "'filename'"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<bsdf type=\"dielectric\">\n <texture name=\"specular_reflectance\" "
                        "type=\"bitmap\"/></bsdf>"))
                .find(":4:2: unsupported: texture \"bitmap\" (as property "
                      "'specular_reflectance' of <bsdf type=\"dielectric\">)"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<bsdf type=\"dielectric\"><string name=\"int_ior\" value=\"glass\"/>"
                        "</bsdf>"))
                .find("unknown IOR name 'glass'; expected a number or one of vacuum"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"1, 2\"/></bsdf>"))
                .find("wrong number of components in '1, 2': expected 3 (or 1)"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"1.5\"/></bsdf>"))
                .find("is out of range; expected components in [0, 1]"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<bsdf type=\"diffuse\"><spectrum name=\"reflectance\" "
                        "value=\"500:1, 400:2\"/></bsdf>"))
                .find("spectrum wavelengths must increase"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<bsdf type=\"diffuse\" colour=\"red\"/>"))
                .find(":3:1: unknown attribute 'colour' on <bsdf>"),
            std::string::npos);
}

TEST_F(MitsubaLoader, Emitters) {
  StatusOr<ptlab::Scene> s = Load(
      Scene("<emitter type=\"point\"><rgb name=\"intensity\" value=\"2\"/><point name=\"position\" "
            "x=\"1\" y=\"2\" z=\"3\"/></emitter>"
            "<emitter type=\"point\"><transform name=\"to_world\"><translate z=\"10\"/></transform>"
            "</emitter>"
            "<emitter type=\"directional\"><vector name=\"direction\" value=\"0, 0, -2\"/><rgb "
            "name=\"irradiance\" value=\"3\"/></emitter>"
            "<emitter type=\"constant\"><spectrum name=\"radiance\" value=\"2\"/></emitter>"
            "<shape type=\"rectangle\"><emitter type=\"area\"><float name=\"radiance\" "
            "value=\"5\"/></emitter></shape>"));
  ASSERT_TRUE(s.ok()) << s.status().message();
  ASSERT_EQ(s->point_lights.size(), 2u);
  const float four_pi = 4.0f * std::numbers::pi_v<float>;
  EXPECT_FLOAT_EQ(s->point_lights.power[0].r, 2.0f * four_pi);  // Φ = 4π I
  EXPECT_FLOAT_EQ(s->point_lights.position[0].z, 3.0f);
  EXPECT_FLOAT_EQ(s->point_lights.power[1].g, four_pi);  // default intensity 1
  EXPECT_FLOAT_EQ(s->point_lights.position[1].z, 10.0f);
  ASSERT_EQ(s->directional_lights.size(), 1u);
  EXPECT_FLOAT_EQ(s->directional_lights.direction[0].z, -1.0f);
  EXPECT_FLOAT_EQ(s->directional_lights.radiance[0].b, 3.0f);
  // A uniform emission spectrum becomes the sRGB of an equal-energy white (Mitsuba's rgb rule).
  ASSERT_EQ(s->distant_disks.size(), 1u);
  EXPECT_NEAR(s->distant_disks.radiance[0].r, 2 * (3.240479 - 1.537150 - 0.498535), 1e-5);
  EXPECT_NEAR(s->distant_disks.radiance[0].b, 2 * (0.055648 - 0.204043 + 1.057311), 1e-5);
  ASSERT_EQ(s->area_lights.size(), 1u);
  EXPECT_FLOAT_EQ(s->area_lights.radiance[0].g, 5.0f);  // a float is grey
  EXPECT_EQ(s->emitters.size(), 5u);
  // spot and projector (their light: tests/engine/light/delta_light_test.cpp). A spot's
  // texture must be a spatially varying <texture> (bitmap or checkerboard), as in Mitsuba 3.
  EXPECT_NE(Error(Scene("\n\n<emitter type=\"spot\">\n<texture name=\"texture\" "
                        "type=\"mesh_attribute\"><string name=\"name\" value=\"vertex_color\"/>"
                        "</texture></emitter>"))
                .find(":6:1: unsupported: texture \"mesh_attribute\""),
            std::string::npos);
  EXPECT_NE(Error(Scene("<emitter type=\"spot\"><rgb name=\"texture\" value=\"1\"/></emitter>"))
                .find("must be a spatially varying <texture>"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<emitter type=\"spot\"><float name=\"cutoff_angle\" value=\"10\"/>"
                        "<float name=\"beam_width\" value=\"12\"/></emitter>"))
                .find("beam_width = 12 is out of range; expected [0, cutoff_angle = 10]"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<emitter type=\"spot\"><transform name=\"to_world\"><scale "
                        "value=\"2\"/></transform></emitter>"))
                .find("is not a rotation"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<emitter type=\"projector\"/>")).find("missing the required property 'irradiance'"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<emitter type=\"projector\">\n<texture name=\"irradiance\" "
                        "type=\"bitmap\"/></emitter>"))
                .find("missing the required property 'filename'"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<emitter type=\"projector\"><rgb name=\"irradiance\" value=\"1\"/>"
                        "<float name=\"fov\" value=\"180\"/></emitter>"))
                .find("fov = 180 is out of range; expected (0, 180)"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<emitter type=\"envmap\"><string name=\"filename\" value=\"sky.exr\"/>"
                        "</emitter>"))
                .find("file 'sky.exr' of <emitter type=\"envmap\"> not found"),
            std::string::npos);
  // sampling_weight only changes how often an emitter is picked: accepted, checked.
  EXPECT_TRUE(Load(Scene("<emitter type=\"constant\"><float name=\"sampling_weight\" "
                         "value=\"2\"/></emitter>"))
                  .ok());
  EXPECT_NE(Error(Scene("<emitter type=\"point\"><float name=\"sampling_weight\" "
                        "value=\"0\"/></emitter>"))
                .find("sampling_weight must be > 0"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<emitter type=\"area\"/>"))
                .find("an area emitter must be inside a "
                      "<shape>"),
            std::string::npos);
}

// Mitsuba 0.6 spellings: camelCase names (toWorld, intIOR, sampleCount, maxDepth), <srgb>.
TEST_F(MitsubaLoader, LegacyVersion06) {
  StatusOr<ptlab::Scene> s = Load(
      "<scene version=\"0.6.0\">\n"
      "<integrator type=\"path\"><integer name=\"maxDepth\" value=\"3\"/></integrator>\n"
      "<sensor type=\"perspective\"><float name=\"nearClip\" value=\"0.5\"/>"
      "<transform name=\"toWorld\"><lookat origin=\"0,0,-1\" target=\"0,0,0\" up=\"0,1,0\"/>"
      "</transform><sampler type=\"ldsampler\"><integer name=\"sampleCount\" value=\"12\"/>"
      "</sampler><film type=\"hdrfilm\"><boolean name=\"highQualityEdges\" value=\"false\"/>"
      "</film></sensor>\n"
      "<shape type=\"cube\"><bsdf type=\"dielectric\"><float name=\"intIOR\" value=\"1.7\"/>"
      "</bsdf><transform name=\"toWorld\"><translate x=\"4\"/></transform></shape>\n"
      "<shape type=\"cube\"><bsdf type=\"diffuse\"><srgb name=\"reflectance\" value=\"0.5\"/>"
      "</bsdf></shape>\n</scene>\n");
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->integrator.max_depth, 2);
  EXPECT_FLOAT_EQ(s->camera.near_clip, 0.5f);
  EXPECT_EQ(s->sampler.sample_count, 12u);
  EXPECT_FLOAT_EQ(s->materials.dielectric.int_ior[0], 1.7f);
  EXPECT_GT(s->triangles.V0(0).x, 2.0f);
  EXPECT_NEAR(s->materials.diffuse.albedo_r[0], 0.2140411f, 1e-5f);
}

TEST_F(MitsubaLoader, DocumentErrors) {
  EXPECT_EQ(Error("<scene version=\"3.0.0\">\n  <sensor type=\"perspective\">\n</scene>"),
            Path("scene.xml") + ":3:3: XML syntax error: Start-end tags mismatch");
  EXPECT_NE(Error("<scene version=\"3.0.0\"/>").find(":1:1: no <sensor> in the scene"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<medium type=\"homogeneous\"/>"))
                .find(":3:1: unsupported: medium "
                      "\"homogeneous\""),
            std::string::npos);
  EXPECT_NE(Error(Scene("<film type=\"hdrfilm\"/>"))
                .find("<film> is not allowed directly "
                      "inside <scene>"),
            std::string::npos);
  EXPECT_NE(Error(Scene("<widget/>")).find(":3:1: unknown tag <widget> inside <scene>"),
            std::string::npos);
  EXPECT_NE(Error(Scene("", "4.0.0")).find("is newer than 3.x"), std::string::npos);
}

// LoadSceneFile picks the Mitsuba loader for <scene version=...> and keeps Nori scenes Nori.
TEST_F(MitsubaLoader, SceneFileChoosesTheFormat) {
  const std::string mitsuba = Write("m.xml", Scene("<shape type=\"cube\"/>"));
  EXPECT_EQ(SceneFormatOf(mitsuba), SceneFormat::kMitsuba);
  StatusOr<ptlab::Scene> s = LoadSceneFile(mitsuba);
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->meshes.size(), 1u);
  const std::string nori =
      Write("n.xml", "<scene><integrator type=\"normals\"/><camera type=\"perspective\"/></scene>");
  EXPECT_EQ(SceneFormatOf(nori), SceneFormat::kNoriXml);
  EXPECT_TRUE(LoadSceneFile(nori).ok());
  // Mitsuba words in a Nori scene's comment or strings do not change its format.
  const std::string commented =
      Write("c.xml",
            "<scene><!-- <sensor> <default name=\"a\"/> --><integrator type=\"normals\"/>"
            "<camera type=\"perspective\"/></scene>");
  EXPECT_EQ(SceneFormatOf(commented), SceneFormat::kNoriXml);
  // A Mitsuba file without a version is still recognised by its tags, and told what is missing.
  const std::string unversioned = Write("u.xml", "<scene><sensor type=\"perspective\"/></scene>");
  EXPECT_EQ(SceneFormatOf(unversioned), SceneFormat::kMitsuba);
  StatusOr<ptlab::Scene> u = LoadSceneFile(unversioned);
  ASSERT_FALSE(u.ok());
  EXPECT_NE(u.status().message().find("is missing the attribute 'version'"), std::string::npos);
}

}  // namespace
}  // namespace ptlab

namespace ptlab {
namespace {

// Damaged scenes (cut short, or one byte replaced by a character that matters to XML, numbers
// or parameters) load or fail with a message naming the file: never a crash or a check failure.
TEST(MitsubaLoaderRobustness, DamagedScenesFailCleanly) {
  const std::string scene =
      "<scene version=\"3.0.0\">\n"
      "  <default name=\"spp\" value=\"4\"/>\n"
      "  <integrator type=\"moment\"><integrator type=\"path\"><integer name=\"max_depth\" "
      "value=\"3\"/></integrator></integrator>\n"
      "  <sensor type=\"thinlens\"><float name=\"aperture_radius\" value=\"0.1\"/>"
      "<float name=\"fov\" value=\"40\"/><string name=\"fov_axis\" value=\"y\"/>"
      "<transform name=\"to_world\"><lookat origin=\"0, -5, 1\" target=\"0, 0, 1\" up=\"0, 0, "
      "1\"/></transform><sampler type=\"independent\"><integer name=\"sample_count\" "
      "value=\"$spp\"/></sampler><film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/>"
      "<integer name=\"height\" value=\"6\"/><rfilter type=\"gaussian\"/></film></sensor>\n"
      "  <bsdf type=\"diffuse\" id=\"b\"><spectrum name=\"reflectance\" value=\"400:0.2, "
      "700:0.8\"/></bsdf>\n"
      "  <shape type=\"rectangle\"><ref id=\"b\"/><transform name=\"to_world\"><scale x=\"2\"/>"
      "<rotate z=\"1\" angle=\"30\"/><translate value=\"0 1 0\"/></transform></shape>\n"
      "  <shape type=\"sphere\"><float name=\"radius\" value=\"0.5\"/><bsdf "
      "type=\"dielectric\"><string name=\"int_ior\" value=\"bk7\"/></bsdf></shape>\n"
      "  <shape type=\"disk\"><emitter type=\"area\"><rgb name=\"radiance\" value=\"1, 2, "
      "3\"/></emitter></shape>\n"
      "  <emitter type=\"point\"><point name=\"position\" x=\"1\" y=\"2\" z=\"3\"/></emitter>\n"
      "  <emitter type=\"directional\"><vector name=\"direction\" value=\"0, 0, -1\"/></emitter>\n"
      "</scene>\n";
  const std::string base = fs::temp_directory_path().string();
  ASSERT_TRUE(LoadMitsubaSceneFromString(scene, base, "damaged.xml").ok());
  int loaded = 0, failed = 0;
  const auto check = [&](const std::string& text) {
    StatusOr<ptlab::Scene> s = LoadMitsubaSceneFromString(text, base, "damaged.xml");
    if (s.ok()) {
      ++loaded;
    } else {
      ++failed;
      EXPECT_EQ(s.status().message().rfind("damaged.xml", 0), 0u) << s.status().message();
    }
  };
  for (size_t i = 0; i < scene.size(); i += 7) check(scene.substr(0, i));
  for (size_t i = 0; i < scene.size(); i += 3)
    for (const char c : {'<', '"', '$', '-', '9', ','}) {
      std::string text = scene;
      text[i] = c;
      check(text);
    }
  EXPECT_GT(failed, 0);
  EXPECT_GT(loaded, 0);
}

}  // namespace
}  // namespace ptlab

namespace ptlab {
namespace {

// Mitsuba's own test meshes: the same rectangle as OBJ, PLY and serialized, whose files store the
// same texture coordinates. Mitsuba 3 (3.9.1, scalar_rgb, mi.traverse(...)['vertex_texcoords'])
// flips v of OBJ files by default, of PLY files only with flip_tex_coords, and reads serialized
// files (which store v flipped) as they are: its first vertex has uv (0.950589, 0.011584) from
// the OBJ and the serialized file, and (0.950589, 0.988416) from the PLY file.
TEST(MitsubaMeshFormats, TexCoordsOfObjPlyAndSerializedAsMitsuba3) {
  const std::string data = ptlab::test_data::Path("mitsuba3/tests/");
  PTLAB_REQUIRE_DATA(data + "ply/rectangle_normals_uv.ply");
  const std::string dir = (std::filesystem::temp_directory_path() / "ptlab_mitsuba_formats").string();
  std::filesystem::create_directories(dir);
  std::vector<std::vector<float>> uvs;
  for (const char* file : {"obj/rectangle_normals_uv.obj", "ply/rectangle_normals_uv.ply",
                           "serialized/rectangle_normals_uv.serialized"}) {
    const std::string type = std::filesystem::path(file).parent_path().string();
    const std::string xml = dir + "/" + type + ".xml";
    std::ofstream(xml) << "<scene version=\"3.0.0\"><sensor type=\"perspective\"><film "
                          "type=\"hdrfilm\"><integer name=\"width\" value=\"4\"/><integer "
                          "name=\"height\" value=\"4\"/></film></sensor><shape type=\""
                       << type << "\"><string name=\"filename\" value=\"" << data << file
                       << "\"/></shape></scene>\n";
    StatusOr<Scene> s = LoadMitsubaScene(xml, {});
    ASSERT_TRUE(s.ok()) << file << ": " << s.status().message();
    ASSERT_EQ(s->triangles.size(), 2u) << file;
    std::vector<float> uv;
    for (uint32_t t = 0; t < 2; ++t)
      for (uint32_t row : {s->shading.vertex0[t], s->shading.vertex1[t], s->shading.vertex2[t]}) {
        uv.push_back(s->vertices.u[row]);
        uv.push_back(s->vertices.v[row]);
      }
    uvs.push_back(uv);
  }
  std::filesystem::remove_all(dir);
  const float expected_v[3] = {1.0f - 0.988416f, 0.988416f, 1.0f - 0.988416f};
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(uvs[k][0], 0.950589f, 1e-6f) << k;
    EXPECT_NEAR(uvs[k][1], expected_v[k], 1e-6f) << k;
  }
  for (size_t i = 0; i < uvs[0].size(); ++i) EXPECT_NEAR(uvs[2][i], uvs[0][i], 1e-6f) << i;
}

}  // namespace
}  // namespace ptlab
