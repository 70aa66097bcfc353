// Tests of Nori's `microfacet` (Beckmann rough plastic): definition, weight, reciprocity, albedo.
#include "engine/bsdf/rough_plastic.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/bsdf/bsdf.h"
#include "engine/core/rng.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"

namespace ptlab {
namespace {

TEST(RoughPlastic, DefaultsAndKs) {
  const RoughPlasticParams d;
  EXPECT_EQ(d.alpha, 0.1f);
  EXPECT_FLOAT_EQ(d.eta, 1.5046f / 1.000277f);
  EXPECT_EQ(d.ks, 0.5f);
  const RoughPlasticParams p = MakeRoughPlasticParams(0.3f, 1.5f, 1.01f, {0.2f, 0.1f, 0.6f});
  EXPECT_FLOAT_EQ(p.ks, 0.4f);
  EXPECT_FLOAT_EQ(p.eta, 1.5f / 1.01f);
}

TEST(RoughPlastic, EvalIsNorisFormula) {
  // f = kd/π + ks D_Nori F G / (4 cos θi cos θo cos θh), D_Nori = exp(−tan²θh/α²)/(π α² cos³θh).
  const RoughPlasticParams p = MakeRoughPlasticParams(0.3f, 1.8f, 1.3f, {0.4f, 0.2f, 0.3f});
  Pcg32 rng(2, 3);
  for (int i = 0; i < 500; ++i) {
    const Vec3f wo = bsdf_test::RandomUpperDirection(rng), wi = bsdf_test::RandomUpperDirection(rng);
    const Vec3f h = Normalize(wo + wi);
    const double ch = h.z, tan2 = (1.0 - ch * ch) / (ch * ch), a2 = double(p.alpha) * p.alpha;
    const double d_nori = std::exp(-tan2 / a2) / (M_PI * a2 * ch * ch * ch);
    float cos_t;
    const double fr = FresnelDielectric(Dot(h, wi), 1.8f / 1.3f, &cos_t);
    const double g = BeckmannG1(p.alpha, wi) * BeckmannG1(p.alpha, wo);
    const double spec = p.ks * d_nori * fr * g / (4.0 * wi.z * wo.z * ch);
    const Color3f f = RoughPlasticEval(p, wo, wi);
    for (int c = 0; c < 3; ++c) {
      const double ref = p.kd[c] / M_PI + spec;
      ASSERT_NEAR(f[c], ref, 1e-4 * ref) << i;
    }
  }
  // One-sided.
  EXPECT_TRUE(IsBlack(RoughPlasticEval(p, {0, 0, 1}, {0, 0.6f, -0.8f})));
  EXPECT_EQ(RoughPlasticPdf(p, {0, 0.6f, -0.8f}, {0, 0, 1}), 0.0f);
}

TEST(RoughPlastic, SampleWeightIsEvalCosOverPdf) {
  Pcg32 rng(17, 4);
  int valid = 0;
  for (float alpha : {1e-4f, 1e-3f, 0.005f, 0.05f, 0.1f, 0.5f, 1.0f, 2.0f}) {
    for (const Color3f& kd : {Color3f{0.5f, 0.5f, 0.5f}, Color3f{0, 0, 0},
                              Color3f{0.1f, 0.2f, 0.15f}, Color3f{1, 1, 1}}) {
      const RoughPlasticParams p = MakeRoughPlasticParams(alpha, 1.5046f, 1.000277f, kd);
      for (int i = 0; i < 300; ++i) {
        const Vec3f wo = bsdf_test::RandomUpperDirection(rng);
        const float ul = rng.NextFloat(), ux = rng.NextFloat();
        BsdfSample s;
        if (!RoughPlasticSample(p, wo, ul, {ux, rng.NextFloat()}, &s)) continue;
        ++valid;
        const float pdf = RoughPlasticPdf(p, wo, s.wi);
        ASSERT_EQ(s.pdf, pdf);
        const Color3f f = RoughPlasticEval(p, wo, s.wi);
        for (int c = 0; c < 3; ++c) {
          const float ref = f[c] * s.wi.z / pdf;
          ASSERT_NEAR(s.weight[c], ref, 1e-5f * ref) << alpha;
        }
      }
    }
  }
  EXPECT_GT(valid, 6000);
}

TEST(RoughPlastic, Reciprocity) {
  Pcg32 rng(8, 8);
  const RoughPlasticParams p = MakeRoughPlasticParams(0.2f, 1.5f, 1.0f, {0.3f, 0.2f, 0.1f});
  for (int i = 0; i < 2000; ++i) {
    const Vec3f a = bsdf_test::RandomUpperDirection(rng), b = bsdf_test::RandomUpperDirection(rng);
    const Color3f fab = RoughPlasticEval(p, a, b), fba = RoughPlasticEval(p, b, a);
    for (int c = 0; c < 3; ++c) ASSERT_EQ(fab[c], fba[c]);
  }
}

// Albedo ∫ f cos θi dωi: kd exactly for the Lambertian part, plus the specular part by a
// stratified midpoint grid with h ~ D cos θh.
Color3f Albedo(const RoughPlasticParams& p, const Vec3f& wo, int n) {
  double spec = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec3f wi =
          ReflectAbout(wo, SampleBeckmannNormal(p.alpha, {(i + 0.5f) / n, (j + 0.5f) / n}));
      if (wi.z <= 0) continue;
      const float pdf = BeckmannReflectionPdf(p.alpha, wo, wi);
      if (!(pdf > 0)) continue;
      spec += double(RoughPlasticEval(p, wo, wi).g - p.kd.g * kInvPi) * wi.z / pdf;
    }
  const float s = float(spec / (double(n) * n));
  return p.kd + Color3f{s, s, s};
}

TEST(RoughPlastic, AlbedoMatchesNorisTtestReferences) {
  // scenes/pa5/tests/ttest-microfacet.xml (SOURCES.md): alpha 0.1, intIOR 1.5, extIOR 1.000277,
  // kd (0.1, 0.2, 0.15); luminance of the albedo at 0/45/60/80/85 degrees.
  const RoughPlasticParams p = MakeRoughPlasticParams(0.1f, 1.5f, 1.000277f, {0.1f, 0.2f, 0.15f});
  const float deg[] = {0, 45, 60, 80, 85};
  const float ref[] = {0.207067f, 0.215733f, 0.247884f, 0.430936f, 0.519016f};
  for (int i = 0; i < 5; ++i) {
    const Vec3f wo = bsdf_test::DirectionWithCos(std::cos(Radians(deg[i])), 0.0f);
    EXPECT_NEAR(Luminance(Albedo(p, wo, 512)), ref[i], 2e-3f) << deg[i] << " degrees";
  }
}

TEST(RoughPlastic, AlbedoIsAtMostOne) {
  for (float alpha : {1e-3f, 0.05f, 0.5f, 1.0f, 2.0f})
    for (const Color3f& kd : {Color3f{0, 0, 0}, Color3f{0.5f, 0.5f, 0.5f}, Color3f{1, 1, 1}}) {
      const RoughPlasticParams p = MakeRoughPlasticParams(alpha, 1.5046f, 1.000277f, kd);
      for (float d : {0.0f, 30.0f, 60.0f, 80.0f, 89.0f, 89.9f}) {
        const Color3f a = Albedo(p, bsdf_test::DirectionWithCos(std::cos(Radians(d)), 0.3f), 128);
        EXPECT_LE(MaxComponent(a), 1.0f + 1e-3f) << alpha << " " << d;
      }
    }
}

TEST(RoughPlastic, DispatchByMaterialRef) {
  MaterialTables m;
  const MaterialRef ref = m.AddRoughPlastic(0.3f, 1.5f, 1.01f, {0.2f, 0.1f, 0.6f});
  const RoughPlasticParams p = MakeRoughPlasticParams(0.3f, 1.5f, 1.01f, {0.2f, 0.1f, 0.6f});
  const Vec3f wo = Normalize(Vec3f{0.3f, 0.1f, 0.8f}), wi = Normalize(Vec3f{-0.2f, 0.0f, 0.9f});
  EXPECT_EQ(BsdfEval(m, ref, wo, wi).r, RoughPlasticEval(p, wo, wi).r);
  EXPECT_EQ(BsdfPdf(m, ref, wo, wi), RoughPlasticPdf(p, wo, wi));
  BsdfSample a, b;
  ASSERT_TRUE(BsdfSampleDirection(m, ref, wo, 0.2f, {0.3f, 0.7f}, &a));
  ASSERT_TRUE(RoughPlasticSample(p, wo, 0.2f, {0.3f, 0.7f}, &b));
  EXPECT_EQ(a.wi, b.wi);
  EXPECT_FALSE(IsDeltaMaterial(MaterialTag::kRoughPlastic));
}

}  // namespace
}  // namespace ptlab
