// Tests of the rough conductor: Fresnel, presets, sample weight, reciprocity, white furnace.
#include "engine/bsdf/conductor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/bsdf/conductor_presets.h"
#include "engine/core/rng.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"

namespace ptlab {
namespace {

ConductorParams Preset(const char* name, float alpha) {
  ConductorParams p;
  p.alpha = alpha;
  EXPECT_TRUE(LookupConductorPreset(name, &p.eta, &p.k)) << name;
  return p;
}

TEST(Conductor, FresnelAtNormalAndGrazingIncidence) {
  for (float eta : {0.2f, 1.0f, 1.5f, 3.0f})
    for (float k : {0.0f, 0.5f, 3.0f, 8.0f}) {
      const float ref = ((eta - 1) * (eta - 1) + k * k) / ((eta + 1) * (eta + 1) + k * k);
      EXPECT_NEAR(FresnelConductor(1.0f, eta, k), ref, 2e-6f) << eta << " " << k;
      EXPECT_EQ(FresnelConductor(0.0f, eta, k), 1.0f) << eta << " " << k;
    }
  EXPECT_EQ(FresnelConductor(0.3f, 0.0f, 1.0f), 1.0f);  // Mitsuba's "none"
  EXPECT_EQ(FresnelConductor(1.0f, 0.0f, 0.0f), 1.0f);
}

TEST(Conductor, FresnelIsInUnitRangeOnExtremeInputs) {
  // Tiny, zero and clamped η, κ and cosines, denormals included: no NaN or Inf, never above 1.
  // (ds·dp of the one-quotient form must not underflow to 0; every num <= its den.)
  const float values[] = {0.0f,  1e-45f, 1e-38f, 1e-30f, 1e-23f, 1e-15f, 1e-8f,
                          1e-3f, 0.5f,   1.0f,   3.0f,   1e4f,   1e30f};
  for (float c : values)
    for (float eta : values)
      for (float k : values) {
        if (c > 1.0f) continue;
        const float f = FresnelConductor(c, eta, k);
        ASSERT_TRUE(std::isfinite(f)) << c << " " << eta << " " << k;
        EXPECT_GE(f, 0.0f) << c << " " << eta << " " << k;
        EXPECT_LE(f, 1.0f) << c << " " << eta << " " << k;
      }
  // η, κ ~ 1e-23 at normal incidence (found by a random search): Re z is float's least
  // denormal, |z| underflows to 0, and a = 0 made ek / a infinite. The limit there is 1.
  EXPECT_EQ(FresnelConductor(1.0f, 3.84846e-23f, 2.24301e-23f), 1.0f);
  EXPECT_EQ(FresnelConductor(1.0f, 6.0064e-23f, 3.97018e-23f), 1.0f);
  // η = 1, κ tiny, cos θ tiny: a, b ~ 1e-17 and the squares of Rs are denormal (it was 1.032).
  EXPECT_LE(FresnelConductor(2.07785e-22f, 1.0f, 1.28374e-35f), 1.0f);
  EXPECT_LE(FresnelConductor(1.92215e-20f, 1.0f, 5.76979e-27f), 1.0f);
}

TEST(Conductor, FresnelWithZeroKIsTheDielectricFresnel) {
  for (float eta : {1.1f, 1.5f, 2.5f})
    for (float c = 0.0f; c <= 1.0f; c += 0.01f) {
      float cos_t;
      EXPECT_NEAR(FresnelConductor(c, eta, 0.0f), FresnelDielectric(c, eta, &cos_t), 2e-6f)
          << eta << " " << c;
    }
}

TEST(Conductor, PresetsExistAndLookPlausible) {
  for (const char* name : {"Au", "Ag", "Al", "Cu", "Fe", "Na", "Na_palik", "Si", "Sn", "none"}) {
    Color3f eta, k;
    ASSERT_TRUE(LookupConductorPreset(name, &eta, &k)) << name;
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(eta[c], 0.0f);
      EXPECT_LT(eta[c], 6.0f);
      EXPECT_GE(k[c], 0.0f);
      EXPECT_LT(k[c], 10.0f);
    }
  }
  Color3f eta{7, 7, 7}, k{7, 7, 7};
  EXPECT_FALSE(LookupConductorPreset("Unobtainium", &eta, &k));
  EXPECT_FALSE(LookupConductorPreset("au", &eta, &k));
  EXPECT_EQ(eta.r, 7.0f);
  EXPECT_NE(std::string(ConductorPresetNames()).find("Au"), std::string::npos);
  // Gold and copper reflect red more than blue; silver and aluminium are bright and neutral.
  auto r0 = [](const char* name) {
    Color3f eta, k;
    LookupConductorPreset(name, &eta, &k);
    return FresnelConductor(1.0f, eta, k);
  };
  EXPECT_GT(r0("Au").r, r0("Au").b + 0.3f);
  EXPECT_GT(r0("Cu").r, r0("Cu").b + 0.3f);
  EXPECT_GT(r0("Ag").b, 0.85f);
  EXPECT_GT(r0("Al").g, 0.85f);
  EXPECT_NEAR(r0("Au").r, 0.92f, 0.03f);  // textbook normal-incidence reflectance of gold
  // Tin: ((n-1)^2 + k^2) / ((n+1)^2 + k^2) at n = 2.384, k = 4.727, the same in every channel.
  EXPECT_NEAR(r0("Sn").g, 0.718f, 0.002f);
  EXPECT_EQ(r0("Sn").r, r0("Sn").b);
}

TEST(Conductor, SampleWeightIsEvalCosOverPdf) {
  Pcg32 rng(11, 2);
  int valid = 0;
  for (const char* name : {"Au", "Cu", "Al", "Fe", "Si"}) {
    for (float alpha : {1e-4f, 1e-3f, 0.005f, 0.05f, 0.5f, 1.0f, 2.0f}) {
      const ConductorParams p = Preset(name, alpha);
      for (int i = 0; i < 400; ++i) {
        const Vec3f wo = bsdf_test::RandomUpperDirection(rng);
        const float u1 = rng.NextFloat();
        BsdfSample s;
        if (!ConductorSample(p, wo, {u1, rng.NextFloat()}, &s)) continue;
        ++valid;
        const float pdf = ConductorPdf(p, wo, s.wi);
        ASSERT_EQ(s.pdf, pdf);
        ASSERT_GT(pdf, 0.0f);
        const Color3f f = ConductorEval(p, wo, s.wi);
        for (int c = 0; c < 3; ++c) {
          const float ref = f[c] * s.wi.z / pdf;
          ASSERT_NEAR(s.weight[c], ref, 1e-4f * ref) << name << " alpha " << alpha;
        }
      }
    }
  }
  EXPECT_GT(valid, 8000);
}

TEST(Conductor, Reciprocity) {
  Pcg32 rng(5, 9);
  const ConductorParams p = Preset("Cu", 0.3f);
  for (int i = 0; i < 2000; ++i) {
    const Vec3f a = bsdf_test::RandomUpperDirection(rng), b = bsdf_test::RandomUpperDirection(rng);
    const Color3f fab = ConductorEval(p, a, b), fba = ConductorEval(p, b, a);
    for (int c = 0; c < 3; ++c) ASSERT_EQ(fab[c], fba[c]);
  }
}

// ∫ f cos θi dωi by a stratified midpoint grid over the sampling square (importance sampling
// with h ~ D cos θh), i.e. the mean sample weight.
Color3f Albedo(const ConductorParams& p, const Vec3f& wo, int n) {
  Color3f sum;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      BsdfSample s;
      if (ConductorSample(p, wo, {(i + 0.5f) / n, (j + 0.5f) / n}, &s)) sum += s.weight;
    }
  return sum / float(n * n);
}

TEST(Conductor, WhiteFurnaceAlbedoWithUnitFresnelIsAtMostOne) {
  // F = 1 (η = 0, κ = 1): the albedo is the fraction of energy the shadowing term keeps.
  ConductorParams p = Preset("none", 0.1f);
  for (float alpha : {1e-4f, 1e-3f, 0.005f, 0.05f, 0.2f, 0.5f, 1.0f, 2.0f}) {
    p.alpha = alpha;
    for (float deg : {0.0f, 15.0f, 30.0f, 45.0f, 60.0f, 75.0f, 85.0f, 89.0f, 89.9f}) {
      const Vec3f wo = bsdf_test::DirectionWithCos(std::cos(Radians(deg)), 0.3f);
      const float albedo = Albedo(p, wo, 256).g;
      EXPECT_LE(albedo, 1.0f + 1e-3f) << "alpha " << alpha << " theta " << deg;
      EXPECT_GE(albedo, 0.0f);
      // Smooth surfaces lose (almost) nothing away from grazing angles.
      if (alpha <= 0.05f && deg <= 60.0f) {
        EXPECT_GT(albedo, 0.99f) << alpha << " " << deg;
      }
    }
  }
}

TEST(Conductor, TinyAlphaBehavesAsAMirror) {
  const ConductorParams p = Preset("Au", 0.0f);  // clamped to kBeckmannMinAlpha
  Pcg32 rng(1, 1);
  for (int i = 0; i < 200; ++i) {
    const Vec3f wo = bsdf_test::DirectionWithCos(0.05f + 0.95f * rng.NextFloat(), 1.0f);
    const float u1 = rng.NextFloat();
    BsdfSample s;
    ASSERT_TRUE(ConductorSample(p, wo, {u1, rng.NextFloat()}, &s));
    EXPECT_NEAR(s.wi.x, -wo.x, 2e-3f);
    EXPECT_NEAR(s.wi.y, -wo.y, 2e-3f);
    EXPECT_NEAR(s.wi.z, wo.z, 2e-3f);
    const Color3f f = FresnelConductor(wo.z, p.eta, p.k);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c], f[c], 5e-3f);
  }
}

}  // namespace
}  // namespace ptlab
