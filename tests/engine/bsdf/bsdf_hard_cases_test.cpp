// Hard cases for every scalar BSDF: grazing/denormal/huge inputs never give NaN, Inf or < 0.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/conductor_presets.h"
#include "engine/bsdf/plastic_precompute.h"
#include "engine/core/rng.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"

namespace ptlab {
namespace {

// One row per hard parameter combination of every model.
std::vector<MaterialRef> HardMaterials(MaterialTables* m) {
  std::vector<MaterialRef> refs;
  for (float a : {0.0f, 0.5f, 1.0f, 1e30f}) refs.push_back(m->AddDiffuse({a, a, a}));
  refs.push_back(m->AddMirror());
  refs.push_back(m->AddMirror({0.0f, 0.25f, 1.0f}));
  for (float eta : bsdf_test::HardEtas())
    for (uint8_t flags : {0, int(kDielectricSchlick), int(kDielectricScaleRadiance),
                          int(kDielectricRefractOnly | kDielectricSchlick)})
      refs.push_back(m->AddDielectric(eta, 1.0f, flags));
  refs.push_back(m->AddDielectric(1.5f, 0.0f));
  for (float alpha : bsdf_test::HardAlphas()) {
    for (const char* name : {"Au", "none", "Si"}) {
      Color3f eta, k;
      LookupConductorPreset(name, &eta, &k);
      refs.push_back(m->AddConductor(alpha, eta, k));
    }
    refs.push_back(m->AddConductor(alpha, {1e30f, 1e30f, 1e30f}, {1e30f, 0.0f, 1e-40f}));
    refs.push_back(m->AddConductor(alpha, {1e-40f, 0.0f, 1.0f}, {0.0f, 1e-40f, 0.0f}));
    for (float kd : {0.0f, 0.5f, 1.0f})
      for (float int_ior : {1.5f, 1.0f, 1e30f})
        refs.push_back(m->AddRoughPlastic(alpha, int_ior, 1.0f, {kd, kd * 0.5f, kd}));
  }
  // matB: smooth plastics, thin dielectrics, blends (of a delta and a non-delta child, of a
  // plastic and a conductor), two-sided rows.
  for (float eta : bsdf_test::HardEtas()) {
    for (bool nonlinear : {false, true})
      for (float kd : {0.0f, 0.5f, 1.0f}) {
        PlasticDesc d;
        d.int_ior = eta, d.ext_ior = 1.0f, d.diffuse = {kd, kd * 0.5f, 1.0f}, d.nonlinear = nonlinear;
        refs.push_back(m->AddPlastic(*MakePlasticRow(d)));
      }
    refs.push_back(m->AddThinDielectric(eta, {1, 0.5f, 0}, {0, 0.5f, 1}));
  }
  for (float alpha : {1e-4f, 0.01f, 0.3f, 1.0f})
    for (CoatingDistribution dist : {CoatingDistribution::kGgx, CoatingDistribution::kBeckmann}) {
      PlasticDesc r;
      r.distribution = dist, r.alpha = alpha, r.int_ior = alpha < 0.1f ? 1.0f + 1e-6f : 1.5f;
      r.diffuse = {alpha, 1.0f, 0.0f}, r.nonlinear = alpha > 0.5f;
      refs.push_back(m->AddPlastic(*MakePlasticRow(r)));
    }
  PlasticDesc d;
  d.specular = {0, 0, 0};
  refs.push_back(m->AddPlastic(*MakePlasticRow(d)));
  d.diffuse = {0, 0, 0}, d.specular = {1, 1, 1};
  refs.push_back(m->AddPlastic(*MakePlasticRow(d)));
  const MaterialRef plastic = refs.back();
  for (float w : {0.0f, 0.3f, 1.0f}) {
    refs.push_back(m->AddBlend(w, m->AddDiffuse({0.5f, 0.5f, 0.5f}), m->AddMirror()));
    refs.push_back(m->AddBlend(w, plastic, m->AddConductor(0.2f, {0.2f, 0.4f, 1.4f}, {3, 2.7f, 1.8f})));
  }
  refs.push_back(m->AddBlend(0.5f, refs.back(), m->AddThinDielectric(1.5f)));
  for (MaterialRef r : {m->AddDiffuse({0.5f, 0.5f, 0.5f}), m->AddRoughPlastic(0.2f, 1.5f, 1.0f, {0.5f, 0.5f, 0.5f}),
                        m->AddPlastic(*MakePlasticRow(PlasticDesc{})), refs.back()}) {
    m->two_sided.Set(r);
    refs.push_back(r);
  }
  return refs;
}

bool Finite(const Vec3f& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

TEST(BsdfHardCases, NoNanInfOrNegativeValuesAnywhere) {
  MaterialTables m;
  const std::vector<MaterialRef> refs = HardMaterials(&m);
  const std::vector<Vec3f> dirs = bsdf_test::HardDirections();
  const std::vector<float> us = bsdf_test::HardUs();
  size_t evals = 0, samples = 0, valid = 0;
  for (MaterialRef ref : refs) {
    for (size_t a = 0; a < dirs.size(); ++a) {
      const Vec3f& wo = dirs[a];
      for (const Vec3f& wi : dirs) {
        const Color3f f = BsdfEval(m, ref, wo, wi);
        const float pdf = BsdfPdf(m, ref, wo, wi);
        ++evals;
        ASSERT_TRUE(IsFinite(f) && f.r >= 0 && f.g >= 0 && f.b >= 0 && std::isfinite(pdf) &&
                    pdf >= 0)
            << "tag " << int(ref.tag()) << " row " << ref.index() << " wo " << wo.x << "," << wo.y
            << "," << wo.z << " wi " << wi.x << "," << wi.y << "," << wi.z;
      }
      const bool unit = std::fabs(Length(wo) - 1.0f) < 1e-5f;
      for (float ul : {0.0f, 0.5f, kOneMinusEpsilon})
        for (float ux : us)
          for (float uy : {0.0f, 0.3f, kOneMinusEpsilon}) {
            BsdfSample s;
            ++samples;
            if (!BsdfSampleDirection(m, ref, wo, ul, {ux, uy}, &s)) continue;
            ++valid;
            ASSERT_TRUE(Finite(s.wi) && IsFinite(s.weight) && std::isfinite(s.pdf) && s.pdf > 0 &&
                        std::isfinite(s.eta) && s.eta > 0)
                << "tag " << int(ref.tag()) << " row " << ref.index() << " wo " << wo.x << ","
                << wo.y << "," << wo.z << " u " << ul << "," << ux << "," << uy;
            ASSERT_TRUE(s.weight.r >= 0 && s.weight.g >= 0 && s.weight.b >= 0);
            if (!unit) continue;
            ASSERT_NEAR(Length(s.wi), 1.0f, 1e-4f) << "tag " << int(ref.tag());
            if (IsDeltaMaterial(ref.tag()) || s.delta) continue;
            // Below |cos θi| = 1e-30, f |cos θi| is a denormal with few significant bits (as in
            // bsdf8_test: finiteness only there).
            if (std::fabs(s.wi.z) < 1e-30f) continue;
            // weight = Eval cos / Pdf for the sampled direction.
            const Color3f f = BsdfEval(m, ref, wo, s.wi);
            const float pdf = BsdfPdf(m, ref, wo, s.wi);
            ASSERT_EQ(pdf, s.pdf);
            for (int c = 0; c < 3; ++c) {
              const float ref_w = f[c] * std::fabs(s.wi.z) / pdf;  // f |cos θi| / pdf
              ASSERT_NEAR(s.weight[c], ref_w, 1e-4f * std::fabs(ref_w) + 1e-20f)
                  << "tag " << int(ref.tag()) << " row " << ref.index() << " wo.z " << wo.z;
            }
          }
    }
  }
  EXPECT_GT(valid, samples / 5);
  EXPECT_GT(evals, 100000u);
}

// BsdfEvalPdf is BsdfEval and BsdfPdf bit for bit (the emitter samples' MIS reads it instead of
// the two): every hard material, on the hard directions and on random unit ones.
TEST(BsdfHardCases, EvalPdfIsEvalAndPdf) {
  MaterialTables m;
  const std::vector<MaterialRef> refs = HardMaterials(&m);
  std::vector<Vec3f> dirs = bsdf_test::HardDirections();
  Pcg32 rng(11, 3);
  for (int k = 0; k < 64; ++k) {
    const Vec3f v{rng.NextFloat() * 2 - 1, rng.NextFloat() * 2 - 1, rng.NextFloat() * 2 - 1};
    if (Length(v) > 1e-3f) dirs.push_back(Normalize(v));
  }
  const auto bits = [](float x) { return std::bit_cast<uint32_t>(x); };
  size_t positive = 0;
  for (MaterialRef ref : refs) {
    for (const Vec3f& wo : dirs) {
      for (const Vec3f& wi : dirs) {
        float pdf = -1.0f;
        const Color3f f = BsdfEvalPdf(m, ref, wo, wi, &pdf);
        const Color3f want_f = BsdfEval(m, ref, wo, wi);
        ASSERT_EQ(bits(pdf), bits(BsdfPdf(m, ref, wo, wi))) << "tag " << int(ref.tag());
        ASSERT_TRUE(bits(f.r) == bits(want_f.r) && bits(f.g) == bits(want_f.g) &&
                    bits(f.b) == bits(want_f.b))
            << "tag " << int(ref.tag()) << " row " << ref.index();
        positive += pdf > 0;
      }
    }
  }
  EXPECT_GT(positive, 10000u);
}

TEST(BsdfHardCases, WoBelowTheSurface) {
  MaterialTables m;
  const Vec3f below = bsdf_test::DirectionWithCos(-0.3f, 0.2f);
  const Vec3f above = bsdf_test::DirectionWithCos(0.7f, 1.2f);
  for (MaterialRef ref : {m.AddDiffuse({0.5f, 0.5f, 0.5f}), m.AddMirror(),
                          m.AddConductor(0.2f, {0.2f, 0.4f, 1.4f}, {3, 2.7f, 1.8f}),
                          m.AddRoughPlastic(0.2f, 1.5f, 1.0f, {0.5f, 0.5f, 0.5f})}) {
    BsdfSample s;
    EXPECT_FALSE(BsdfSampleDirection(m, ref, below, 0.3f, {0.4f, 0.6f}, &s)) << int(ref.tag());
    EXPECT_TRUE(IsBlack(BsdfEval(m, ref, below, above)));
    EXPECT_TRUE(IsBlack(BsdfEval(m, ref, above, below)));
    EXPECT_EQ(BsdfPdf(m, ref, below, above), 0.0f);
    EXPECT_EQ(BsdfPdf(m, ref, above, below), 0.0f);
  }
  // The dielectric is two-sided: wo below means "inside".
  BsdfSample s;
  EXPECT_TRUE(BsdfSampleDirection(m, m.AddDielectric(1.5f, 1.0f), below, 0.99f, {0, 0}, &s));
}

TEST(BsdfHardCases, ExactlyGrazingWo) {
  MaterialTables m;
  const Vec3f grazing{1.0f, 0.0f, 0.0f};
  for (MaterialRef ref : {m.AddDiffuse({0.5f, 0.5f, 0.5f}), m.AddMirror(),
                          m.AddConductor(0.2f, {0.2f, 0.4f, 1.4f}, {3, 2.7f, 1.8f}),
                          m.AddRoughPlastic(0.2f, 1.5f, 1.0f, {0.5f, 0.5f, 0.5f})}) {
    BsdfSample s;
    EXPECT_FALSE(BsdfSampleDirection(m, ref, grazing, 0.3f, {0.4f, 0.6f}, &s)) << int(ref.tag());
    EXPECT_TRUE(IsBlack(BsdfEval(m, ref, grazing, {0, 0, 1})));
  }
  // A smooth dielectric reflects everything at exactly grazing incidence (F = 1).
  BsdfSample s;
  ASSERT_TRUE(
      BsdfSampleDirection(m, m.AddDielectric(1.5f, 1.0f), grazing, kOneMinusEpsilon, {0, 0}, &s));
  EXPECT_EQ(s.pdf, 1.0f);
  EXPECT_EQ(s.wi, (Vec3f{-1.0f, 0.0f, 0.0f}));
}

}  // namespace
}  // namespace ptlab
