// Tests of Mitsuba's roughdielectric (engine/bsdf/rough_dielectric.h): the α → 0 limit is the
// smooth dielectric, total internal reflection, reciprocity of f/η², and hard inputs.
#include "engine/bsdf/rough_dielectric.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/bsdf/dielectric.h"
#include "engine/core/rng.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"

namespace ptlab {
namespace {

RoughDielectricParams Params(MicrofacetType type, float au, float av, bool visible, float eta) {
  RoughDielectricParams p;
  p.dist = MakeMicrofacet(type, au, av, visible);
  p.eta = eta;
  return p;
}

// As α → 0 (1e-4, the clamp) the rough interface samples what `dielectric` with Mitsuba's
// radiance scale samples: reflection with probability F (within 5σ of 4000 draws), the same
// directions (within 2e-3: the lobe's width is ~α/cos) and weights (within 1e-2: G1 ≈ 1).
TEST(RoughDielectric, TendsToTheSmoothDielectricAsAlphaVanishes) {
  Pcg32 rng(4, 4);
  for (MicrofacetType type : {MicrofacetType::kBeckmann, MicrofacetType::kGgx}) {
    for (bool visible : {true, false}) {
      for (float eta : {1.5f, 1.0f / 1.5f, 1.33f}) {
        const RoughDielectricParams p = Params(type, 1e-4f, 1e-4f, visible, eta);
        for (float c : {1.0f, 0.8f, 0.4f, -0.5f, -0.95f, -0.3f}) {
          const Vec3f wo = bsdf_test::DirectionWithCos(c, 0.7f);
          float cos_t;
          const float f = FresnelDielectric(c, eta, &cos_t);
          constexpr int kN = 4000;
          int reflected = 0;
          double weight_sum = 0, smooth_sum = 0;
          int outliers = 0;  // samples off by more than 2e-3 in wi or 1 % in weight
          for (int i = 0; i < kN; ++i) {
            const float u1 = rng.NextFloat();
            BsdfSample rough, smooth;
            ASSERT_TRUE(RoughDielectricSample(p, wo, u1, {rng.NextFloat(), rng.NextFloat()},
                                              &rough));
            const bool reflect = rough.wi.z * wo.z > 0;
            reflected += reflect ? 1 : 0;
            // The smooth sample of the same lobe.
            ASSERT_TRUE(DielectricSample(eta, wo, reflect ? 0.0f : 1.0f, &smooth,
                                         kDielectricScaleRadiance));
            ASSERT_EQ(smooth.wi.z * wo.z > 0, reflect) << "TIR disagrees at cos " << c;
            const float dev = std::max({std::fabs(rough.wi.x - smooth.wi.x),
                                        std::fabs(rough.wi.y - smooth.wi.y),
                                        std::fabs(rough.wi.z - smooth.wi.z)});
            // With visible normals the weight is G1 → 1 per sample; with D cos θ sampling of
            // the widened lobe it is D/D_wide, which only has mean 1.
            const bool off_weight =
                visible && std::fabs(rough.weight.r - smooth.weight.r) > 1e-2f * smooth.weight.r;
            if (dev > 2e-3f || off_weight) ++outliers;
            weight_sum += rough.weight.r, smooth_sum += smooth.weight.r;
            EXPECT_EQ(rough.eta, smooth.eta);
          }
          const double sigma = std::sqrt(f * (1 - f) / kN);
          EXPECT_NEAR(double(reflected) / kN, f, 5 * sigma + 1e-3) << "cos " << c << " η " << eta;
          // Beckmann's lobe has no tail: every sample is within the bounds. GGX's long tail
          // (P(tan θm > t) = α²/(α² + t²)) puts ~0.5 % of the normals beyond 15 α.
          if (type == MicrofacetType::kBeckmann) {
            EXPECT_EQ(outliers, 0) << "cos " << c << " η " << eta;
          } else {
            EXPECT_LT(outliers, kN / 50) << "cos " << c << " η " << eta;
          }
          // The mean weights: within 3 % (the D/D_wide ratio's spread over 4000 draws).
          EXPECT_NEAR(weight_sum / smooth_sum, 1.0, 0.03) << "cos " << c << " η " << eta;
        }
      }
    }
  }
}

// Beyond the critical angle (inside, θ = 72.5° > 41.8°) a smooth-ish Beckmann interface only
// reflects: no normal of α = 0.05 tilts far enough for light to escape. GGX's long tail lets
// a few rim normals (tilted > 70°) refract, as they physically would: fewer than 1 %.
TEST(RoughDielectric, TotalInternalReflectionReflects) {
  Pcg32 rng(8, 1);
  const Vec3f wo = bsdf_test::DirectionWithCos(-0.3f, 0.2f);
  for (MicrofacetType type : {MicrofacetType::kBeckmann, MicrofacetType::kGgx}) {
    const RoughDielectricParams p = Params(type, 0.05f, 0.05f, true, 1.5f);
    int refracted = 0, n = 0;
    for (int i = 0; i < 4000; ++i) {
      BsdfSample s;
      if (!RoughDielectricSample(p, wo, rng.NextFloat(), {rng.NextFloat(), rng.NextFloat()}, &s))
        continue;
      ++n;
      if (s.wi.z > 0) {
        ++refracted;
        continue;
      }
      EXPECT_GT(RoughDielectricPdf(p, wo, s.wi), 0.0f);
    }
    EXPECT_GT(n, 3900);
    if (type == MicrofacetType::kBeckmann) EXPECT_EQ(refracted, 0);
    EXPECT_LT(refracted, n / 100);
  }
}

// With the radiance scale, f(wo, wi) η_i² = f(wi, wo) η_o² (η_i, η_o: the IOR on wi's and wo's
// side; Veach 1997 §5.2 for the unscaled BTDF, whose ratio the scale inverts); reflection is
// symmetric.
TEST(RoughDielectric, GeneralisedReciprocity) {
  Pcg32 rng(2, 7);
  const float eta = 1.5f;
  for (MicrofacetType type : {MicrofacetType::kBeckmann, MicrofacetType::kGgx}) {
    const RoughDielectricParams p = Params(type, 0.3f, 0.2f, true, eta);
    int compared = 0;
    for (int i = 0; i < 4000; ++i) {
      // cos θ ≥ 0.1: at grazing angles the half vector, and so D, is ill-conditioned.
      // Named draws (a call's arguments are evaluated in an unspecified order).
      const float ca = 0.1f + 0.9f * rng.NextFloat(), pa = 6 * rng.NextFloat();
      const float cb = 0.1f + 0.9f * rng.NextFloat(), pb = 6 * rng.NextFloat();
      const Vec3f a = bsdf_test::DirectionWithCos(ca, pa);
      Vec3f b = bsdf_test::DirectionWithCos(cb, pb);
      if (i % 2) b.z = -b.z;
      const Color3f fab = RoughDielectricEval(p, a, b), fba = RoughDielectricEval(p, b, a);
      if (!(fab.r > 1e-6f)) continue;
      // Light grazing the microfacet (|a·h| < 0.05) refracts at the critical angle: 1 − F is
      // then small and computed from either side with an error of ~1e-4 absolute.
      const Vec3f h = Normalize(a + b * (b.z < 0 ? eta : 1.0f));
      if (std::fabs(Dot(a, h)) < 0.05f) continue;
      ++compared;
      // a is outside (η 1); b inside (η 1.5) for the refracted half.
      const float eta_b = b.z < 0 ? eta : 1.0f;
      EXPECT_NEAR(fab.r * eta_b * eta_b, fba.r, 1e-4f * fba.r) << i;
    }
    EXPECT_GT(compared, 1000);
  }
}

TEST(RoughDielectric, HardInputsStayFinite) {
  const std::vector<Vec3f> dirs = bsdf_test::HardDirections(true);
  size_t sampled = 0;
  for (MicrofacetType type : {MicrofacetType::kBeckmann, MicrofacetType::kGgx}) {
    for (bool visible : {true, false}) {
      for (float a : bsdf_test::HardAlphas()) {
        for (float eta : bsdf_test::HardEtas()) {
          const RoughDielectricParams p = Params(type, a, a * 100.0f, visible, eta);
          for (size_t i = 0; i < dirs.size(); ++i) {
            const Vec3f& wo = dirs[i];
            const Vec3f& wi = dirs[(i * 7 + 3) % dirs.size()];
            ASSERT_TRUE(IsFinite(RoughDielectricEval(p, wo, wi)));
            const float pdf = RoughDielectricPdf(p, wo, wi);
            ASSERT_TRUE(std::isfinite(pdf) && pdf >= 0);
            for (float u : bsdf_test::HardUs()) {
              BsdfSample s;
              if (!RoughDielectricSample(p, wo, u, {u, 1.0f - u}, &s)) continue;
              ++sampled;
              ASSERT_TRUE(IsFinite(s.weight) && std::isfinite(s.pdf) && s.pdf > 0);
              ASSERT_TRUE(std::isfinite(s.wi.x) && std::isfinite(s.wi.y) && std::isfinite(s.wi.z));
              ASSERT_TRUE(std::isfinite(s.eta) && s.eta > 0);
            }
          }
        }
      }
    }
  }
  EXPECT_GT(sampled, 1000u);
}

}  // namespace
}  // namespace ptlab
