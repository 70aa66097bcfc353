// Emitter selection: power-proportional probabilities (area, point, infinite emitters), the
// uniform rule, the XML and variant names, and the pick agreeing with its pmf.
#include "engine/light/light_selection.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/io/xml_loader.h"

namespace ptlab {
namespace {

// Two quads (areas 1 and 4, radiances 2 and 1) and a point light of power 3π.
Scene TwoQuadsAndAPoint(const std::string& integrator_props) {
  const std::string xml = R"(<scene>
    <integrator type="path_mis">)" + integrator_props + R"(</integrator>
    <camera type="perspective"><integer name="width" value="8"/><integer name="height" value="8"/></camera>
    <shape type="rectangle">
      <transform name="toWorld"><scale value="0.5, 0.5, 1"/><translate value="0, 0, 3"/></transform>
      <emitter type="area"><color name="radiance" value="2, 2, 2"/></emitter>
    </shape>
    <shape type="rectangle">
      <transform name="toWorld"><translate value="0, 0, 5"/></transform>
      <emitter type="area"><color name="radiance" value="1, 1, 1"/></emitter>
    </shape>
    <emitter type="point"><point name="position" value="0, 1, 0"/><color name="power" value="9.42477796, 9.42477796, 9.42477796"/></emitter>
  </scene>)";
  StatusOr<Scene> scene = LoadSceneFromString(xml, ".", "selection.xml");
  EXPECT_TRUE(scene.ok()) << scene.status().message();
  return scene.ok() ? std::move(*scene) : Scene{};
}

TEST(LightSelection, PowerIsFluxLuminance) {
  const Scene scene = TwoQuadsAndAPoint("");
  ASSERT_EQ(scene.emitters.size(), 3u);
  const EmitterSelectionTable& t = scene.emitter_selection;
  ASSERT_EQ(t.size(), 3u);
  // Φ = π A L for a one-sided diffuse emitter: 2π and 4π; the point light's power 3π.
  const double pi = 3.14159265358979;
  EXPECT_NEAR(t.power[0], 2 * pi, 1e-4);
  EXPECT_NEAR(t.power[1], 4 * pi, 1e-4);
  EXPECT_NEAR(t.power[2], 3 * pi, 1e-4);
  EXPECT_NEAR(t.pmf[0], 2.0 / 9.0, 1e-6);
  EXPECT_NEAR(t.pmf[1], 4.0 / 9.0, 1e-6);
  EXPECT_NEAR(t.pmf[2], 3.0 / 9.0, 1e-6);
  EXPECT_EQ(scene.integrator.light_selection, LightSelection::kPower);  // the default
}

// The power of delta lights: a directional light's power is its
// radiance over the disk of the scene's bounding sphere (pbrt's DistantLight::Phi), a spot's
// its intensity integrated over the cone, 2π (1 - cos^(e+1) θh) / (e + 1) · I.
TEST(LightSelection, DirectionalAndSpotPower) {
  Scene scene;
  scene.triangles.Append({0, 0, 0}, {3, 0, 0}, {0, 4, 0});  // bounding box diagonal 5
  scene.directional_lights.direction.push_back({0, -1, 0});
  scene.directional_lights.radiance.push_back({2, 2, 2});
  scene.spot_lights.position.push_back({0, 1, 0});
  scene.spot_lights.axis.push_back({0, -1, 0});
  scene.spot_lights.intensity.push_back({3, 3, 3});
  scene.spot_lights.cos_half_angle.push_back(0.5f);
  scene.spot_lights.exponent.push_back(2.0f);
  scene.spot_lights.cos_beam.push_back(0.5f);  // no ramp (COLLADA's spots)
  scene.spot_lights.cutoff.push_back(std::acos(0.5f));
  scene.spot_lights.inv_transition.push_back(0.0f);
  scene.spot_lights.position.push_back({0, 1, 0});
  scene.spot_lights.axis.push_back({0, -1, 0});
  scene.spot_lights.intensity.push_back({1, 1, 1});
  scene.spot_lights.cos_half_angle.push_back(0.0f);  // 180°, exponent 0: a hemisphere
  scene.spot_lights.exponent.push_back(0.0f);
  scene.spot_lights.cos_beam.push_back(0.0f);
  scene.spot_lights.cutoff.push_back(0.5f * 3.14159265f);
  scene.spot_lights.inv_transition.push_back(0.0f);
  scene.emitters = {EmitterRef::Make(EmitterTag::kSpot, 1),
                    EmitterRef::Make(EmitterTag::kDirectional, 0),
                    EmitterRef::Make(EmitterTag::kSpot, 0)};
  BuildEmitterSelection(&scene);
  const EmitterSelectionTable& t = scene.emitter_selection;
  ASSERT_EQ(t.size(), 3u);
  const double pi = 3.14159265358979;
  EXPECT_NEAR(t.power[0], 2 * pi, 1e-5);
  EXPECT_NEAR(t.power[1], pi * 2.5 * 2.5 * 2, 1e-4);
  EXPECT_NEAR(t.power[2], 2 * pi * (1 - 0.125) / 3 * 3, 1e-5);
  EXPECT_NEAR(EmitterSelectionPmf(scene, EmitterRef::Make(EmitterTag::kSpot, 0)),
              t.power[2] / (t.power[0] + t.power[1] + t.power[2]), 1e-6);
  EXPECT_EQ(t.slot_directional[0], 1u);
  EXPECT_EQ(t.slot_spot[1], 0u);
}

TEST(LightSelection, PickFrequenciesMatchThePmf) {
  for (const char* rule : {"uniform", "power"}) {
    const Scene scene =
        TwoQuadsAndAPoint(std::string(R"(<string name="lightSelection" value=")") + rule + R"("/>)");
    const int n = 90000;
    std::vector<int> count(3, 0);
    for (int i = 0; i < n; ++i) {
      float pmf = 0;
      const EmitterRef e = SelectEmitter(scene, (float(i) + 0.5f) / float(n), &pmf);
      EXPECT_EQ(pmf, EmitterSelectionPmf(scene, e));
      for (size_t k = 0; k < 3; ++k)
        if (scene.emitters[k] == e) ++count[k];
    }
    for (size_t k = 0; k < 3; ++k)
      EXPECT_NEAR(double(count[k]) / n, EmitterSelectionPmf(scene, scene.emitters[k]), 1e-4)
          << rule << " emitter " << k;
  }
}

// The remapped number (the Sobol' sampler's folded pick): within each emitter's interval of
// [0, 1) it runs over [0, 1) uniformly, in order, so a stratified set of u gives each emitter a
// stratified set of its own; the extreme u stay in [0, 1).
TEST(LightSelection, RemappedNumberIsUniformOverEachEmittersInterval) {
  for (const char* rule : {"uniform", "power"}) {
    const Scene scene =
        TwoQuadsAndAPoint(std::string(R"(<string name="lightSelection" value=")") + rule + R"("/>)");
    const int n = 90000;
    std::vector<std::vector<float>> remapped(3);
    for (int i = 0; i < n; ++i) {
      float pmf = 0, r = -1;
      const EmitterRef e = SelectEmitter(scene, (float(i) + 0.5f) / float(n), &pmf, &r);
      float pmf_alone = 0;
      ASSERT_TRUE(e == SelectEmitter(scene, (float(i) + 0.5f) / float(n), &pmf_alone));
      ASSERT_EQ(pmf, pmf_alone);
      for (size_t k = 0; k < 3; ++k)
        if (scene.emitters[k] == e) remapped[k].push_back(r);
    }
    for (size_t k = 0; k < 3; ++k) {
      const std::vector<float>& r = remapped[k];
      ASSERT_GT(r.size(), 100u) << rule << " emitter " << k;
      // Increasing, and the j-th of m lies near the middle of the j-th of m equal strata.
      for (size_t j = 0; j < r.size(); ++j) {
        if (j > 0) {
          ASSERT_GT(r[j], r[j - 1]) << rule << " emitter " << k << " j " << j;
        }
        ASSERT_NEAR(r[j], (float(j) + 0.5f) / float(r.size()), 2.0f / float(r.size()))
            << rule << " emitter " << k << " j " << j;
      }
    }
    for (float u : {0.0f, 1e-7f, 0.5f, 0x1.fffffep-1f}) {
      float pmf = 0, r = -1;
      SelectEmitter(scene, u, &pmf, &r);
      EXPECT_TRUE(r >= 0.0f && r < 1.0f) << rule << " u " << u << " -> " << r;
    }
  }
}

TEST(LightSelection, ZeroPowerEmittersAreNeverPicked) {
  Scene scene = TwoQuadsAndAPoint("");
  scene.area_lights.radiance[0] = {0, 0, 0};
  BuildEmitterSelection(&scene);
  EXPECT_EQ(scene.emitter_selection.pmf[0], 0.0f);
  for (float u : {0.0f, 1e-7f, 0.3f, 0.9999999f}) {
    float pmf = 0;
    const EmitterRef e = SelectEmitter(scene, u, &pmf);
    EXPECT_FALSE(e == scene.emitters[0]) << u;
    EXPECT_GT(pmf, 0.0f);
  }
  // All black: uniform, so that nothing divides by zero.
  scene.area_lights.radiance[1] = {0, 0, 0};
  scene.point_lights.power[0] = {0, 0, 0};
  BuildEmitterSelection(&scene);
  for (float p : scene.emitter_selection.pmf) EXPECT_NEAR(p, 1.0f / 3.0f, 1e-6f);
}

TEST(LightSelection, BadXmlValuesAreErrors) {
  const std::string xml = R"(<scene><integrator type="path_mis"><string name="lightSelection" value="area"/></integrator></scene>)";
  StatusOr<Scene> s = LoadSceneFromString(xml, ".", "bad.xml");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.status().message().find("expected uniform or power"), std::string::npos)
      << s.status().message();
  const std::string xml2 = R"(<scene><integrator type="path_mis"><string name="triangleSampling" value="x"/></integrator></scene>)";
  s = LoadSceneFromString(xml2, ".", "bad.xml");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.status().message().find("expected area or solidAngle"), std::string::npos)
      << s.status().message();
}

}  // namespace
}  // namespace ptlab
