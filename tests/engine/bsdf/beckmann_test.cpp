// Tests of the Beckmann distribution: normalisation, G1, sampling, pdf conventions.
#include "engine/bsdf/beckmann.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/rng.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"

namespace ptlab {
namespace {

// ∫ BeckmannPdfH dω_h over the hemisphere, by the midpoint rule in θ (φ-symmetric).
double IntegratePdfH(float alpha) {
  const int n = 400000;
  const double dtheta = 0.5 * M_PI / n;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double theta = (i + 0.5) * dtheta;
    const Vec3f h{float(std::sin(theta)), 0.0f, float(std::cos(theta))};
    sum += double(BeckmannPdfH(alpha, h)) * std::sin(theta);
  }
  return 2.0 * M_PI * sum * dtheta;
}

TEST(Beckmann, PdfHIntegratesToOneAndDIsItsCosineQuotient) {
  for (float alpha : {1e-3f, 0.05f, 0.1f, 0.5f, 1.0f}) {
    EXPECT_NEAR(IntegratePdfH(alpha), 1.0, 2e-4) << "alpha " << alpha;
  }
  const Vec3f h = Normalize(Vec3f{0.3f, -0.2f, 0.9f});
  EXPECT_FLOAT_EQ(BeckmannPdfH(0.3f, h), BeckmannD(0.3f, h) * h.z);
  // D is independent of the length of h.
  EXPECT_FLOAT_EQ(BeckmannD(0.3f, h * 7.0f), BeckmannD(0.3f, h));
  // Peak value 1/(π α²) at the normal.
  EXPECT_FLOAT_EQ(BeckmannD(0.2f, {0, 0, 1}), 1.0f / (kPi * 0.04f));
}

TEST(Beckmann, DIsZeroBelowHorizonAndForDegenerateH) {
  EXPECT_EQ(BeckmannD(0.5f, {0.3f, 0.0f, -0.1f}), 0.0f);
  EXPECT_EQ(BeckmannD(0.5f, {1.0f, 0.0f, 0.0f}), 0.0f);
  EXPECT_EQ(BeckmannD(0.5f, {0.0f, 0.0f, 0.0f}), 0.0f);
  EXPECT_EQ(BeckmannD(0.5f, {1e-40f, 0.0f, 1e-40f}), BeckmannD(0.5f, {1e-40f, 0.0f, 1e-40f}));
}

TEST(Beckmann, G1RationalApproximation) {
  const float alpha = 0.3f;
  for (float c : {1e-6f, 1e-3f, 0.1f, 0.3f, 0.5f, 0.7f, 0.9f, 1.0f}) {
    const Vec3f v = bsdf_test::DirectionWithCos(c, 0.4f);
    const float g = BeckmannG1(alpha, v);
    EXPECT_GE(g, 0.0f);
    EXPECT_LE(g, 1.0f);
    EXPECT_NEAR(BeckmannG1OverCos(alpha, v) * c, g, 1e-6f * std::max(1.0f, g)) << c;
    // Walter et al. 2007 eq. 27 written with tan θ.
    const double tan_t = std::sqrt(1.0 - double(c) * c) / c;
    const double b = 1.0 / (alpha * tan_t);
    const double ref = b < 1.6 ? (3.535 * b + 2.181 * b * b) / (1 + 2.276 * b + 2.577 * b * b) : 1;
    EXPECT_NEAR(g, ref, 1e-5) << c;
  }
  // Continuous where the rational branch meets 1 (b = 1.6).
  const float tan_at = 1.0f / (1.6f * alpha);
  const Vec3f v = Normalize(Vec3f{tan_at, 0.0f, 1.0f});
  EXPECT_NEAR(BeckmannG1(alpha, Normalize(Vec3f{tan_at * 1.0001f, 0, 1})), 1.0f, 1e-3f);
  EXPECT_EQ(BeckmannG1(alpha, {0, 0, 1}), 1.0f);
  EXPECT_NEAR(BeckmannG1(alpha, v), 1.0f, 1e-3f);
  // Finite at exactly grazing: G1/cos → 3.535/α.
  EXPECT_NEAR(BeckmannG1OverCos(alpha, {1, 0, 0}), 3.535f / alpha, 1e-4f);
}

TEST(Beckmann, SampledNormalsFollowTheInverseCdf) {
  Pcg32 rng(7, 1);
  for (float alpha : {1e-4f, 1e-3f, 0.05f, 0.5f, 1.0f, 2.0f}) {
    for (int i = 0; i < 2000; ++i) {
      const float u1 = rng.NextFloat(), u2 = rng.NextFloat();
      const Vec3f h = SampleBeckmannNormal(alpha, {u1, u2});
      ASSERT_NEAR(Length(h), 1.0f, 2e-6f);
      ASSERT_GT(h.z, 0.0f);
      // tan²θ / α² = −log(1 − u1): the Beckmann CDF 1 − exp(−tan²θ/α²) inverted.
      const double tan2 = (double(h.x) * h.x + double(h.y) * h.y) / (double(h.z) * h.z);
      ASSERT_NEAR(tan2 / (double(alpha) * alpha), -std::log1p(-double(u1)),
                  2e-5 * (1.0 - std::log1p(-double(u1))))
          << alpha << " " << u1;
    }
  }
  // Ends of the unit square.
  EXPECT_EQ(SampleBeckmannNormal(0.3f, {0.0f, 0.0f}).z, 1.0f);
  const Vec3f h = SampleBeckmannNormal(0.3f, {kOneMinusEpsilon, kOneMinusEpsilon});
  EXPECT_TRUE(std::isfinite(h.x) && std::isfinite(h.y) && h.z > 0);
}

TEST(Beckmann, ReflectionPdfIsHalfVectorDensityTimesJacobian) {
  // Reference in double: D(h) cos θh / (4 wo·h) with h = (wo + wi)/|wo + wi|.
  Pcg32 rng(3, 5);
  int checked = 0;
  for (int i = 0; i < 4000; ++i) {
    const float alpha = bsdf_test::RandomAlpha(rng);
    const Vec3f wo = bsdf_test::RandomUpperDirection(rng);
    const Vec3f wi = bsdf_test::NearSpecularPartner(alpha, wo, rng);
    if (wi.z <= 0) continue;
    const double hx = double(wo.x) + wi.x, hy = double(wo.y) + wi.y, hz = double(wo.z) + wi.z;
    const double len = std::sqrt(hx * hx + hy * hy + hz * hz), cos_h = hz / len;
    const double tan2 = (hx * hx + hy * hy) / (hz * hz), a2 = double(alpha) * alpha;
    const double d = std::exp(-tan2 / a2) / (M_PI * a2 * cos_h * cos_h * cos_h * cos_h);
    const double wo_h = (wo.x * hx + wo.y * hy + wo.z * hz) / len;
    const double ref = d * cos_h / (4.0 * wo_h);
    // Relative conditioning of the Jacobian: ~1e-7 / |wo + wi| (float-rounded inputs).
    ASSERT_NEAR(BeckmannReflectionPdf(alpha, wo, wi), ref, (2e-5 + 1e-7 / len) * ref + 1e-30)
        << alpha << " |H| " << len;
    float dv, pdf;
    BeckmannEvalPdf(alpha, wo, wi, &dv, &pdf);
    ASSERT_NEAR(dv, d, 2e-5 * d + 1e-30) << alpha;
    ++checked;
  }
  EXPECT_GT(checked, 2000);
  // One-sided.
  EXPECT_EQ(BeckmannReflectionPdf(0.5f, {0, 0, 1}, {0.1f, 0, -0.99f}), 0.0f);
  EXPECT_EQ(BeckmannReflectionPdf(0.5f, {0.1f, 0, -0.99f}, {0, 0, 1}), 0.0f);
}

TEST(Beckmann, ReflectionPdfIntegratesToTheMassAboveTheSurface) {
  // ∫ pdf(wi) dωi over the upper hemisphere = P(reflected wi is above) ≤ 1, → 1 at normal
  // incidence for small α. Midpoint rule in (cos θ, φ).
  for (float alpha : {0.1f, 0.5f}) {
    const Vec3f wo = bsdf_test::DirectionWithCos(1.0f, 0.0f);
    const int nt = 2000, np = 64;
    double sum = 0;
    for (int i = 0; i < nt; ++i) {
      const float c = (i + 0.5f) / nt;
      for (int j = 0; j < np; ++j) {
        const Vec3f wi = bsdf_test::DirectionWithCos(c, 2 * kPi * (j + 0.5f) / np);
        sum += BeckmannReflectionPdf(alpha, wo, wi);
      }
    }
    const double integral = sum * (2.0 * M_PI) / (double(nt) * np);
    EXPECT_LE(integral, 1.0 + 1e-3) << alpha;
    if (alpha == 0.1f) {
      EXPECT_NEAR(integral, 1.0, 2e-3);
    }
  }
}

}  // namespace
}  // namespace ptlab
