// Mitsuba `plastic` (engine/bsdf/plastic.h) and its load-time terms (plastic_precompute.h).
#include "engine/bsdf/plastic.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/plastic_precompute.h"
#include "engine/core/rng.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"

namespace ptlab {
namespace {

MaterialRef AddPlastic(MaterialTables* m, float int_ior, const Color3f& diffuse, bool nonlinear,
                       const Color3f& specular = {1, 1, 1}) {
  PlasticDesc d;
  d.int_ior = int_ior, d.ext_ior = 1.0f, d.diffuse = diffuse, d.nonlinear = nonlinear;
  d.specular = specular;
  StatusOr<PlasticRow> row = MakePlasticRow(d);
  EXPECT_TRUE(row.ok());
  return m->AddPlastic(*row);
}

// The internal hemispherical reflectance against an independent route: reciprocity of the
// smooth interface, 1 − F_int(η) = (1 − F_ext(η)) / η², with F_ext(η) = 2 ∫ F(μ) μ dμ from
// outside integrated here by a plain midpoint rule (no TIR from outside for η > 1).
TEST(Plastic, InternalDiffuseFresnelMatchesReciprocity) {
  EXPECT_NEAR(InternalDiffuseFresnel(1.0), 0.0, 1e-7);
  for (double eta : {1.1, 1.333, 1.49, 1.5046, 2.0, 3.0}) {
    const int n = 200000;
    double ext = 0;
    for (int i = 0; i < n; ++i) {
      const double mu = (i + 0.5) / n;
      float cos_t;
      ext += 2.0 * FresnelDielectric(float(mu), float(eta), &cos_t) * mu / n;
    }
    EXPECT_NEAR(1.0 - InternalDiffuseFresnel(eta), (1.0 - ext) / (eta * eta), 2e-6) << eta;
  }
}

// Albedo of the whole BSDF (delta lobe included) at wo, by sampling: E[weight]. With ρ_d = 1
// and the linear model it is exactly 1 (reciprocity above makes the diffuse part 1 − F_o);
// otherwise F_o + (1 − F_o) ρ (1 − F_int) / (1 − ρ F_int) (nonlinear) or ρ (linear).
TEST(Plastic, WhiteFurnaceMatchesTheClosedForm) {
  MaterialTables m;
  Pcg32 rng(7, 1);
  const int n = 200000;
  for (bool nonlinear : {false, true}) {
    for (float rho : {1.0f, 0.6f, 0.1f}) {
      for (float eta : {1.5f, 1.1f}) {
        const MaterialRef ref = AddPlastic(&m, eta, {rho, rho, rho}, nonlinear);
        const double f_int = InternalDiffuseFresnel(eta);
        for (float c : {0.95f, 0.5f, 0.1f}) {
          const Vec3f wo = bsdf_test::DirectionWithCos(c, 0.4f);
          float cos_t;
          const double f_o = FresnelDielectric(c, eta, &cos_t);
          const double want =
              nonlinear ? f_o + (1 - f_o) * rho * (1 - f_int) / (1 - rho * f_int)
                        : f_o + (1 - f_o) * rho;
          double sum = 0, sum2 = 0;
          for (int i = 0; i < n; ++i) {
            BsdfSample s;
            double w = 0;
            if (BsdfSampleDirection(m, ref, wo, rng.NextFloat(),
                                    {rng.NextFloat(), rng.NextFloat()}, &s))
              w = s.weight.g;
            sum += w, sum2 += w * w;
          }
          const double mean = sum / n, sd = std::sqrt((sum2 / n - mean * mean) / n);
          // 5 standard errors: a false failure has probability < 1e-6 per case.
          EXPECT_NEAR(mean, want, 5 * sd + 1e-6) << nonlinear << " " << rho << " " << eta << " "
                                                 << c;
          EXPECT_LE(mean, 1.0 + 5 * sd);
        }
      }
    }
  }
}

// The delta lobe: mirror direction, flagged, chosen with Mitsuba's probability
// F w_s / (F w_s + (1 − F)(1 − w_s)).
TEST(Plastic, DeltaLobeIsTheMirrorWithMitsubasProbability) {
  MaterialTables m;
  const MaterialRef ref = AddPlastic(&m, 1.5f, {0.5f, 0.2f, 0.1f}, false, {0.8f, 0.8f, 0.8f});
  const Vec3f wo = bsdf_test::DirectionWithCos(0.3f, 1.0f);
  float cos_t;
  const float f = FresnelDielectric(0.3f, 1.5f, &cos_t);
  const float ws = 0.8f / (0.8f + 0.8f / 3.0f);
  const float ps = f * ws / (f * ws + (1 - f) * (1 - ws));
  BsdfSample s;
  ASSERT_TRUE(BsdfSampleDirection(m, ref, wo, ps * 0.999f, {0.3f, 0.3f}, &s));
  EXPECT_TRUE(s.delta);
  EXPECT_FLOAT_EQ(s.wi.x, -wo.x);
  EXPECT_FLOAT_EQ(s.wi.z, wo.z);
  EXPECT_NEAR(s.pdf, ps, 1e-6f);
  EXPECT_NEAR(s.weight.r, 0.8f * f / ps, 1e-5f);
  ASSERT_TRUE(BsdfSampleDirection(m, ref, wo, ps * 1.001f, {0.3f, 0.3f}, &s));
  EXPECT_FALSE(s.delta);
  EXPECT_NEAR(s.pdf, (1 - ps) * s.wi.z / kPi, 1e-6f);
  EXPECT_FALSE(IsDeltaMaterial(MaterialTag::kPlastic));
  EXPECT_TRUE(MixesDeltaLobes(MaterialTag::kPlastic));
}

TEST(Plastic, OneSided) {
  MaterialTables m;
  const MaterialRef ref = AddPlastic(&m, 1.5f, {0.5f, 0.5f, 0.5f}, false);
  const Vec3f below = bsdf_test::DirectionWithCos(-0.3f, 0.2f);
  const Vec3f above = bsdf_test::DirectionWithCos(0.7f, 1.2f);
  BsdfSample s;
  EXPECT_FALSE(BsdfSampleDirection(m, ref, below, 0.3f, {0.4f, 0.6f}, &s));
  EXPECT_TRUE(IsBlack(BsdfEval(m, ref, below, above)));
  EXPECT_TRUE(IsBlack(BsdfEval(m, ref, above, below)));
  EXPECT_EQ(BsdfPdf(m, ref, above, below), 0.0f);
}

}  // namespace
}  // namespace ptlab

namespace ptlab {
namespace {

MaterialRef AddRough(MaterialTables* m, CoatingDistribution dist, float alpha, float rho,
                     bool nonlinear) {
  PlasticDesc d;
  d.distribution = dist, d.alpha = alpha, d.int_ior = 1.5f, d.ext_ior = 1.0f;
  d.diffuse = {rho, rho, rho}, d.nonlinear = nonlinear;
  StatusOr<PlasticRow> row = MakePlasticRow(d);
  EXPECT_TRUE(row.ok());
  return m->AddPlastic(*row);
}

// The rough coating's transmittance table tends to the smooth 1 − F as α → 0 (a different
// route: the Fresnel term of the smooth interface, no microfacets), and stays in [0, 1].
TEST(RoughPlasticCoating, TransmittanceTendsToTheSmoothLimit) {
  MaterialTables m;
  for (CoatingDistribution dist : {CoatingDistribution::kGgx, CoatingDistribution::kBeckmann}) {
    const MaterialRef ref = AddRough(&m, dist, 1e-3f, 0.5f, false);
    const float* t = m.plastic.transmittance.data() + ref.index() * kCoatingTransmittanceRes;
    for (int j = 0; j < kCoatingTransmittanceRes; ++j) {
      const float mu = float(j) / float(kCoatingTransmittanceRes - 1);
      EXPECT_GE(t[j], 0.0f); EXPECT_LE(t[j], 1.0f);
      if (mu < 0.1f) continue;  // near grazing even α = 1e-3 shadows measurably
      EXPECT_NEAR(t[j], 1.0f - CoatingFresnel(mu, 1.5f), 5e-3f) << int(dist) << " " << mu;
    }
    const MaterialRef rough = AddRough(&m, dist, 1.0f, 0.5f, false);
    const float* r = m.plastic.transmittance.data() + rough.index() * kCoatingTransmittanceRes;
    for (int j = 0; j < kCoatingTransmittanceRes; ++j) { EXPECT_GE(r[j], 0.0f); EXPECT_LE(r[j], 1.0f); }
  }
}

// Energy: the albedo E[weight] of a rough plastic with ρ = 1 (the most reflective base) is at
// most 1 at every angle and roughness (single-scattering microfacets lose a little), and not
// far below the smooth plastic's exact 1 for a moderately rough coating.
TEST(RoughPlasticCoating, WhiteFurnaceIsAtMostOne) {
  MaterialTables m;
  Pcg32 rng(17, 4);
  const int n = 100000;
  for (CoatingDistribution dist : {CoatingDistribution::kGgx, CoatingDistribution::kBeckmann})
    for (float alpha : {1e-3f, 0.1f, 0.5f, 1.0f})
      for (bool nonlinear : {false, true}) {
        const MaterialRef ref = AddRough(&m, dist, alpha, 1.0f, nonlinear);
        for (float c : {0.9f, 0.5f, 0.1f}) {
          const Vec3f wo = bsdf_test::DirectionWithCos(c, 1.1f);
          double sum = 0, sum2 = 0;
          for (int i = 0; i < n; ++i) {
            BsdfSample s;
            double w = 0;
            if (BsdfSampleDirection(m, ref, wo, rng.NextFloat(),
                                    {rng.NextFloat(), rng.NextFloat()}, &s))
              w = s.weight.r;
            sum += w, sum2 += w * w;
          }
          const double mean = sum / n, sd = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
          EXPECT_LE(mean, 1.0 + 5 * sd) << int(dist) << " " << alpha << " " << c;
          if (alpha <= 0.1f && c >= 0.5f) EXPECT_GT(mean, 0.9) << int(dist) << " " << alpha;
        }
      }
}

}  // namespace
}  // namespace ptlab
