// normal: Mitsuba's normalmap and bumpmap through the loader (engine/io/mitsuba_perturbed_bsdfs.cpp):
// the nested row perturbed, the tangents built, rawconstant, and the errors for bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/core/frame.h"
#include "engine/io/mitsuba_loader.h"
#include "tests/test_data.h"

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

// principled's `anisotropic` orients its lobes by ∂p/∂u, as Mitsuba's shading frame does: an
// anisotropic row (constant or textured) gets the uv-aligned frame, an isotropic one keeps its
// own.
TEST(MitsubaPerturbedBsdfs, AnisotropicPrincipledGetsTheUvAlignedFrame) {
  for (const char* type : {"principled", "principledthin"}) {
    StatusOr<Scene> s = Load(std::string("<bsdf type=\"") + type +
                             "\"><float name=\"anisotropic\" value=\"0.7\"/></bsdf>");
    ASSERT_TRUE(s.ok()) << s.status().message();
    const MaterialTag tag = std::string(type) == "principled" ? MaterialTag::kPrincipled
                                                              : MaterialTag::kPrincipledThin;
    const ShadingPerturbations& p = s->materials.perturbation;
    ASSERT_EQ(p.size(), 1u) << type;
    EXPECT_EQ(p.Of(MaterialRef::Make(tag, 0)), 0) << type;
    EXPECT_EQ(PerturbationKind(p.kind[0]), PerturbationKind::kNormalMap);
    EXPECT_EQ(p.dp_du_x.size(), s->triangles.size());
  }
  StatusOr<Scene> textured = Load(
      "<bsdf type=\"principled\"><texture name=\"anisotropic\" type=\"checkerboard\"/></bsdf>");
  ASSERT_TRUE(textured.ok()) << textured.status().message();
  EXPECT_EQ(textured->materials.perturbation.size(), 1u);
  StatusOr<Scene> isotropic = Load("<bsdf type=\"principled\"><float name=\"roughness\" value=\"0.3\"/></bsdf>");
  ASSERT_TRUE(isotropic.ok()) << isotropic.status().message();
  EXPECT_TRUE(isotropic->materials.perturbation.empty());
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

// The suite's rotated uv sphere (meshes/sphere.obj): every triangle's tangents are finite,
// the poles included (measured: none of its 32,512 triangles has a zero-area uv triangle, its
// pole fans give each triangle its own u; the fallback is tested in SurfaceTangents.*).
TEST(MitsubaPerturbedBsdfs, SphereTangentsAreFinite) {
  const std::string path = std::string(PTLAB_SOURCE_DIR) +
                           "/../shared/data/mitsuba3/tests/scenes/bsdf_spheres/"
                           "test_normalmap_roughconductor_path.xml";
  PTLAB_REQUIRE_DATA(path);
  StatusOr<Scene> s = LoadMitsubaScene(path);
  ASSERT_TRUE(s.ok()) << s.status().message();
  const ShadingPerturbations& p = s->materials.perturbation;
  ASSERT_EQ(p.dp_du_x.size(), s->triangles.size());
  int fallback = 0;
  for (size_t i = 0; i < p.dp_du_x.size(); ++i) {
    const Vec3f du{p.dp_du_x[i], p.dp_du_y[i], p.dp_du_z[i]}, dv{p.dp_dv_x[i], p.dp_dv_y[i], p.dp_dv_z[i]};
    ASSERT_TRUE(std::isfinite(du.x) && std::isfinite(du.y) && std::isfinite(du.z) &&
                std::isfinite(dv.x) && std::isfinite(dv.y) && std::isfinite(dv.z)) << i;
    const Vec3f g = Cross(s->triangles.V1(i) - s->triangles.V0(i), s->triangles.V2(i) - s->triangles.V0(i));
    const Frame basis(g / Length(g));
    fallback += du == basis.s && dv == basis.t;
  }
  std::printf("sphere: %zu triangles, %d with a degenerate uv map\n", p.dp_du_x.size(), fallback);
}

}  // namespace
}  // namespace ptlab
