// Mitsuba's `mask` bsdf, a textured blendbsdf weight and a textured roughconductor or
// roughdielectric alpha in the loader (engine/io/mitsuba_mask_bsdf.cpp, mitsuba_bsdfs.cpp, mitsuba_microfacet_bsdfs.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/io/mitsuba_loader.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;

StatusOr<Scene> LoadBody(const std::string& name, const std::string& body) {
  const fs::path dir = fs::temp_directory_path() / ("ptlab_mask_" + name);
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

const char kChecker[] =
    "<texture name=\"%s\" type=\"checkerboard\"><float name=\"color0\" value=\"0.1\"/>"
    "<float name=\"color1\" value=\"0.4\"/></texture>";

std::string Checker(const char* name) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), kChecker, name);
  return buf;
}

TEST(MitsubaMaskBsdf, MaskBlendWeightAndRoughnessTexturesLoad) {
  StatusOr<Scene> s = LoadBody(
      "ok",
      "<shape type=\"cube\"><bsdf type=\"mask\"><float name=\"opacity\" value=\"0.25\"/>"
      "<bsdf type=\"twosided\"><bsdf type=\"diffuse\"/></bsdf></bsdf></shape>"
      "<shape type=\"cube\"><bsdf type=\"mask\">" + Checker("opacity") +
      "<bsdf type=\"diffuse\"/></bsdf></shape>"
      "<shape type=\"cube\"><bsdf type=\"mask\"><bsdf type=\"diffuse\"/></bsdf></shape>"
      "<shape type=\"cube\"><bsdf type=\"blendbsdf\">" + Checker("weight") +
      "<bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/></bsdf></shape>"
      "<shape type=\"cube\"><bsdf type=\"roughconductor\">" + Checker("alpha_u") +
      "<float name=\"alpha_v\" value=\"0.2\"/></bsdf></shape>");
  ASSERT_TRUE(s.ok()) << s.status().message();
  const MaterialTables& m = s->materials;
  ASSERT_EQ(m.mask.size(), 3u);
  EXPECT_EQ(m.mask.opacity[0], 0.25f);
  EXPECT_EQ(m.mask.opacity[2], 0.5f);  // Mitsuba's default
  ASSERT_EQ(m.mask.opacity_texture.size(), 3u);
  EXPECT_EQ(m.mask.opacity_texture[0], kNoTexture);
  EXPECT_NE(m.mask.opacity_texture[1], kNoTexture);
  EXPECT_EQ(m.mask.Nested(0).tag(), MaterialTag::kDiffuse);
  EXPECT_TRUE(m.two_sided.Of(m.mask.Nested(0)));
  ASSERT_EQ(m.blend.weight_texture.size(), 1u);
  EXPECT_NE(m.blend.weight_texture[0], kNoTexture);
  ASSERT_EQ(m.conductor.alpha_texture.size(), 1u);
  EXPECT_NE(m.conductor.alpha_texture[0], kNoTexture);
  EXPECT_EQ(m.conductor.alpha_v_texture[0], kNoTexture);
  EXPECT_EQ(m.conductor.alpha_v[0], 0.2f);
  // Three checkerboards, each read as a scalar (a copy with the colours swapped, Mitsuba's
  // eval_1), and the constant normal that gives the anisotropic conductor the uv-aligned frame.
  EXPECT_EQ(s->textures.size(), 7u);
  EXPECT_GE(m.perturbation.Of(MaterialRef::Make(MaterialTag::kConductor, 0)), 0);
  EXPECT_LT(m.perturbation.Of(m.mask.Nested(1)), 0);  // an isotropic row keeps its frame
}

// roughdielectric's alpha as a texture (Mitsuba 3 lets a texture drive it): both αu and αv
// read it, the row gets the uv-aligned frame as a textured rough conductor does.
TEST(MitsubaMaskBsdf, RoughDielectricTakesATexturedAlpha) {
  StatusOr<Scene> s = LoadBody("rd", "<shape type=\"cube\"><bsdf type=\"roughdielectric\">" +
                                         Checker("alpha") + "</bsdf></shape>");
  ASSERT_TRUE(s.ok()) << s.status().message();
  const RoughDielectricTable& t = s->materials.rough_dielectric;
  ASSERT_EQ(t.size(), 1u);
  ASSERT_TRUE(t.textured());
  EXPECT_NE(t.alpha_texture[0], kNoTexture);
  EXPECT_EQ(t.alpha_v_texture[0], t.alpha_texture[0]);
  EXPECT_GE(s->materials.perturbation.Of(MaterialRef::Make(MaterialTag::kRoughDielectric, 0)), 0);
}

TEST(MitsubaMaskBsdf, ErrorsNameTheProblem) {
  const auto error = [](const std::string& body) {
    StatusOr<Scene> s = LoadBody("error", body);
    EXPECT_FALSE(s.ok());
    return s.ok() ? std::string() : s.status().message();
  };
  EXPECT_NE(error("<shape type=\"cube\"><bsdf type=\"mask\"><float name=\"opacity\" "
                  "value=\"1.5\"/><bsdf type=\"diffuse\"/></bsdf></shape>")
                .find("opacity must be in [0, 1]"),
            std::string::npos);
  EXPECT_NE(error("<shape type=\"cube\"><bsdf type=\"mask\"/></shape>").find("one nested"),
            std::string::npos);
  EXPECT_NE(error("<shape type=\"cube\"><bsdf type=\"mask\"><bsdf type=\"diffuse\"/>"
                  "<bsdf type=\"diffuse\"/></bsdf></shape>")
                .find("one nested"),
            std::string::npos);
  EXPECT_NE(error("<shape type=\"cube\"><bsdf type=\"conductor\">" + Checker("alpha") +
                  "</bsdf></shape>")
                .find("unsupported"),
            std::string::npos);
}

}  // namespace
}  // namespace ptlab
