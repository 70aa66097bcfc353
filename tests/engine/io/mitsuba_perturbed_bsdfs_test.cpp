// normal: Mitsuba's normalmap and bumpmap through the loader (engine/io/mitsuba_perturbed_bsdfs.cpp):
// the nested row perturbed, the tangents built, rawconstant, and the errors for bad input.
#include <gtest/gtest.h>

#include <string>

#include "engine/io/mitsuba_loader.h"

namespace ptlab {
namespace {

// A scene with one cube of `bsdf`.
StatusOr<Scene> Load(const std::string& bsdf) {
  const std::string xml =
      "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><film type=\"hdrfilm\"><integer "
      "name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/></film></sensor>\n"
      "<shape type=\"cube\">" + bsdf + "</shape>\n</scene>\n";
  return LoadMitsubaSceneFromString(xml, ".", "perturbed.xml");
}

std::string Error(const std::string& bsdf) {
  StatusOr<Scene> s = Load(bsdf);
  EXPECT_FALSE(s.ok());
  return s.ok() ? "" : s.status().message();
}

const char* kRawConstant =
    "<texture name=\"normalmap\" type=\"rawconstant\"><vector name=\"value\" value=\"0.5, 0.5, "
    "1\"/></texture>";

TEST(MitsubaPerturbedBsdfs, NormalMapPerturbsTheNestedRow) {
  StatusOr<Scene> s = Load(std::string("<bsdf type=\"normalmap\">") + kRawConstant +
                           "<bsdf type=\"diffuse\"/></bsdf>");
  ASSERT_TRUE(s.ok()) << s.status().message();
  const ShadingPerturbations& p = s->materials.perturbation;
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(PerturbationKind(p.kind[0]), PerturbationKind::kNormalMap);
  EXPECT_EQ(p.Of(MaterialRef::Make(MaterialTag::kDiffuse, 0)), 0);
  // rawconstant: a constant texture of the value as is.
  const TextureTable& t = s->textures;
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t.data[t.offset[0] + 2], 1.0f);
  EXPECT_EQ(t.data[t.offset[0] + 5], 1.0f);
  EXPECT_EQ(t.data[t.offset[0] + 3], 0.5f);
  // One tangent row per triangle of the cube.
  EXPECT_EQ(p.dp_du_x.size(), s->triangles.size());
}

TEST(MitsubaPerturbedBsdfs, BumpMapTakesItsTextureUnderAnyName) {
  StatusOr<Scene> s = Load(
      "<bsdf type=\"bumpmap\"><float name=\"scale\" value=\"0.02\"/><texture name=\"height\" "
      "type=\"rawconstant\"><float name=\"value\" value=\"0.3\"/></texture><bsdf "
      "type=\"diffuse\"/></bsdf>");
  ASSERT_TRUE(s.ok()) << s.status().message();
  const ShadingPerturbations& p = s->materials.perturbation;
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(PerturbationKind(p.kind[0]), PerturbationKind::kBumpMap);
  EXPECT_EQ(p.scale[0], 0.02f);
}

TEST(MitsubaPerturbedBsdfs, ScenesWithoutMapsHaveNoPerturbationColumns) {
  StatusOr<Scene> s = Load("<bsdf type=\"diffuse\"/>");
  ASSERT_TRUE(s.ok());
  EXPECT_TRUE(s->materials.perturbation.empty());
  EXPECT_TRUE(s->materials.perturbation.dp_du_x.empty());
  for (const auto& c : s->materials.perturbation.by_tag) EXPECT_TRUE(c.empty());
}

TEST(MitsubaPerturbedBsdfs, BadInputIsAnError) {
  EXPECT_NE(Error(std::string("<bsdf type=\"normalmap\">") + kRawConstant + "</bsdf>")
                .find("expects one nested <bsdf>"),
            std::string::npos);
  EXPECT_NE(Error("<bsdf type=\"normalmap\"><bsdf type=\"diffuse\"/></bsdf>").find("normalmap"),
            std::string::npos);
  EXPECT_NE(Error(std::string("<bsdf type=\"normalmap\">") + kRawConstant +
                  "<boolean name=\"flip_invalid_normals\" value=\"false\"/><bsdf "
                  "type=\"diffuse\"/></bsdf>")
                .find("flip_invalid_normals"),
            std::string::npos);
  EXPECT_NE(Error("<bsdf type=\"bumpmap\"><bsdf type=\"diffuse\"/></bsdf>").find("texture"),
            std::string::npos);
  EXPECT_NE(Error("<bsdf type=\"bumpmap\"><texture name=\"a\" type=\"rawconstant\"><float "
                  "name=\"value\" value=\"1\"/></texture><texture name=\"b\" "
                  "type=\"rawconstant\"><float name=\"value\" value=\"1\"/></texture><bsdf "
                  "type=\"diffuse\"/></bsdf>")
                .find("one <texture>"),
            std::string::npos);
  // A map inside a blend: the blend's children see no shading point.
  EXPECT_NE(Error(std::string("<bsdf type=\"blendbsdf\"><bsdf type=\"normalmap\">") + kRawConstant +
                  "<bsdf type=\"diffuse\"/></bsdf><bsdf type=\"diffuse\"/></bsdf>")
                .find("unsupported"),
            std::string::npos);
}

}  // namespace
}  // namespace ptlab
