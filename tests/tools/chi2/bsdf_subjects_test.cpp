// The BSDF subjects of the chi-square lab: their albedo, the registry, and hard roughness.
#include "tools/chi2/bsdf_subjects.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/bsdf/conductor.h"
#include "engine/core/rng.h"
#include "tools/chi2/chi2.h"

namespace ptlab {
namespace {

const Chi2Registry& Registry() {
  static const Chi2Registry registry = [] {
    Chi2Registry r;
    RegisterBsdfSubjects(&r);
    return r;
  }();
  return registry;
}

// At normal incidence every half vector within 45° reflects above the horizon: tan θmax = 1.
TEST(BsdfSubjects, AlbedoAtNormalIncidenceIsClosedForm) {
  for (float alpha : {0.1f, 0.5f, 1.0f, 2.0f}) {
    const double a = alpha;
    EXPECT_NEAR(BeckmannReflectionAlbedo(alpha, 1.0f), -std::expm1(-1.0 / (a * a)), 1e-12);
  }
  EXPECT_EQ(BeckmannReflectionAlbedo(1e-4f, 0.5f), 1.0);
}

// The escape rate of ConductorSample agrees with the albedo within 5 standard deviations.
TEST(BsdfSubjects, AlbedoMatchesTheSamplersEscapeRate) {
  Pcg32 rng(3, 5);
  for (float alpha : {0.2f, 1.0f}) {
    for (float theta : {30.0f, 60.0f, 85.0f}) {
      const Vec3f wo = Chi2Direction(theta, 20.0f);
      ConductorParams params;
      params.alpha = alpha;
      params.eta = {1.5f, 1.5f, 1.5f};
      params.k = {3.0f, 3.0f, 3.0f};
      constexpr int kN = 200000;
      int kept = 0;
      for (int i = 0; i < kN; ++i) {
        BsdfSample s;
        kept += ConductorSample(params, wo, {rng.NextFloat(), rng.NextFloat()}, &s) ? 1 : 0;
      }
      const double a = BeckmannReflectionAlbedo(alpha, wo.z);
      const double sigma = std::sqrt(a * (1 - a) / kN);
      EXPECT_NEAR(double(kept) / kN, a, 5 * sigma + 1e-6) << "alpha=" << alpha << " θ=" << theta;
    }
  }
}

TEST(BsdfSubjects, RegistersEveryModelScalarAndSimdAndTheBrokenVariants) {
  for (const char* name :
       {"bsdf/diffuse_t85", "bsdf/conductor_a0p005_t0", "bsdf/conductor_a1_t85",
        "bsdf/conductor_a0p0001_t60", "bsdf/conductor_a2_t85", "bsdf/rough_plastic_a0p005_t85",
        "bsdf/rough_plastic_a1_t0", "simd/beckmann_reflection_a0p05_t60", "simd/shade_diffuse_t60",
        "simd/shade_conductor_a0p5_t85", "simd/shade_rough_plastic_a0p05_t60"}) {
    const Chi2Subject* s = Registry().Find(name);
    ASSERT_NE(s, nullptr) << name;
    EXPECT_EQ(s->expect, Chi2Expect::kPass);
  }
  for (const char* name : {"broken/conductor_pdf_no_reflection_jacobian",
                           "broken/rough_plastic_pdf_swapped_weights"}) {
    const Chi2Subject* s = Registry().Find(name);
    ASSERT_NE(s, nullptr) << name;
    EXPECT_EQ(s->expect, Chi2Expect::kFail);
  }
  // Narrow lobes go to the zoomed disk, wide ones stay on the hemisphere.
  EXPECT_EQ(Registry().Find("bsdf/conductor_a0p2_t30")->domain.kind, Chi2DomainKind::kDisk);
  EXPECT_EQ(Registry().Find("bsdf/conductor_a0p5_t30")->domain.kind, Chi2DomainKind::kHemisphere);
  EXPECT_EQ(Registry().Find("bsdf/rough_plastic_a0p005_t0")->uniform_dims, 3);
}

// Roughness at and beyond the clamp limits and grazing incidence: every sample any path draws
// is finite and in the domain, and the subject's pdf there is finite and positive. (The χ²
// subjects at α = 1e-4 and 2 cover the distributions where a grid resolves them.)
TEST(BsdfSubjects, HardRoughnessSamplesAreFiniteWithPositivePdf) {
  struct Case {
    Chi2BsdfModel model;
    Chi2BsdfPath path;
  };
  const Case cases[] = {{Chi2BsdfModel::kConductor, Chi2BsdfPath::kScalar},
                        {Chi2BsdfModel::kConductor, Chi2BsdfPath::kSimd},
                        {Chi2BsdfModel::kRoughPlastic, Chi2BsdfPath::kScalar},
                        {Chi2BsdfModel::kRoughPlastic, Chi2BsdfPath::kSimd},
                        {Chi2BsdfModel::kBeckmannReflection, Chi2BsdfPath::kScalar},
                        {Chi2BsdfModel::kBeckmannReflection, Chi2BsdfPath::kSimd}};
  Pcg32 rng(11, 2);
  constexpr int kN = 1024;
  std::vector<float> u1(kN);
  std::vector<Vec2f> u2(kN);
  std::vector<Chi2Point> p(kN);
  std::vector<uint8_t> ok(kN);
  for (const Case& c : cases) {
    for (float alpha : {0.0f, 1e-5f, 1e-4f, 1e-3f, 2.0f, 10.0f, 100.0f}) {
      for (float theta : {0.0f, 30.0f, 60.0f, 85.0f, 89.9f}) {
        // On the hemisphere: the directions themselves, not their float disk coordinates.
        const Chi2Subject s = BsdfChi2Subject("test", c.model, c.path, alpha,
                                              Chi2Direction(theta, 123.0f), /*zoom=*/false);
        for (int i = 0; i < kN; ++i) {
          u1[i] = rng.NextFloat();
          u2[i] = {rng.NextFloat(), rng.NextFloat()};
        }
        // The extreme uniforms too: 0 and the largest float below 1.
        u2[0] = {0.0f, 0.0f}, u2[1] = {0x1.fffffep-1f, 0x1.fffffep-1f};
        if (s.sample_batch) {
          s.sample_batch(u1.data(), u2.data(), kN, p.data(), ok.data());
        } else {
          for (int i = 0; i < kN; ++i) ok[i] = s.sample(u1[i], u2[i], &p[i]) ? 1 : 0;
        }
        int bad = 0, accepted = 0;
        for (int i = 0; i < kN; ++i) {
          if (!ok[i]) continue;
          ++accepted;
          const double pdf = s.pdf(p[i]);
          const bool good = Chi2Contains(s.domain, p[i]) && std::isfinite(pdf) && pdf > 0;
          if (!good && bad++ == 0) {
            ADD_FAILURE() << "model " << int(c.model) << " path " << int(c.path)
                          << " alpha=" << alpha << " θ=" << theta << " sample " << i << " at ("
                          << p[i].x << ", " << p[i].y << ", " << p[i].z << "), pdf " << pdf;
          }
        }
        // Not vacuous: some draws are accepted samples. Up to α = 2 at least 1/8 of them (the
        // fewest: 222 of 1024 at α = 2, θ = 0); at α = 10 and 100 most microfacet reflections
        // leave the hemisphere (fewest: 1 of 1024 at α = 100), so at least one.
        EXPECT_GE(accepted, alpha <= 2.0f ? kN / 8 : 1)
            << "model " << int(c.model) << " path " << int(c.path) << " alpha=" << alpha
            << " θ=" << theta;
      }
    }
  }
}

}  // namespace
}  // namespace ptlab
