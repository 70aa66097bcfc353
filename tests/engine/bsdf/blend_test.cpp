// Mitsuba `blendbsdf` (engine/bsdf/blend.h) and the two-sided flag (engine/bsdf/two_sided.h).
#include "engine/bsdf/blend.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/plastic_precompute.h"
#include "engine/core/rng.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"

namespace ptlab {
namespace {

TEST(Blend, EvalAndPdfAreTheMixture) {
  MaterialTables m;
  const MaterialRef a = m.AddDiffuse({0.8f, 0.2f, 0.4f});
  const MaterialRef b = m.AddConductor(0.3f, {0.2f, 0.4f, 1.4f}, {3, 2.7f, 1.8f});
  const MaterialRef ref = m.AddBlend(0.25f, a, b);
  Pcg32 rng(3, 5);
  for (int k = 0; k < 1000; ++k) {
    const Vec3f wo = bsdf_test::RandomUpperDirection(rng), wi = bsdf_test::RandomUpperDirection(rng);
    const Color3f f = BsdfEval(m, ref, wo, wi);
    const Color3f want = BsdfEval(m, a, wo, wi) * 0.75f + BsdfEval(m, b, wo, wi) * 0.25f;
    EXPECT_FLOAT_EQ(f.r, want.r); EXPECT_FLOAT_EQ(f.b, want.b);
    EXPECT_FLOAT_EQ(BsdfPdf(m, ref, wo, wi),
                    0.75f * BsdfPdf(m, a, wo, wi) + 0.25f * BsdfPdf(m, b, wo, wi));
  }
}

// A delta child's sample keeps its weight, and its pdf times the pick probability.
TEST(Blend, DeltaChildSampleIsScaledByThePick) {
  MaterialTables m;
  const MaterialRef ref =
      m.AddBlend(0.3f, m.AddDiffuse({0.5f, 0.5f, 0.5f}), m.AddMirror({0.9f, 0.9f, 0.9f}));
  const Vec3f wo = bsdf_test::DirectionWithCos(0.6f, 0.1f);
  BsdfSample s;
  ASSERT_TRUE(BsdfSampleDirection(m, ref, wo, 0.1f, {0.2f, 0.7f}, &s));  // 0.1 < 0.3: mirror
  EXPECT_TRUE(s.delta);
  EXPECT_FLOAT_EQ(s.pdf, 0.3f);
  EXPECT_FLOAT_EQ(s.weight.r, 0.9f);
  ASSERT_TRUE(BsdfSampleDirection(m, ref, wo, 0.6f, {0.2f, 0.7f}, &s));  // diffuse
  EXPECT_FALSE(s.delta);
  EXPECT_FLOAT_EQ(s.pdf, 0.7f * s.wi.z / kPi);
  EXPECT_FLOAT_EQ(s.weight.r, 0.5f);  // (0.7 · 0.5/π) cos / (0.7 cos/π)
}

// Energy: the blend of two white furnaces (a white diffuse and a white smooth plastic) has
// albedo 1 at every angle, and a blend's mean weight is the weighted mean of its children's.
TEST(Blend, WhiteFurnace) {
  MaterialTables m;
  PlasticDesc d;
  d.diffuse = {1, 1, 1}, d.int_ior = 1.5f, d.ext_ior = 1.0f;
  const MaterialRef ref = m.AddBlend(0.4f, m.AddDiffuse({1, 1, 1}), m.AddPlastic(*MakePlasticRow(d)));
  Pcg32 rng(5, 9);
  const int n = 200000;
  for (float c : {0.9f, 0.4f, 0.05f}) {
    const Vec3f wo = bsdf_test::DirectionWithCos(c, 2.0f);
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
      BsdfSample s;
      double w = 0;
      if (BsdfSampleDirection(m, ref, wo, rng.NextFloat(), {rng.NextFloat(), rng.NextFloat()}, &s))
        w = s.weight.r;
      sum += w, sum2 += w * w;
    }
    const double mean = sum / n, sd = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, 1.0, 5 * sd + 1e-4) << c;  // 5 standard errors (p < 1e-6)
  }
}

TEST(TwoSided, BelowIsTheMirrorImageOfAbove) {
  MaterialTables m;
  const MaterialRef one = m.AddDiffuse({0.5f, 0.4f, 0.3f});
  const MaterialRef two = m.AddDiffuse({0.5f, 0.4f, 0.3f});
  m.two_sided.Set(two);
  EXPECT_FALSE(m.two_sided.Of(one));
  EXPECT_TRUE(m.two_sided.Of(two));
  Pcg32 rng(1, 2);
  for (int k = 0; k < 200; ++k) {
    const Vec3f wo = bsdf_test::RandomUpperDirection(rng), wi = bsdf_test::RandomUpperDirection(rng);
    const Vec3f wo_b{wo.x, wo.y, -wo.z}, wi_b{wi.x, wi.y, -wi.z};
    EXPECT_EQ(BsdfEval(m, two, wo_b, wi_b).r, BsdfEval(m, one, wo, wi).r);
    EXPECT_EQ(BsdfPdf(m, two, wo_b, wi_b), BsdfPdf(m, one, wo, wi));
    EXPECT_TRUE(IsBlack(BsdfEval(m, one, wo_b, wi_b)));
    EXPECT_TRUE(IsBlack(BsdfEval(m, two, wo_b, wi)));  // still a BRDF: wi on wo's side only
    BsdfSample s, t;
    const float u = rng.NextFloat(), ux = rng.NextFloat(), uy = rng.NextFloat();
    ASSERT_TRUE(BsdfSampleDirection(m, two, wo_b, u, {ux, uy}, &s));
    ASSERT_TRUE(BsdfSampleDirection(m, one, wo, u, {ux, uy}, &t));
    EXPECT_EQ(s.wi.x, t.wi.x); EXPECT_EQ(s.wi.z, -t.wi.z);
    EXPECT_EQ(s.weight.g, t.weight.g); EXPECT_EQ(s.pdf, t.pdf);
  }
}

}  // namespace
}  // namespace ptlab
