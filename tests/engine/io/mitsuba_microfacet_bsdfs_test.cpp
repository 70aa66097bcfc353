// Mitsuba's conductor, roughconductor and roughdielectric through the loader: parameters,
// defaults, and the errors for bad input.
#include "engine/io/mitsuba_microfacet_bsdfs.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/io/mitsuba_loader.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;

class MitsubaMicrofacetBsdfs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("ptlab_mitsuba_mf_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A scene with one cube of `bsdf`.
  StatusOr<ptlab::Scene> Load(const std::string& bsdf) {
    const fs::path p = dir_ / "scene.xml";
    std::ofstream(p) << "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><film "
                        "type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer "
                        "name=\"height\" value=\"8\"/></film></sensor>\n<shape type=\"cube\">"
                     << bsdf << "</shape>\n</scene>\n";
    return LoadMitsubaScene(p.string());
  }
  std::string Error(const std::string& bsdf) {
    StatusOr<ptlab::Scene> s = Load(bsdf);
    EXPECT_FALSE(s.ok());
    return s.ok() ? "" : s.status().message();
  }
  fs::path dir_;
};

TEST_F(MitsubaMicrofacetBsdfs, RoughConductorParameters) {
  StatusOr<ptlab::Scene> s = Load(
      "<bsdf type=\"roughconductor\"><string name=\"distribution\" value=\"GGX\"/>"
      "<float name=\"alpha_u\" value=\"0.05\"/><float name=\"alpha_v\" value=\"0.3\"/>"
      "<boolean name=\"sample_visible\" value=\"false\"/>"
      "<rgb name=\"eta\" value=\"0.2, 0.9, 1.1\"/><rgb name=\"k\" value=\"3.9, 2.4, 2.1\"/>"
      "<rgb name=\"specular_reflectance\" value=\"0.5, 1, 1\"/></bsdf>");
  ASSERT_TRUE(s.ok()) << s.status().message();
  const ConductorTable& t = s->materials.conductor;
  ASSERT_EQ(t.size(), 1u);
  ASSERT_TRUE(t.microfacet());
  EXPECT_FLOAT_EQ(t.alpha[0], 0.05f);
  EXPECT_FLOAT_EQ(t.alpha_v[0], 0.3f);
  EXPECT_EQ(t.flags[0], kMicrofacetGgx);  // no visible-normal sampling
  EXPECT_FLOAT_EQ(t.eta_g[0], 0.9f);
  EXPECT_FLOAT_EQ(t.k_b[0], 2.1f);
  EXPECT_FLOAT_EQ(t.specular_r[0], 0.5f);
  // Mitsuba's defaults: Beckmann, α = 0.1, visible normals, material "none" (η 0, κ 1).
  s = Load("<bsdf type=\"roughconductor\"/>");
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_FLOAT_EQ(s->materials.conductor.alpha[0], 0.1f);
  EXPECT_FLOAT_EQ(s->materials.conductor.alpha_v[0], 0.1f);
  EXPECT_EQ(s->materials.conductor.flags[0], kMicrofacetSampleVisible);
  EXPECT_EQ(s->materials.conductor.eta_r[0], 0.0f);
  EXPECT_EQ(s->materials.conductor.k_r[0], 1.0f);
}

TEST_F(MitsubaMicrofacetBsdfs, SmoothConductorAndRoughDielectric) {
  StatusOr<ptlab::Scene> s =
      Load("<bsdf type=\"conductor\"><spectrum name=\"eta\" value=\"0.789\"/>"
           "<spectrum name=\"k\" value=\"6.15\"/></bsdf>");
  ASSERT_TRUE(s.ok()) << s.status().message();
  ASSERT_TRUE(s->materials.mirror.fresnel());
  EXPECT_FLOAT_EQ(s->materials.mirror.eta_b[0], 0.789f);
  EXPECT_FLOAT_EQ(s->materials.mirror.k_g[0], 6.15f);
  EXPECT_EQ(s->materials.mirror.reflectance_r[0], 1.0f);
  s = Load("<bsdf type=\"roughdielectric\"><string name=\"distribution\" value=\"beckmann\"/>"
           "<float name=\"alpha\" value=\"0.02\"/><string name=\"int_ior\" value=\"bk7\"/>"
           "<string name=\"ext_ior\" value=\"air\"/></bsdf>");
  ASSERT_TRUE(s.ok()) << s.status().message();
  const RoughDielectricTable& d = s->materials.rough_dielectric;
  ASSERT_EQ(d.size(), 1u);
  EXPECT_FLOAT_EQ(d.alpha_u[0], 0.02f);
  EXPECT_FLOAT_EQ(d.alpha_v[0], 0.02f);
  EXPECT_EQ(d.flags[0], kMicrofacetSampleVisible);
  EXPECT_FLOAT_EQ(d.int_ior[0], 1.5046f);
  EXPECT_FLOAT_EQ(d.ext_ior[0], 1.000277f);
}

TEST_F(MitsubaMicrofacetBsdfs, BadInputNamesWhatIsAccepted) {
  EXPECT_NE(Error("<bsdf type=\"roughconductor\"><string name=\"distribution\" value=\"phong\"/>"
                  "</bsdf>")
                .find("unknown distribution 'phong'; expected beckmann or ggx"),
            std::string::npos);
  EXPECT_NE(Error("<bsdf type=\"roughconductor\"><float name=\"alpha\" value=\"0.1\"/>"
                  "<float name=\"alpha_u\" value=\"0.1\"/><float name=\"alpha_v\" value=\"0.1\"/>"
                  "</bsdf>")
                .find("give either 'alpha' or 'alpha_u' and 'alpha_v', not both"),
            std::string::npos);
  EXPECT_NE(Error("<bsdf type=\"roughdielectric\"><float name=\"alpha_u\" value=\"0.1\"/></bsdf>")
                .find("both 'alpha_u' and 'alpha_v' are needed"),
            std::string::npos);
  EXPECT_NE(Error("<bsdf type=\"roughdielectric\"><float name=\"alpha\" value=\"-1\"/></bsdf>")
                .find("is out of range; expected a finite value >= 0"),
            std::string::npos);
  EXPECT_NE(Error("<bsdf type=\"conductor\"><string name=\"material\" value=\"Au\"/>"
                  "<rgb name=\"eta\" value=\"1, 1, 1\"/></bsdf>")
                .find("give either string 'material' or 'eta' and 'k', not both"),
            std::string::npos);
  EXPECT_NE(Error("<bsdf type=\"conductor\"><string name=\"material\" value=\"Unobtainium\"/>"
                  "</bsdf>")
                .find("unknown conductor 'Unobtainium'"),
            std::string::npos);
  // The error names the file, line and column (the bsdf is on line 3).
  EXPECT_NE(Error("<bsdf type=\"roughdielectric\"><string name=\"int_ior\" value=\"glass\"/>"
                  "</bsdf>")
                .find("scene.xml:3:49: unknown IOR name 'glass'"),
            std::string::npos);
}

}  // namespace
}  // namespace ptlab
