// Emission sampling (engine/light/emission.h): each emitter's sample agrees with EmissionPdf,
// and Monte Carlo integrals of 1/pdf recover the support's measure and the emitted power.
#include "engine/light/emission.h"

#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "engine/core/rng.h"
#include "engine/image/image.h"
#include "engine/light/environment_map.h"
#include "engine/light/distant_disk.h"
#include "engine/sampling/warp.h"
#include "engine/scene/scene.h"

namespace ptlab {
namespace {

constexpr int kSamples = 200000;

// Uniform numbers of a fixed stream.
struct Numbers {
  Pcg32 rng{17, 3};
  Vec2f Next2() {
    const float a = rng.NextFloat();
    return {a, rng.NextFloat()};
  }
};

// A 2 × 1 quad light (radiance 3) facing -y, a point light, a spot light, a directional light,
// a distant disk and an environment map.
Scene QuadLightScene() {
  Scene s;
  const MaterialRef m = s.materials.AddDiffuse({0.5f, 0.5f, 0.5f});
  // Two triangles of the quad x ∈ [-1, 1], z ∈ [0, 1] at y = 1, emitting towards -y.
  const Vec3f a{-1, 1, 0}, b{1, 1, 0}, c{1, 1, 1}, d{-1, 1, 1};
  s.meshes.first_triangle.push_back(0);
  s.meshes.triangle_count.push_back(2);
  for (const auto& t : {std::array<Vec3f, 3>{a, c, b}, std::array<Vec3f, 3>{a, d, c}}) {
    s.triangles.Append(t[0], t[1], t[2]);
    s.shading.mesh.push_back(0);
    s.shading.material.push_back(m);
    s.shading.vertex0.push_back(kNoVertex);
    s.shading.vertex1.push_back(kNoVertex);
    s.shading.vertex2.push_back(kNoVertex);
  }
  const EmitterRef e = EmitterRef::Make(EmitterTag::kArea, 0);
  s.meshes.material.push_back(m);
  s.meshes.emitter.push_back(e);
  s.meshes.has_normals.push_back(0);
  s.meshes.has_uvs.push_back(0);
  s.meshes.name.push_back("quad");
  s.area_lights.radiance.push_back({3, 3, 3});
  s.area_lights.mesh.push_back(0);
  s.emitters.push_back(e);
  s.point_lights.position.push_back({0.2f, 0.1f, 0.3f});
  s.point_lights.power.push_back({4, 4, 4});
  s.emitters.push_back(EmitterRef::Make(EmitterTag::kPoint, 0));
  s.spot_lights.position.push_back({0, 0, 0});
  s.spot_lights.axis.push_back(Normalize(Vec3f{0.3f, -1, 0.2f}));
  s.spot_lights.intensity.push_back({2, 2, 2});
  s.spot_lights.cos_half_angle.push_back(std::cos(0.5f));
  s.spot_lights.exponent.push_back(3.0f);
  // No linear ramp (COLLADA's spots): cos^exponent up to the cone's edge.
  s.spot_lights.cos_beam.push_back(s.spot_lights.cos_half_angle.back());
  s.spot_lights.cutoff.push_back(std::acos(s.spot_lights.cos_half_angle.back()));
  s.spot_lights.inv_transition.push_back(0.0f);
  s.emitters.push_back(EmitterRef::Make(EmitterTag::kSpot, 0));
  s.directional_lights.direction.push_back(Normalize(Vec3f{1, -2, 0.5f}));
  s.directional_lights.radiance.push_back({1, 1, 1});
  s.emitters.push_back(EmitterRef::Make(EmitterTag::kDirectional, 0));
  EXPECT_TRUE(AddDistantDisk({2, 2, 2}, 30.0f, Frame(Normalize(Vec3f{0, 1, 1})), "disk",
                             &s.distant_disks)
                  .ok());
  s.emitters.push_back(EmitterRef::Make(EmitterTag::kDistantDisk, 0));
  Image map(16, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) map.Set(x, y, Color3f{1.0f + x, 0.5f + y, 1.0f});
  EXPECT_TRUE(AddEnvironmentMap(map, EnvironmentMapDesc{}, "map", &s.environment_maps).ok());
  s.emitters.push_back(EmitterRef::Make(EmitterTag::kEnvironment, 0));
  FinalizeAreaLights(&s);
  return s;
}

TEST(Emission, SamplesAgreeWithEmissionPdf) {
  const Scene scene = QuadLightScene();
  const SceneSphere sphere = BoundingSphereOf(scene);
  Numbers u;
  for (const EmitterRef e : scene.emitters) {
    for (int i = 0; i < 2000; ++i) {
      EmissionSample es;
      if (!SampleEmission(scene, sphere, e, u.Next2(), u.Next2(), &es)) continue;
      ASSERT_TRUE(es.pdf_pos > 0 && es.pdf_dir > 0 && std::isfinite(es.pdf_dir)) << int(e.tag());
      EXPECT_NEAR(Length(es.w), 1.0f, 1e-5f);
      float pdf_pos, pdf_dir;
      EmissionPdf(scene, sphere, e, es.n, es.w, &pdf_pos, &pdf_dir);
      EXPECT_NEAR(pdf_pos, es.pdf_pos, 1e-5f * es.pdf_pos) << int(e.tag());
      EXPECT_NEAR(pdf_dir, es.pdf_dir, 2e-3f * es.pdf_dir) << int(e.tag());
      if (es.infinite) {
        // The origin lies on the disk one radius out, facing the scene.
        EXPECT_NEAR(Dot(es.p - sphere.center, -es.w), sphere.radius, 1e-3f * sphere.radius);
        EXPECT_LE(Length(es.p - sphere.center), sphere.radius * std::sqrt(2.0f) * 1.0001f);
      }
    }
  }
}

// E[Le cos / (pdf_pos pdf_dir)] is the emitted power: the quad's π A L (A = 2), the point
// light's 4π I = its power, the spot's ∫ I cos^k over its cone. Independent samples, 200k:
// the relative standard error is well under 1 %; the bound is 2 %.
TEST(Emission, EstimatesTheEmittedPower) {
  const Scene scene = QuadLightScene();
  const SceneSphere sphere = BoundingSphereOf(scene);
  const auto power = [&](EmitterRef e) {
    Numbers u;
    double sum = 0;
    for (int i = 0; i < kSamples; ++i) {
      EmissionSample es;
      if (!SampleEmission(scene, sphere, e, u.Next2(), u.Next2(), &es)) continue;
      const double cos = e.tag() == EmitterTag::kArea ? std::abs(Dot(es.n, es.w)) : 1.0;
      sum += double(es.radiance.r) * cos / (double(es.pdf_pos) * double(es.pdf_dir));
    }
    return sum / kSamples;
  };
  EXPECT_NEAR(power(scene.emitters[0]), 3.0 * 2.0 * 3.14159265, 0.02 * 3 * 2 * 3.14159265);
  EXPECT_NEAR(power(scene.emitters[1]), 4.0, 0.02 * 4.0);
  // Spot: 2π I ∫_{cos 0.5}^1 c^3 dc = 2π · 2 · (1 - cos⁴ 0.5) / 4.
  const double c4 = std::pow(std::cos(0.5), 4.0);
  const double spot = 2 * 3.14159265 * 2 * (1 - c4) / 4;
  EXPECT_NEAR(power(scene.emitters[2]), spot, 0.02 * spot);
  // Directional: E · π r² (what crosses the disk).
  const double disk = 3.14159265 * sphere.radius * sphere.radius;
  EXPECT_NEAR(power(scene.emitters[3]), disk, 1e-3 * disk);
  // Distant disk: L Ω π r².
  const double omega = 2 * 3.14159265 * (1 - std::cos(30.0 * 3.14159265 / 180));
  EXPECT_NEAR(power(scene.emitters[4]), 2 * omega * disk, 0.02 * 2 * omega * disk);
}

// The direction densities integrate to 1 over the sphere: E[pdf_dir / (1/4π)] for uniform
// directions (area light: its hemisphere; spot: its cone; infinite emitters: the map and the
// disk's cone). 400k directions; bound 3 % (the map's 1/sinθ poles make it the noisiest).
TEST(Emission, DirectionDensitiesIntegrateToOne) {
  const Scene scene = QuadLightScene();
  const SceneSphere sphere = BoundingSphereOf(scene);
  const Vec3f quad_normal{0, -1, 0};
  for (const size_t k : {size_t(0), size_t(1), size_t(2), size_t(4), size_t(5)}) {
    Numbers u;
    double sum = 0;
    constexpr int kN = 400000;
    for (int i = 0; i < kN; ++i) {
      const Vec3f w = SampleUniformSphere(u.Next2());
      float pdf_pos, pdf_dir;
      EmissionPdf(scene, sphere, scene.emitters[k], quad_normal, w, &pdf_pos, &pdf_dir);
      sum += double(pdf_dir) * 4.0 * 3.14159265358979;
    }
    EXPECT_NEAR(sum / kN, 1.0, 0.03) << "emitter " << k;
  }
}

TEST(Emission, BlackOrDegenerateEmittersSampleNothing) {
  Scene scene = QuadLightScene();
  scene.area_lights.radiance[0] = {0, 0, 0};
  const SceneSphere sphere = BoundingSphereOf(scene);
  EmissionSample es;
  EXPECT_FALSE(SampleEmission(scene, sphere, scene.emitters[0], {0.3f, 0.6f}, {0.2f, 0.9f}, &es));
  EXPECT_FALSE(SampleEmission(scene, sphere, EmitterRef::None(), {0.3f, 0.6f}, {0.2f, 0.9f}, &es));
  // Outside the spot's cone and behind the quad: density 0, never NaN.
  float pdf_pos, pdf_dir;
  EmissionPdf(scene, sphere, scene.emitters[2], {}, -scene.spot_lights.axis[0], &pdf_pos,
              &pdf_dir);
  EXPECT_EQ(pdf_dir, 0.0f);
  EmissionPdf(scene, sphere, scene.emitters[0], {0, -1, 0}, {0, 1, 0}, &pdf_pos, &pdf_dir);
  EXPECT_EQ(pdf_dir, 0.0f);
}

}  // namespace
}  // namespace ptlab
