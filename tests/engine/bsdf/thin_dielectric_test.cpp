// Mitsuba `thindielectric` (engine/bsdf/thin_dielectric.h).
#include "engine/bsdf/thin_dielectric.h"

#include <gtest/gtest.h>

#include "engine/bsdf/bsdf.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"

namespace ptlab {
namespace {

// R' = R + T²R + T²R³ + … summed numerically against the closed form 2R / (1 + R).
TEST(ThinDielectric, ReflectanceSumsTheInternalBounces) {
  for (float eta : {1.5f, 1.333f, 2.4f, 1.0f})
    for (float c : {1.0f, 0.7f, 0.2f, 0.01f}) {
      float cos_t;
      const double r = FresnelDielectric(c, eta, &cos_t), t = 1 - r;
      double sum = r, term = t * t * r;
      for (int k = 0; k < 1000; ++k) sum += term, term *= r * r;
      EXPECT_NEAR(ThinDielectricReflectance(c, eta), sum, 1e-6) << eta << " " << c;
      EXPECT_FLOAT_EQ(ThinDielectricReflectance(-c, eta), ThinDielectricReflectance(c, eta));
    }
  EXPECT_EQ(ThinDielectricReflectance(0.5f, 1.0f), 0.0f);
}

TEST(ThinDielectric, SamplesReflectOrPassStraightThrough) {
  MaterialTables m;
  const MaterialRef ref = m.AddThinDielectric(1.5f, {0.9f, 0.8f, 0.7f}, {0.3f, 0.2f, 0.1f});
  EXPECT_TRUE(IsDeltaMaterial(ref.tag()));
  for (float c : {0.8f, -0.8f, 0.05f}) {
    const Vec3f wo = bsdf_test::DirectionWithCos(c, 0.3f);
    const float r = ThinDielectricReflectance(c, 1.5f);
    BsdfSample s;
    ASSERT_TRUE(BsdfSampleDirection(m, ref, wo, r * 0.99f, {0.5f, 0.5f}, &s));
    EXPECT_TRUE(s.delta);
    EXPECT_EQ(s.wi.x, -wo.x); EXPECT_EQ(s.wi.y, -wo.y); EXPECT_EQ(s.wi.z, wo.z);
    EXPECT_EQ(s.pdf, r);
    EXPECT_EQ(s.weight.r, 0.9f);
    EXPECT_EQ(s.eta, 1.0f);
    ASSERT_TRUE(BsdfSampleDirection(m, ref, wo, r * 1.01f + 1e-6f, {0.5f, 0.5f}, &s));
    EXPECT_EQ(s.wi.x, -wo.x); EXPECT_EQ(s.wi.y, -wo.y); EXPECT_EQ(s.wi.z, -wo.z);
    EXPECT_EQ(s.pdf, 1.0f - r);
    EXPECT_EQ(s.weight.b, 0.1f);
    EXPECT_EQ(s.eta, 1.0f);
    EXPECT_TRUE(IsBlack(BsdfEval(m, ref, wo, s.wi)));
    EXPECT_EQ(BsdfPdf(m, ref, wo, s.wi), 0.0f);
  }
  // η = 1: nothing reflects (u = 0 included).
  const MaterialRef clear = m.AddThinDielectric(1.0f);
  BsdfSample s;
  ASSERT_TRUE(BsdfSampleDirection(m, clear, {0, 0.6f, 0.8f}, 0.0f, {0.5f, 0.5f}, &s));
  EXPECT_EQ(s.wi.z, -0.8f);
  EXPECT_EQ(s.pdf, 1.0f);
}

}  // namespace
}  // namespace ptlab
