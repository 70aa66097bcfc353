// The Mitsuba loader's plastic, thindielectric, twosided and blendbsdf (matB).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/io/mitsuba_loader.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;

StatusOr<Scene> LoadBody(const std::string& name, const std::string& body) {
  const fs::path dir = fs::temp_directory_path() / ("ptlab_matb_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path p = dir / "scene.xml";
  std::ofstream(p) << "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><film "
                      "type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer "
                      "name=\"height\" value=\"8\"/></film></sensor>\n"
                   << body << "\n</scene>\n";
  StatusOr<Scene> s = LoadMitsubaScene(p.string(), LoadOptions{});
  fs::remove_all(dir);
  return s;
}

TEST(MitsubaCoatedBsdfs, PlasticThinDielectricTwoSidedBlend) {
  StatusOr<Scene> s = LoadBody(
      "all",
      "<shape type=\"cube\"><bsdf type=\"plastic\"><rgb name=\"diffuse_reflectance\" "
      "value=\"0.2, 0.4, 0.6\"/><string name=\"int_ior\" value=\"bk7\"/><boolean "
      "name=\"nonlinear\" value=\"true\"/></bsdf></shape>"
      "<shape type=\"cube\"><bsdf type=\"thindielectric\"><float name=\"int_ior\" "
      "value=\"1.33\"/></bsdf></shape>"
      "<shape type=\"cube\"><bsdf type=\"twosided\"><bsdf type=\"diffuse\"/></bsdf></shape>"
      "<shape type=\"cube\"><bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"0.3\"/>"
      "<bsdf type=\"diffuse\"/><bsdf type=\"plastic\"/></bsdf></shape>");
  ASSERT_TRUE(s.ok()) << s.status().message();
  const MaterialTables& m = s->materials;
  ASSERT_EQ(m.plastic.size(), 2u);
  EXPECT_NEAR(m.plastic.eta[0], 1.5046f / 1.000277f, 1e-6f);
  EXPECT_NEAR(m.plastic.eta[1], 1.49f / 1.000277f, 1e-6f);  // polypropylene in air
  ASSERT_EQ(m.thin_dielectric.size(), 1u);
  EXPECT_NEAR(m.thin_dielectric.eta[0], 1.33f / 1.000277f, 1e-6f);
  EXPECT_TRUE(m.two_sided.Of(MaterialRef::Make(MaterialTag::kDiffuse, 0)));
  ASSERT_EQ(m.blend.size(), 1u);
  EXPECT_FLOAT_EQ(m.blend.weight[0], 0.3f);
  EXPECT_EQ(m.blend.Second(0).tag(), MaterialTag::kPlastic);
  EXPECT_FALSE(m.two_sided.Of(m.blend.First(0)));
}

TEST(MitsubaCoatedBsdfs, ErrorsNameTheProblem) {
  const auto error = [](const std::string& body) {
    StatusOr<Scene> s = LoadBody("error", body);
    EXPECT_FALSE(s.ok());
    return s.ok() ? std::string() : s.status().message();
  };
  // mask: a textured weight is accepted; a broken texture in it is reported.
  EXPECT_NE(error("<bsdf type=\"blendbsdf\"><texture name=\"weight\" type=\"bitmap\"/>"
                  "<bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/></bsdf>")
                .find("filename"),
            std::string::npos);
  EXPECT_NE(error("<shape type=\"cube\"><bsdf type=\"blendbsdf\"><float name=\"weight\" "
                  "value=\"1.5\"/><bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/></bsdf></shape>")
                .find("weight must be in [0, 1]"),
            std::string::npos);
  EXPECT_NE(error("<shape type=\"cube\"><bsdf type=\"plastic\"><rgb "
                  "name=\"diffuse_reflectance\" value=\"2, 0, 0\"/></bsdf></shape>")
                .find("expected components in [0, 1]"),
            std::string::npos);
  EXPECT_NE(error("<shape type=\"cube\"><bsdf type=\"twosided\"><bsdf type=\"diffuse\"/><bsdf "
                  "type=\"diffuse\"/></bsdf></shape>")
                .find("unsupported: bsdf \"twosided\""),
            std::string::npos);
  EXPECT_NE(error("<shape type=\"cube\"><bsdf type=\"roughplastic\"><string "
                  "name=\"distribution\" value=\"phong\"/></bsdf></shape>")
                .find("expected beckmann or ggx"),
            std::string::npos);
}

}  // namespace
}  // namespace ptlab
