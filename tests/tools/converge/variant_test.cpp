// Variants of `ptlab converge`: parsing, errors that name the key, and what they change.
#include "tools/converge/variant.h"

#include <gtest/gtest.h>

namespace ptlab {
namespace {

TEST(ConvergeVariant, ParsesSettingsInOrder) {
  StatusOr<Variant> v = ParseVariant("integrator=path_mis,heuristic=power,lightSamples=4");
  ASSERT_TRUE(v.ok()) << v.status().message();
  EXPECT_EQ(v->name, "integrator=path_mis,heuristic=power,lightSamples=4");
  ASSERT_EQ(v->settings.size(), 3u);
  EXPECT_EQ(v->settings[1].first, "heuristic");
  EXPECT_EQ(v->settings[1].second, "power");
  StatusOr<Variant> empty = ParseVariant("");
  ASSERT_TRUE(empty.ok());
  EXPECT_EQ(empty->name, "scene");
  EXPECT_TRUE(empty->settings.empty());
}

TEST(ConvergeVariant, RejectsUnknownKeysAndBadValuesNamingThem) {
  struct Case {
    const char* spec;
    const char* says;
  };
  for (const Case& c : {Case{"integratr=path_mis", "unknown key 'integratr'"},
                        Case{"integrator=path", "'path' is not one of"},
                        Case{"heuristic=max", "balance or power"},
                        Case{"lightSamples=0", "an integer in [1, 65536]"},
                        Case{"lightSamples=2x", "an integer in [1, 65536]"},
                        Case{"lightSamples=65537", "an integer in [1, 65536]"},
                        Case{"maxDepth=-2", "an integer in [-1, 1048576]"},
                        Case{"sampling=cosine", "uniform or importance"},
                        Case{"path=gpu", "packet or scalar"},
                        Case{"sampler=halton", "independent or sobol"},
                        Case{"lights=area", "uniform or power"},
                        Case{"triangles=solid", "area or solidAngle"},
                        Case{"integrator", "is not key=value"},
                        Case{"=3", "is not key=value"}}) {
    StatusOr<Variant> v = ParseVariant(c.spec);
    ASSERT_FALSE(v.ok()) << c.spec;
    EXPECT_NE(v.status().message().find(c.says), std::string::npos)
        << c.spec << ": " << v.status().message();
  }
}

TEST(ConvergeVariant, AppliesToTheSceneAndTheExecutionPath) {
  Scene scene;
  scene.integrator.type = IntegratorDesc::Type::kDirectMis;
  StatusOr<Variant> v =
      ParseVariant("integrator=path_ems,maxDepth=3,lightSamples=2,heuristic=power,path=scalar");
  ASSERT_TRUE(v.ok());
  VariantTarget target(&scene);
  ASSERT_TRUE(ApplyVariant(*v, &target).ok());
  EXPECT_EQ(scene.integrator.type, IntegratorDesc::Type::kPathEms);
  EXPECT_EQ(scene.integrator.max_depth, 3);
  EXPECT_EQ(scene.integrator.light_samples, 2);
  EXPECT_TRUE(scene.integrator.power_heuristic);
  EXPECT_TRUE(target.scalar);
}

TEST(ConvergeVariant, SamplerLightSelectionAndTriangleSampling) {
  Scene scene;
  StatusOr<Variant> v = ParseVariant("sampler=independent,lights=uniform,triangles=area");
  ASSERT_TRUE(v.ok());
  VariantTarget target(&scene);
  ASSERT_TRUE(ApplyVariant(*v, &target).ok());
  EXPECT_EQ(scene.sampler.type, SamplerType::kIndependent);
  EXPECT_EQ(scene.integrator.light_selection, LightSelection::kUniform);
  EXPECT_EQ(scene.integrator.triangle_sampling, TriangleSampling::kArea);
  v = ParseVariant("sampler=sobol,lights=power,triangles=solidAngle");
  ASSERT_TRUE(v.ok());
  ASSERT_TRUE(ApplyVariant(*v, &target).ok());
  EXPECT_EQ(scene.sampler.type, SamplerType::kSobol);
  EXPECT_EQ(scene.integrator.light_selection, LightSelection::kPower);
  EXPECT_EQ(scene.integrator.triangle_sampling, TriangleSampling::kSolidAngle);
}

TEST(ConvergeVariant, ImportanceSamplingNeedsTheMapsDistribution) {
  Scene scene;
  scene.environment_maps.sampling = {EnvironmentSampling::kImportance,
                                     EnvironmentSampling::kUniform};
  scene.environment_maps.width = {1, 1};
  VariantTarget target(&scene);
  StatusOr<Variant> importance = ParseVariant("sampling=importance");
  const Status st = ApplyVariant(*importance, &target);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("environment map 1"), std::string::npos) << st.message();
  StatusOr<Variant> uniform = ParseVariant("sampling=uniform");
  ASSERT_TRUE(ApplyVariant(*uniform, &target).ok());
  EXPECT_EQ(scene.environment_maps.sampling[0], EnvironmentSampling::kUniform);
}

TEST(ConvergeVariant, IntegratorNamesRoundTrip) {
  for (int i = 0; i <= int(IntegratorDesc::Type::kPtracer); ++i) {
    IntegratorDesc::Type t{};
    ASSERT_TRUE(IntegratorTypeFromName(IntegratorTypeName(IntegratorDesc::Type(i)), &t));
    EXPECT_EQ(int(t), i);
  }
  IntegratorDesc::Type t{};
  EXPECT_FALSE(IntegratorTypeFromName("path", &t));
}

}  // namespace
}  // namespace ptlab
