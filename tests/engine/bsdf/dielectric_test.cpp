// Tests of the smooth dielectric and its Fresnel term: values, TIR, η → 1, Snell, options.
#include "engine/bsdf/dielectric.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/fresnel.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"

namespace ptlab {
namespace {

// Textbook form with cosines and sines in double (the inverted index for light from inside is
// rounded to float, as the code under test sees it). *cos_t_out gets the refracted cosine.
double FresnelReference(float cos_i_f, float eta_f, double* cos_t_out = nullptr) {
  double cos_i = cos_i_f, eta = eta_f;
  if (cos_i < 0) eta = 1.0f / eta_f, cos_i = -cos_i;
  const double sin2_t = (1 - cos_i * cos_i) / (eta * eta);
  if (cos_t_out) *cos_t_out = 0;
  if (sin2_t >= 1) return 1;
  const double ct = std::sqrt(1 - sin2_t);
  if (cos_t_out) *cos_t_out = ct;
  const double rs = (cos_i - eta * ct) / (cos_i + eta * ct);
  const double rp = (eta * cos_i - ct) / (eta * cos_i + ct);
  return 0.5 * (rs * rs + rp * rp);
}

TEST(Dielectric, FresnelMatchesTextbookFormula) {
  for (float eta : {1.5f, 1.0f / 1.5f, 1.33f, 2.4f})
    for (float c = -1.0f; c <= 1.0f; c += 0.001f) {
      float cos_t;
      const float f = FresnelDielectric(c, eta, &cos_t);
      // Near the critical angle F ∝ √(cos² − cos²_crit) amplifies the float rounding of the
      // inputs: allow ~1e-7 / cos θt there.
      double ct;
      const double ref = FresnelReference(c, eta, &ct);
      ASSERT_NEAR(f, ref, 2e-6 + 2e-7 / std::max(ct, 1e-6)) << eta << " " << c;
      ASSERT_NEAR(cos_t, ct, 2e-6 + 2e-7 / std::max(ct, 1e-6)) << eta << " " << c;
      ASSERT_GE(f, 0.0f);
      ASSERT_LE(f, 1.0f);
    }
  float cos_t;
  EXPECT_NEAR(FresnelDielectric(1.0f, 1.5f, &cos_t), 0.04f, 1e-7f);
  EXPECT_EQ(cos_t, 1.0f);
}

TEST(Dielectric, TotalInternalReflectionIncludingTheCriticalAngle) {
  const float eta = 1.5f;
  const float cos_crit = std::sqrt(1.0f - 1.0f / (eta * eta));
  float cos_t = -1;
  // From inside, beyond the critical angle.
  EXPECT_EQ(FresnelDielectric(-0.5f * cos_crit, eta, &cos_t), 1.0f);
  EXPECT_EQ(cos_t, 0.0f);
  // Exactly at the critical angle: from outside with η < 1, walk η up one ulp at a time across
  // sin θi; the last η with total internal reflection is "at" the critical angle in float.
  for (float c : {0.6f, 0.3f, 0.01f, 0.9f}) {
    float tir_eta = std::nextafter(std::sqrt(1.0f - c * c), 0.0f);
    for (int k = 0; k < 64; ++k) tir_eta = std::nextafter(tir_eta, 0.0f);
    ASSERT_EQ(FresnelDielectric(c, tir_eta, &cos_t), 1.0f) << c;
    while (FresnelDielectric(c, std::nextafter(tir_eta, 2.0f), &cos_t) == 1.0f)
      tir_eta = std::nextafter(tir_eta, 2.0f);
    EXPECT_EQ(FresnelDielectric(c, tir_eta, &cos_t), 1.0f) << c;
    EXPECT_EQ(cos_t, 0.0f);
    BsdfSample smp;
    ASSERT_TRUE(
        DielectricSample(tir_eta, bsdf_test::DirectionWithCos(c, 0.0f), kOneMinusEpsilon, &smp));
    EXPECT_EQ(smp.pdf, 1.0f);
    EXPECT_EQ(smp.wi.z, c);
    // One ulp above, light refracts (barely); F is the Fresnel formula at that cos θt.
    const double next = std::nextafter(tir_eta, 2.0f);
    const float f = FresnelDielectric(c, float(next), &cos_t);
    EXPECT_GT(cos_t, 0.0f);
    EXPECT_LT(cos_t, 1e-3f);
    const double rs = (c - next * cos_t) / (c + next * cos_t);
    const double rp = (c - cos_t / next) / (c + cos_t / next);
    EXPECT_NEAR(f, 0.5 * (rs * rs + rp * rp), 1e-5) << c;
  }
  // Approaching it, F rises continuously to 1 and follows the reference.
  float prev = 0.0f;
  for (int j = 200; j >= 0; --j) {
    const float c = -cos_crit * (1.0f + j * 1e-5f);
    const float f = FresnelDielectric(c, eta, &cos_t);
    EXPECT_GE(f, prev - 1e-6f);
    double ct;
    const double ref = FresnelReference(c, eta, &ct);
    EXPECT_NEAR(f, ref, 2e-6 + 2e-7 / std::max(ct, 1e-6)) << c;
    prev = f;
  }
  EXPECT_GT(prev, 0.99f);
  BsdfSample s;
  for (float u : {0.0f, 0.5f, kOneMinusEpsilon}) {
    const Vec3f wo = bsdf_test::DirectionWithCos(-0.5f * cos_crit, 0.2f);
    ASSERT_TRUE(DielectricSample(eta, wo, u, &s));
    EXPECT_EQ(s.wi, (Vec3f{-wo.x, -wo.y, wo.z}));
    EXPECT_EQ(s.pdf, 1.0f);
  }
}

TEST(Dielectric, IndexMatchedInterfaceIsInvisible) {
  for (float eta : {1.0f, 1.0f + 1e-6f, 1.0f - 1e-6f}) {
    for (float c : {1.0f, 0.5f, 0.1f, -0.5f}) {
      float cos_t;
      EXPECT_LT(FresnelDielectric(c, eta, &cos_t), 1e-8f) << eta << " " << c;
      EXPECT_NEAR(cos_t, std::fabs(c), 2e-5f);
      BsdfSample s;
      const Vec3f wo = bsdf_test::DirectionWithCos(c, 0.9f);
      ASSERT_TRUE(DielectricSample(eta, wo, 0.5f, &s));
      EXPECT_NEAR(s.wi.x, -wo.x, 1e-5f);
      EXPECT_NEAR(s.wi.y, -wo.y, 1e-5f);
      EXPECT_NEAR(s.wi.z, -wo.z, 2e-5f);
    }
    // Near grazing the tiny index step still matters (η = 1 − 1e-6 has a critical angle at
    // cos θ ≈ 1.4e-3): follow the reference there.
    for (float c : {1e-1f, 1e-2f, 2e-3f, 1e-3f, 1e-4f, 1e-6f, -1e-3f, -1e-6f}) {
      float cos_t;
      double ct;
      const double ref = FresnelReference(c, eta, &ct);
      EXPECT_NEAR(FresnelDielectric(c, eta, &cos_t), ref, 2e-6 + 2e-7 / std::max(ct, 1e-6))
          << eta << " " << c;
      EXPECT_NEAR(cos_t, ct, 1e-6 * ct + 1e-9) << eta << " " << c;
    }
    float cos_t;
    EXPECT_EQ(FresnelDielectric(0.0f, eta, &cos_t), 1.0f);  // exactly grazing
  }
}

TEST(Dielectric, RefractionObeysSnellAndLobesSumToOne) {
  for (float eta : {1.5f, 1.0f / 1.5f, 1.5046f / 1.000277f})
    for (float c : {0.9f, 0.5f, 0.2f, -0.2f, -0.9f}) {
      const Vec3f wo = bsdf_test::DirectionWithCos(c, 0.4f);
      BsdfSample refl, refr;
      ASSERT_TRUE(DielectricSample(eta, wo, 0.0f, &refl));
      ASSERT_TRUE(DielectricSample(eta, wo, kOneMinusEpsilon, &refr));
      if (refl.pdf == 1.0f) continue;  // TIR
      EXPECT_NEAR(refl.pdf + refr.pdf, 1.0f, 1e-6f);
      EXPECT_NEAR(Length(refr.wi), 1.0f, 1e-5f);
      EXPECT_LT(refr.wi.z * wo.z, 0.0f);
      // η_o sin θo = η_i sin θi, with s.eta = η_i / η_o.
      const float sin_o = std::sqrt(wo.x * wo.x + wo.y * wo.y);
      const float sin_i = std::sqrt(refr.wi.x * refr.wi.x + refr.wi.y * refr.wi.y);
      EXPECT_NEAR(sin_o, refr.eta * sin_i, 1e-5f);
      EXPECT_FLOAT_EQ(refr.eta, c > 0 ? eta : 1.0f / eta);
      EXPECT_EQ(refr.weight.g, 1.0f);
      EXPECT_TRUE(refr.delta);
    }
}

// Schlick against values worked by hand, not against its own code: η = 1.5 gives R0 =
// (0.5/2.5)² = 0.04 exactly, so F(c) = 0.04 + 0.96 (1 − c)^5 at c = 0.5: 0.04 + 0.96/32 = 0.07;
// c = 0.2: 0.04 + 0.96 · 0.32768 = 0.3545728; c = 0.8: 0.04 + 0.96 · 0.00032 = 0.0403072;
// c = 0.9: 0.04 + 0.96e-5 = 0.0400096. η = 1.33: R0 = (0.33/2.33)² = 0.0200593..., c = 0.5:
// R0 + (1 − R0)/32. And the same law in long double at 101 cosines for three IORs.
TEST(Dielectric, SchlickAtTabulatedValues) {
  const struct {
    float eta, cos, f;
  } table[] = {{1.5f, 0.5f, 0.07f},       {1.5f, 0.2f, 0.3545728f}, {1.5f, 0.8f, 0.0403072f},
               {1.5f, 0.9f, 0.0400096f},  {1.5f, -0.5f, 0.07f},     {1.5f, 1.0f, 0.04f},
               {1.33f, 0.5f, 0.0506824f}, {1.33f, 0.0f, 1.0f}};
  for (const auto& t : table) {
    EXPECT_NEAR(FresnelSchlick(t.cos, t.eta), t.f, 2e-7) << "eta " << t.eta << " cos " << t.cos;
  }
  for (float eta : {1.5f, 1.33f, 2.4f}) {
    for (int k = 0; k <= 100; ++k) {
      const long double c = k / 100.0L, r = (eta - 1.0L) / (eta + 1.0L), r0 = r * r;
      const long double ref = r0 + (1 - r0) * std::pow(1 - c, 5.0L);
      EXPECT_NEAR(FresnelSchlick(float(c), eta), double(ref), 1e-6) << eta << " " << double(c);
    }
  }
}

// The exact reflectance against Fresnel's equations in their angle form (Born & Wolf §1.5.2:
// Rs = sin²(θi − θt)/sin²(θi + θt), Rp = tan²(θi − θt)/tan²(θi + θt), θt from Snell's law), in
// long double: a formulation independent of the cosine form the code and the other test use;
// plus tabulated values (η = 1.5: 0.04 at normal incidence; at Brewster's angle tanθ = η, Rp = 0
// so R = Rs/2 = ((η² − 1)/(η² + 1))²/2 = (1.25/3.25)²/2 = 0.0739645).
TEST(Dielectric, FresnelMatchesTheAngleFormAndTabulatedValues) {
  for (float eta : {1.5f, 1.33f, 2.4f}) {
    for (int k = 1; k < 100; ++k) {  // θi in (0°, 90°): the angle form is 0/0 at normal incidence
      const long double ti = k * 0.9L * 3.14159265358979323846L / 180.0L;
      const long double tt = std::asin(std::sin(ti) / eta);
      const long double rs = std::sin(ti - tt) / std::sin(ti + tt);
      const long double rp = std::tan(ti - tt) / std::tan(ti + tt);
      const long double ref = 0.5L * (rs * rs + rp * rp);
      float cos_t;
      EXPECT_NEAR(FresnelDielectric(float(std::cos(ti)), eta, &cos_t), double(ref), 2e-6)
          << eta << " theta " << double(ti);
    }
  }
  float cos_t;
  EXPECT_NEAR(FresnelDielectric(1.0f, 1.5f, &cos_t), 0.04, 1e-7);
  const float brewster_cos = float(1.0 / std::sqrt(1.0 + 1.5 * 1.5));
  EXPECT_NEAR(FresnelDielectric(brewster_cos, 1.5f, &cos_t), 0.0739645, 1e-6);
}

TEST(Dielectric, SchlickAndRadianceScalingOptions) {
  const float eta = 1.5f;
  const Vec3f wo = bsdf_test::DirectionWithCos(0.6f, 0.0f);
  BsdfSample s;
  ASSERT_TRUE(DielectricSample(eta, wo, 0.0f, &s, kDielectricSchlick));
  EXPECT_FLOAT_EQ(s.pdf, FresnelSchlick(0.6f, eta));
  EXPECT_FLOAT_EQ(FresnelSchlick(1.0f, eta), 0.04f);
  EXPECT_FLOAT_EQ(FresnelSchlick(0.0f, eta), 1.0f);
  // Schlick still detects TIR exactly.
  ASSERT_TRUE(
      DielectricSample(eta, bsdf_test::DirectionWithCos(-0.1f, 0.0f), 0.99f, &s, kDielectricSchlick));
  EXPECT_EQ(s.pdf, 1.0f);
  // Radiance scaling: entering glass from air divides by η², leaving multiplies by η².
  ASSERT_TRUE(DielectricSample(eta, wo, kOneMinusEpsilon, &s, kDielectricScaleRadiance));
  EXPECT_FLOAT_EQ(s.weight.r, 1.0f / (eta * eta));
  ASSERT_TRUE(DielectricSample(eta, bsdf_test::DirectionWithCos(-0.95f, 0.0f), kOneMinusEpsilon, &s,
                               kDielectricScaleRadiance));
  EXPECT_FLOAT_EQ(s.weight.r, eta * eta);
  // Through the tables and the dispatch.
  MaterialTables m;
  const MaterialRef plain = m.AddDielectric(1.5f, 1.0f);
  EXPECT_TRUE(m.dielectric.flags.empty());  // nothing is stored until a row needs it
  const MaterialRef scaled = m.AddDielectric(1.5f, 1.0f, kDielectricScaleRadiance);
  EXPECT_EQ(m.dielectric.Flags(plain.index()), 0);
  EXPECT_EQ(m.dielectric.Flags(scaled.index()), kDielectricScaleRadiance);
  ASSERT_TRUE(BsdfSampleDirection(m, scaled, wo, kOneMinusEpsilon, {0, 0}, &s));
  EXPECT_FLOAT_EQ(s.weight.r, 1.0f / 2.25f);
  ASSERT_TRUE(BsdfSampleDirection(m, plain, wo, kOneMinusEpsilon, {0, 0}, &s));
  EXPECT_EQ(s.weight.r, 1.0f);
  EXPECT_TRUE(IsBlack(BsdfEval(m, plain, wo, s.wi)));
  EXPECT_EQ(BsdfPdf(m, plain, wo, s.wi), 0.0f);
}

// CS184 RefractionBSDF: every sample refracts (whatever u), TIR samples nothing.
TEST(Dielectric, RefractOnlyNeverReflects) {
  const float eta = 1.45f;
  BsdfSample s;
  for (float u : {0.0f, 0.5f, kOneMinusEpsilon}) {
    ASSERT_TRUE(DielectricSample(eta, bsdf_test::DirectionWithCos(0.6f, 0.0f), u, &s,
                                 kDielectricRefractOnly));
    EXPECT_LT(s.wi.z, 0.0f);
    EXPECT_EQ(s.pdf, 1.0f);
    EXPECT_EQ(s.weight.r, 1.0f);
    EXPECT_FLOAT_EQ(s.eta, eta);
  }
  ASSERT_TRUE(DielectricSample(eta, bsdf_test::DirectionWithCos(0.6f, 0.0f), 0.0f, &s,
                               kDielectricRefractOnly | kDielectricScaleRadiance));
  EXPECT_FLOAT_EQ(s.weight.r, 1.0f / (eta * eta));
  // Inside, beyond the critical angle (cos 0.1): nothing refracts, nothing is sampled.
  EXPECT_FALSE(DielectricSample(eta, bsdf_test::DirectionWithCos(-0.1f, 0.0f), 0.0f, &s,
                                kDielectricRefractOnly));
}

}  // namespace
}  // namespace ptlab
