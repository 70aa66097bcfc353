// For every BSDF model, old and new: the weight BsdfSampleDirection returns equals
// BsdfEval·|cos θi| / BsdfPdf at the direction it returns, and a white furnace (the mean sample
// weight, the albedo, is ≤ 1, and ≈ 1 where nothing is absorbed).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/conductor_presets.h"
#include "engine/bsdf/fresnel.h"
#include "engine/bsdf/microfacet.h"
#include "engine/core/rng.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"
#include "engine/bsdf/perturbed_frame.h"  // normal

namespace ptlab {
namespace {

struct Model {
  std::string name;
  MaterialTables m;
  MaterialRef ref;
  float alpha_min = 1;  // the smallest roughness (conditioning of the check below)
};

// Every model at a few roughnesses: the Nori-form conductor and rough plastic, the diffuse,
// and the Mitsuba forms (rough conductor, rough dielectric; GGX and Beckmann, visible normals
// or not, isotropic and 10:1 anisotropic).
std::vector<Model> NonDeltaModels() {
  std::vector<Model> models;
  const auto add = [&models](std::string name, float alpha_min, auto&& make) {
    Model m;
    m.name = std::move(name), m.alpha_min = std::max(alpha_min, kMicrofacetMinAlpha);
    m.ref = make(m.m);
    models.push_back(std::move(m));
  };
  Color3f au_eta, au_k;
  LookupConductorPreset("Au", &au_eta, &au_k);
  add("diffuse", 1, [](MaterialTables& m) { return m.AddDiffuse({0.8f, 0.5f, 0.2f}); });
  // mask: a mask of opacity 1 never passes through (its pass-through samples, a delta lobe, are
  // checked in mask_test.cpp): its Eval / Pdf are the nested model's times the opacity.
  add("mask_o1_diffuse", 1, [](MaterialTables& m) {
    return m.AddMask(1.0f, m.AddDiffuse({0.8f, 0.5f, 0.2f}));
  });
  add("mask_o1_rough_conductor", 0.1f, [&](MaterialTables& m) {
    return m.AddMask(1.0f, m.AddRoughConductor(0.1f, 0.3f, kMicrofacetSampleVisible, au_eta, au_k,
                                               {1, 1, 1}));
  });
  for (float a : {1e-4f, 0.01f, 0.1f, 0.5f, 1.0f}) {
    const std::string s = std::to_string(a);
    add("conductor_nori_a" + s, a, [&](MaterialTables& m) { return m.AddConductor(a, au_eta, au_k); });
    add("rough_plastic_a" + s, a, [&](MaterialTables& m) {
      return m.AddRoughPlastic(a, 1.5046f, 1.000277f, {0.3f, 0.4f, 0.5f});
    });
    for (uint8_t flags = 0; flags < 4; ++flags) {
      const std::string f = "_f" + std::to_string(flags);
      for (float ratio : {1.0f, 0.1f}) {
        const std::string r = ratio == 1 ? "" : "_aniso";
        add("rough_conductor_a" + s + f + r, a * ratio, [&](MaterialTables& m) {
          return m.AddRoughConductor(a, a * ratio, flags, au_eta, au_k, {1, 0.9f, 0.8f});
        });
        for (float eta : {1.5f, 1.0f / 1.33f}) {
          add("rough_dielectric_a" + s + f + r + "_eta" + std::to_string(eta), a * ratio,
              [&](MaterialTables& m) {
                return m.AddRoughDielectric(a, a * ratio, flags, eta, 1.0f, {1, 1, 1},
                                            {0.9f, 1, 1});
              });
        }
      }
    }
  }
  return models;
}

// Incident directions: normal, oblique, grazing, and (for the dielectric) from inside.
std::vector<Vec3f> Incidences() {
  return {bsdf_test::DirectionWithCos(1.0f, 0.0f), bsdf_test::DirectionWithCos(0.7f, 0.4f),
          bsdf_test::DirectionWithCos(0.2f, 2.0f), bsdf_test::DirectionWithCos(0.02f, 4.0f),
          bsdf_test::DirectionWithCos(-0.6f, 1.0f), bsdf_test::DirectionWithCos(-0.05f, 3.0f)};
}

// The tolerance of the weight check: 1e-3 relative, plus 1e-6/(α |cos θo|) because eval and
// pdf recompute the half vector from the returned wi while the rough dielectric's weight is
// that of the sampled normal (as Mitsuba's): the recomputed h is off by δ ≈ 1e-7/|cos θo| (wo + wi
// cancels at grazing angles), and D is steep: a δ tilt changes exp(−tan²/α²) by ~2 δ/α near
// the lobe; with D cos θ sampling the pdf's D and the eval's D have different widths, so it
// does not cancel (measured worst: 1.2e-2 at α = 1e-4, cos θo = 0.02). An algebra error (a
// missing factor of the weight) shows up as O(1).
TEST(BsdfWeight, SampleWeightIsEvalCosOverPdfForEveryModel) {
  Pcg32 rng(17, 2);
  for (const Model& model : NonDeltaModels()) {
    double worst = 0;
    int checked = 0;
    for (const Vec3f& wo : Incidences()) {
      const double tol = 1e-3 + 1e-6 / (model.alpha_min * std::fabs(wo.z));
      for (int i = 0; i < 1000; ++i) {
        BsdfSample s;
        const float u1 = rng.NextFloat();
        const Vec2f u2{rng.NextFloat(), rng.NextFloat()};
        if (!BsdfSampleDirection(model.m, model.ref, wo, u1, u2, &s)) continue;
        ASSERT_TRUE(IsFinite(s.weight) && std::isfinite(s.pdf) && s.pdf > 0) << model.name;
        ASSERT_FALSE(s.delta) << model.name;
        float pdf;
        const Color3f f = BsdfEvalPdf(model.m, model.ref, wo, s.wi, &pdf);
        // Where the recomputed pdf vanishes (the half vector lost to rounding, e.g. grazing
        // pairs) the ratio is undefined; such samples must be rare (counted below).
        if (!(pdf > 0)) continue;
        ++checked;
        for (int c = 0; c < 3; ++c) {
          const double expect = double(f[c]) * std::fabs(s.wi.z) / pdf;
          const double err = std::fabs(s.weight[c] - expect) / std::max(expect, 1e-6);
          worst = std::max(worst, err);
          ASSERT_LE(err, tol) << model.name << " wo " << wo.x << " " << wo.y << " " << wo.z
                              << " wi " << s.wi.x << " " << s.wi.y << " " << s.wi.z
                              << " weight " << s.weight[c] << " eval·cos/pdf " << expect;
        }
      }
    }
    EXPECT_GT(checked, 1000) << model.name;  // of 6000 draws (wo below: none for reflectors)
    std::printf("%-48s checked %5d  max rel %.2g\n", model.name.c_str(), checked, worst);
  }
}

// The white furnace: the albedo E[weight] (for refraction the flux, weight η_i²/η_o², since
// radiance is scaled by (η_o/η_i)²) from 3000 samples is ≤ 1 + 5σ for every model, and for
// the non-absorbing ones (conductor with F = 1: η = 0, κ = 1; the rough dielectric, all
// reflectances 1) at α = 0.01 and θo ≤ 60° it is, from 20000 samples, ≥ 0.99 (measured 0.995 … 1.0: a sharp lobe
// loses almost nothing below the horizon).
double Albedo(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, Pcg32& rng, int kN,
              double* sigma) {
  double sum = 0, sum2 = 0;
  for (int i = 0; i < kN; ++i) {
    BsdfSample s;
    const float u1 = rng.NextFloat();
    const Vec2f u2{rng.NextFloat(), rng.NextFloat()};
    if (!BsdfSampleDirection(m, ref, wo, u1, u2, &s)) continue;
    const double w = double(s.weight.g) * (s.eta != 1.0f ? double(s.eta) * s.eta : 1.0);
    sum += w, sum2 += w * w;
  }
  const double mean = sum / kN;
  *sigma = std::sqrt(std::max(0.0, sum2 / kN - mean * mean) / kN);
  return mean;
}

TEST(BsdfWeight, WhiteFurnaceAlbedoIsAtMostOne) {
  Pcg32 rng(23, 9);
  for (const Model& model : NonDeltaModels()) {
    for (const Vec3f& wo : Incidences()) {
      double sigma;
      const double a = Albedo(model.m, model.ref, wo, rng, 3000, &sigma);
      EXPECT_LE(a, 1.0 + 5 * sigma + 1e-6) << model.name << " cos θo " << wo.z;
    }
  }
  MaterialTables m, nori;
  std::vector<std::pair<const MaterialTables*, MaterialRef>> lossless;
  for (uint8_t flags = 0; flags < 4; ++flags) {
    lossless.push_back(
        {&m, m.AddRoughConductor(0.01f, 0.01f, flags, {0, 0, 0}, {1, 1, 1}, {1, 1, 1})});
    lossless.push_back({&m, m.AddRoughDielectric(0.01f, 0.01f, flags, 1.5f, 1.0f)});
  }
  lossless.push_back({&nori, nori.AddConductor(0.01f, {0, 0, 0}, {1, 1, 1})});
  for (const auto& [t, ref] : lossless) {
    for (float c : {1.0f, 0.7f, 0.5f, -0.9f}) {
      if (c < 0 && ref.tag() != MaterialTag::kRoughDielectric) continue;
      double sigma;
      const double a = Albedo(*t, ref, bsdf_test::DirectionWithCos(c, 0.3f), rng, 20000, &sigma);
      EXPECT_GE(a, 0.99) << int(ref.tag()) << " row " << ref.index() << " cos " << c;
      EXPECT_LE(a, 1.0 + 5 * sigma + 1e-6) << int(ref.tag()) << " row " << ref.index();
    }
  }
}

// The delta models: the weight is the closed form (mirror R; smooth conductor R F(cos θo);
// dielectric 1, or (η_o/η_i)² refracted with the radiance scale) and the pdf the lobe's
// probability.
TEST(BsdfWeight, DeltaModelsReturnTheirClosedFormWeights) {
  MaterialTables m;
  Color3f cu_eta, cu_k;
  LookupConductorPreset("Cu", &cu_eta, &cu_k);
  const MaterialRef mirror = m.AddMirror({0.9f, 0.8f, 0.7f});
  const MaterialRef metal = m.AddSmoothConductor(cu_eta, cu_k, {1, 0.5f, 1});
  const MaterialRef plain = m.AddMirror();  // a mirror row once the Fresnel columns exist
  const MaterialRef glass = m.AddDielectric(1.5f, 1.0f, kDielectricScaleRadiance);
  for (float c : {1.0f, 0.5f, 0.05f}) {
    const Vec3f wo = bsdf_test::DirectionWithCos(c, 0.5f);
    BsdfSample s;
    ASSERT_TRUE(BsdfSampleDirection(m, mirror, wo, 0.5f, {0.5f, 0.5f}, &s));
    EXPECT_TRUE(s.delta);
    EXPECT_EQ(s.weight.r, 0.9f);
    ASSERT_TRUE(BsdfSampleDirection(m, metal, wo, 0.5f, {0.5f, 0.5f}, &s));
    EXPECT_FLOAT_EQ(s.weight.r, FresnelConductor(c, cu_eta.r, cu_k.r));
    EXPECT_FLOAT_EQ(s.weight.g, 0.5f * FresnelConductor(c, cu_eta.g, cu_k.g));
    EXPECT_FLOAT_EQ(s.wi.z, wo.z);
    ASSERT_TRUE(BsdfSampleDirection(m, plain, wo, 0.5f, {0.5f, 0.5f}, &s));
    EXPECT_EQ(s.weight.r, 1.0f);  // η = κ = 0: F = 1 exactly
    ASSERT_TRUE(BsdfSampleDirection(m, glass, wo, 0.999f, {0.5f, 0.5f}, &s));  // refracts
    EXPECT_FLOAT_EQ(s.weight.r, 1.0f / (1.5f * 1.5f));
  }
}

// normal: rows whose frame a normal map (diffuse, 10:1 anisotropic GGX conductor) or a bump
// map (diffuse) perturbs keep the identity weight = Eval·|cos θi| / Pdf, with Eval's factor
// |cos θi'| / |cos θi| and the shadowing term (engine/bsdf/perturbed_frame.h), at random uv
// on a random 8 x 8 bitmap, with tangents that are not orthogonal to the normal.
TEST(BsdfWeight, PerturbedFramesKeepTheWeightIdentity) {
  Pcg32 rng(29, 3);
  TextureTable textures;
  const uint32_t bitmap = textures.AddRow(TextureKind::kBitmap, 8, 8, 3 * 64);
  for (size_t i = 0; i < 3 * 64; ++i) textures.data[i] = 0.2f + 0.6f * rng.NextFloat();
  Color3f al_eta, al_k;
  LookupConductorPreset("Al", &al_eta, &al_k);
  MaterialTables m;
  const MaterialRef rows[] = {
      m.AddDiffuse({0.8f, 0.5f, 0.2f}),
      m.AddRoughConductor(0.25f, 0.025f, kMicrofacetGgx | kMicrofacetSampleVisible, al_eta, al_k, {1, 1, 1}),
      m.AddDiffuse({0.3f, 0.6f, 0.9f})};
  ASSERT_TRUE(m.perturbation.Add(rows[0], PerturbationKind::kNormalMap, bitmap, 1));
  ASSERT_TRUE(m.perturbation.Add(rows[1], PerturbationKind::kNormalMap, bitmap, 1));
  ASSERT_TRUE(m.perturbation.Add(rows[2], PerturbationKind::kBumpMap, bitmap, 0.05f));
  const Vec3f du{1, 0.3f, 0.2f}, dv{-0.2f, 1, 0.1f};
  m.perturbation.dp_du_x = {du.x}, m.perturbation.dp_du_y = {du.y}, m.perturbation.dp_du_z = {du.z};
  m.perturbation.dp_dv_x = {dv.x}, m.perturbation.dp_dv_y = {dv.y}, m.perturbation.dp_dv_z = {dv.z};
  const Frame frame;
  const Vec3f ng{0, 0, 1};
  for (const MaterialRef ref : rows) {
    int checked = 0;
    double worst = 0;
    for (const Vec3f& wo : Incidences()) {
      if (wo.z < 0) continue;
      for (int i = 0; i < 2000; ++i) {
        TextureSite site;
        site.textures = &textures;
        site.at.uv = {rng.NextFloat(), rng.NextFloat()};
        site.frame = &frame, site.ng = &ng;
        BsdfSample s;
        const float u1 = rng.NextFloat();
        const Vec2f u2{rng.NextFloat(), rng.NextFloat()};
        if (!BsdfSampleDirection(m, ref, wo, u1, u2, &s, site)) continue;
        ASSERT_TRUE(IsFinite(s.weight) && std::isfinite(s.pdf) && s.pdf > 0);
        float pdf;
        const Color3f f = BsdfEvalPdf(m, ref, wo, s.wi, &pdf, site);
        if (!(pdf > 0)) continue;
        ++checked;
        for (int c = 0; c < 3; ++c) {
          const double expect = double(f[c]) * std::fabs(s.wi.z) / pdf;
          const double err = std::fabs(s.weight[c] - expect) / std::max(expect, 1e-6);
          worst = std::max(worst, err);
          ASSERT_LE(err, 1e-3 + 1e-6 / (0.025 * std::fabs(wo.z)))
              << "row " << int(ref.tag()) << " wo.z " << wo.z << " weight " << s.weight[c]
              << " eval·cos/pdf " << expect;
        }
      }
    }
    // Of 8000 draws (measured: 2981 normal-mapped diffuse, 1803 conductor, 7992 bump-mapped
    // diffuse; the random map tilts normals by up to ~40°, and samples that leave the perturbed
    // or the shading hemisphere are no samples).
    EXPECT_GT(checked, 1000) << int(ref.tag());
    std::printf("perturbed tag %d row %u: checked %d, max rel %.2g\n", int(ref.tag()),
                ref.index(), checked, worst);
  }
}

}  // namespace
}  // namespace ptlab

// principled: Mitsuba's principled and principledthin (their own block: the white furnace of
// these non-energy-conserving models is in principled_test.cpp). Parameter sets covering every
// lobe, roughness down to 0 (α = 0.001), anisotropic 1, η → 1; wo on both sides.
namespace ptlab {
namespace {

TEST(BsdfWeight, PrincipledSampleWeightIsEvalCosOverPdf) {
  struct Set {
    const char* name;
    bool thin;
    float roughness, anisotropic, metallic, spec_trans, clearcoat, sheen, eta, diff_trans;
  };
  const Set sets[] = {
      {"diffuse_sheen", false, 0.5f, 0, 0, 0, 0, 1, 1.5f, 0},
      {"metal_aniso_cc", false, 0.3f, 1, 0.7f, 0, 0.9f, 0.2f, 1.62f, 0},
      {"glass", false, 0.15f, 0.2f, 0, 0.7f, 0.6f, 0.9f, 1.38f, 0},
      {"glass_smooth", false, 0.0f, 0, 0, 1, 0, 0, 1.5f, 0},
      {"glass_eta1p001", false, 0.7f, 0.5f, 0.2f, 1, 0.3f, 0, 1.001f, 0},
      {"rough1", false, 1, 0, 0.5f, 0.5f, 1, 1, 1.2f, 0},
      {"thin", true, 0.5f, 0.8f, 0, 0.8f, 0, 0.8f, 1.33f, 0.7f},
      {"thin_smooth", true, 0.0f, 1, 0, 0.5f, 0, 0, 2.0f, 1},
      {"thin_rough", true, 1, 0, 0, 0.2f, 0, 0.3f, 1.05f, 0.2f},
  };
  Pcg32 rng(31, 7);
  for (const Set& set : sets) {
    MaterialTables m;
    PrincipledRow row;
    row.base_color = {0.7f, 0.4f, 0.2f};
    row.value[kPrincipledRoughness] = set.roughness;
    row.value[kPrincipledAnisotropic] = set.anisotropic;
    row.value[kPrincipledMetallic] = set.metallic;
    row.value[kPrincipledSpecTrans] = set.spec_trans;
    row.value[kPrincipledClearcoat] = set.clearcoat;
    row.value[kPrincipledSheen] = set.sheen;
    row.value[kPrincipledSheenTint] = 0.5f;
    row.value[kPrincipledSpecTint] = 0.5f;
    row.value[kPrincipledEta] = set.eta;
    row.value[kPrincipledDiffTrans] = 2 * set.diff_trans;
    const MaterialRef ref = m.AddPrincipled(row, set.thin);
    // α = roughness² ≥ 0.001 (and the thin transmission's scaled roughness).
    const float alpha_min = std::max(0.001f, set.roughness * set.roughness * 0.3f);
    double worst = 0;
    int checked = 0;
    for (const Vec3f& wo : Incidences()) {
      const double tol = 1e-3 + 1e-6 / (alpha_min * std::fabs(wo.z));
      for (int i = 0; i < 1000; ++i) {
        BsdfSample s;
        const float u1 = rng.NextFloat();
        const Vec2f u2{rng.NextFloat(), rng.NextFloat()};
        if (!BsdfSampleDirection(m, ref, wo, u1, u2, &s)) continue;
        ASSERT_TRUE(IsFinite(s.weight) && std::isfinite(s.pdf) && s.pdf > 0) << set.name;
        ASSERT_FALSE(s.delta) << set.name;
        float pdf;
        const Color3f f = BsdfEvalPdf(m, ref, wo, s.wi, &pdf);
        ASSERT_GT(pdf, 0) << set.name;
        ++checked;
        for (int c = 0; c < 3; ++c) {
          const double expect = double(f[c]) * std::fabs(s.wi.z) / pdf;
          const double err = std::fabs(s.weight[c] - expect) / std::max(expect, 1e-6);
          worst = std::max(worst, err);
          ASSERT_LE(err, tol) << set.name << " wo " << wo.x << " " << wo.y << " " << wo.z;
        }
      }
    }
    EXPECT_GT(checked, 1500) << set.name;
    std::printf("%-24s checked %5d  max rel %.2g\n", set.name, checked, worst);
  }
}

}  // namespace
}  // namespace ptlab
