// Mitsuba `mask` (engine/bsdf/mask.h) and the textured parameters added with it: a blend's
// weight and a rough conductor's αu, αv (TexturedFloat, engine/texture/texture_site.h).
#include "engine/bsdf/mask.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/bsdf/blend.h"
#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/conductor_presets.h"
#include "engine/core/rng.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"

namespace ptlab {
namespace {

// A checkerboard with one-channel colours v0, v1 (r = g = b): its value at uv.
uint32_t AddChecker(TextureTable* t, float v0, float v1) {
  const uint32_t id = t->AddRow(TextureKind::kCheckerboard, 1, 1, 6);
  for (int k = 0; k < 3; ++k) t->data[t->offset[id] + k] = v0, t->data[t->offset[id] + 3 + k] = v1;
  return id;
}

struct Masks {
  MaterialTables m;
  std::vector<MaterialRef> nested, masks;
  std::vector<float> opacity;
};

// Masks with constant opacities (the ends 0 and 1, a denormal, 1 − ulp) over a diffuse, a
// two-sided diffuse, a rough conductor and a mirror (a delta nested material).
Masks MakeMasks() {
  Masks s;
  Color3f eta, k;
  LookupConductorPreset("Au", &eta, &k);
  const MaterialRef twosided = s.m.AddDiffuse({0.1f, 0.8f, 0.1f});
  s.m.two_sided.Set(twosided);
  const MaterialRef kids[] = {s.m.AddDiffuse({0.8f, 0.5f, 0.2f}), twosided,
                              s.m.AddRoughConductor(0.2f, 0.05f, kMicrofacetSampleVisible, eta, k,
                                                    {1, 1, 1}),
                              s.m.AddMirror({0.9f, 0.8f, 0.7f})};
  for (const MaterialRef kid : kids)
    for (float o : {0.0f, 1e-40f, 0.3f, 0.7f, 0x1.fffffep-1f, 1.0f}) {
      s.nested.push_back(kid), s.opacity.push_back(o);
      s.masks.push_back(s.m.AddMask(o, kid));
    }
  return s;
}

// f and pdf are the nested material's times the opacity, bit for bit.
TEST(Mask, EvalAndPdfAreTheNestedScaledByOpacity) {
  const Masks s = MakeMasks();
  Pcg32 rng(3, 1);
  for (size_t j = 0; j < s.masks.size(); ++j)
    for (int i = 0; i < 200; ++i) {
      Vec3f wo = bsdf_test::RandomUpperDirection(rng), wi = bsdf_test::RandomUpperDirection(rng);
      if (i % 4 == 0) wo.z = -wo.z;  // the two-sided child flips
      const Color3f f = BsdfEval(s.m, s.masks[j], wo, wi), g = BsdfEval(s.m, s.nested[j], wo, wi);
      EXPECT_EQ(f.r, g.r * s.opacity[j]);
      EXPECT_EQ(f.g, g.g * s.opacity[j]);
      EXPECT_EQ(BsdfPdf(s.m, s.masks[j], wo, wi), BsdfPdf(s.m, s.nested[j], wo, wi) * s.opacity[j]);
      float p = -1;
      const Color3f h = BsdfEvalPdf(s.m, s.masks[j], wo, wi, &p);
      EXPECT_EQ(h.b, f.b);
      EXPECT_EQ(p, BsdfPdf(s.m, s.masks[j], wo, wi));
    }
}

// Every sample is either the pass-through (wi = −wo, weight 1, pdf 1 − opacity, a delta lobe) or
// the nested material's, with its pdf times the opacity: for a non-delta nested sample that is
// the mask's Pdf and weight = Eval·|cos|/Pdf (to 1e-3, as BsdfWeight checks every model); a
// delta nested sample keeps the nested weight. The pass-through frequency is 1 − opacity
// (binomial, within 5σ of 20000 draws).
TEST(Mask, SamplesArePassThroughOrNested) {
  const Masks s = MakeMasks();
  Pcg32 rng(7, 3);
  for (size_t j = 0; j < s.masks.size(); ++j) {
    const float o = s.opacity[j];
    const bool delta_kid = s.nested[j].tag() == MaterialTag::kMirror;
    for (float c : {0.8f, 0.3f, -0.5f}) {
      const Vec3f wo = bsdf_test::DirectionWithCos(c, 0.4f);
      const int n = 20000;
      int through = 0;
      for (int i = 0; i < n; ++i) {
        BsdfSample b;
        const float u1 = rng.NextFloat();
        const Vec2f u2{rng.NextFloat(), rng.NextFloat()};
        if (!BsdfSampleDirection(s.m, s.masks[j], wo, u1, u2, &b)) {
          ASSERT_LT(u1, o) << "a pass-through always succeeds";
          continue;
        }
        ASSERT_TRUE(IsFinite(b.weight) && std::isfinite(b.pdf) && b.pdf > 0);
        if (!(u1 < o)) {
          ++through;
          EXPECT_EQ(b.wi.x, -wo.x); EXPECT_EQ(b.wi.y, -wo.y); EXPECT_EQ(b.wi.z, -wo.z);
          EXPECT_EQ(b.weight.r, 1.0f); EXPECT_EQ(b.weight.b, 1.0f);
          EXPECT_EQ(b.pdf, 1.0f - o);
          EXPECT_TRUE(b.delta);
          EXPECT_EQ(b.eta, 1.0f);
          continue;
        }
        EXPECT_EQ(b.delta, delta_kid);
        if (delta_kid) {
          EXPECT_EQ(b.pdf, o);
          EXPECT_EQ(b.weight.r, 0.9f);
          continue;
        }
        float pdf;
        const Color3f f = BsdfEvalPdf(s.m, s.masks[j], wo, b.wi, &pdf);
        ASSERT_GT(pdf, 0);
        EXPECT_NEAR(b.pdf, pdf, 1e-3 * pdf);
        for (int ch = 0; ch < 3; ++ch) {
          const double want = double(f[ch]) * std::fabs(b.wi.z) / pdf;
          EXPECT_NEAR(b.weight[ch], want, 1e-3 * std::max(want, 1e-6));
        }
      }
      const double p = 1.0 - double(o), sigma = std::sqrt(p * (1 - p) / n);
      EXPECT_NEAR(double(through) / n, p, 5 * sigma + 1e-9) << "opacity " << o;
    }
  }
}

// Energy: a mask over a white diffuse passes or reflects everything: the mean sample weight
// over wo above the surface is 1 (5σ of 40000 draws) for every opacity; over an absorbing
// nested material it is opacity · albedo + (1 − opacity).
TEST(Mask, WhiteFurnace) {
  MaterialTables m;
  const MaterialRef white = m.AddDiffuse({1, 1, 1}), grey = m.AddDiffuse({0.5f, 0.5f, 0.5f});
  Pcg32 rng(11, 2);
  for (float o : {0.0f, 0.25f, 0.9f, 1.0f})
    for (const MaterialRef kid : {white, grey}) {
      const MaterialRef ref = m.AddMask(o, kid);
      const Vec3f wo = bsdf_test::DirectionWithCos(0.6f, 1.0f);
      const int n = 40000;
      double sum = 0, sum2 = 0;
      for (int i = 0; i < n; ++i) {
        BsdfSample b;
        if (!BsdfSampleDirection(m, ref, wo, rng.NextFloat(), {rng.NextFloat(), rng.NextFloat()},
                                 &b))
          continue;
        sum += b.weight.g, sum2 += double(b.weight.g) * b.weight.g;
      }
      const double mean = sum / n, sigma = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
      const double want = o * (kid == white ? 1.0 : 0.5) + (1.0 - o);
      EXPECT_NEAR(mean, want, 5 * sigma + 1e-6) << "opacity " << o;
    }
}

// A textured opacity: the texture's value at the site, clipped to [0, 1]; the sample's pick
// follows it.
TEST(Mask, TexturedOpacityIsTheTextureAtTheSite) {
  TextureTable textures;
  const uint32_t checker = AddChecker(&textures, 0.25f, 1.75f);  // 1.75 clips to 1
  MaterialTables m;
  const MaterialRef kid = m.AddDiffuse({0.5f, 0.5f, 0.5f});
  const MaterialRef ref = m.AddMask(0.5f, kid, checker);
  const MaterialRef constant = m.AddMask(0.5f, kid);  // a constant row after a textured one
  EXPECT_EQ(m.mask.opacity_texture.size(), 2u);
  const Vec3f wo = bsdf_test::DirectionWithCos(0.7f, 0.2f), wi = bsdf_test::DirectionWithCos(0.5f, 2.0f);
  for (const Vec2f uv : {Vec2f{0.25f, 0.25f}, Vec2f{0.75f, 0.25f}}) {
    const TextureSite site{&textures, {uv, {0, 0, 0}, 0}};
    const float v = TexturedFloat(m.mask.opacity_texture, ref.index(), 0.5f, site);
    const float o = MaskOpacity(m.mask, ref.index(), site);
    EXPECT_EQ(o, std::min(v, 1.0f));
    EXPECT_EQ(BsdfEval(m, ref, wo, wi, site).r, BsdfEval(m, kid, wo, wi).r * o);
    EXPECT_EQ(BsdfEval(m, constant, wo, wi, site).r, BsdfEval(m, kid, wo, wi).r * 0.5f);
    BsdfSample b;
    ASSERT_TRUE(BsdfSampleDirection(m, ref, wo, 0.5f, {0.3f, 0.3f}, &b, site));
    EXPECT_EQ(b.wi.z == -wo.z, !(0.5f < o));  // 0.25: passes; 1: the nested diffuse
  }
}

// A blend's textured weight: BlendWeight is the texture at the site, clipped to [0, 1], and the
// children see the same site.
TEST(Mask, BlendWithTexturedWeightMixesWithTheTexture) {
  TextureTable textures;
  const uint32_t checker = AddChecker(&textures, 0.2f, -0.5f);  // −0.5 clips to 0
  const uint32_t albedo = AddChecker(&textures, 0.9f, 0.1f);
  MaterialTables m;
  const MaterialRef a = m.AddDiffuse({0.0f, 0.5f, 0.5f}), b = m.AddTexturedDiffuse(albedo);
  const MaterialRef ref = m.AddBlend(0.5f, a, b, checker);
  const MaterialRef plain = m.AddBlend(0.5f, a, b);
  const Vec3f wo = bsdf_test::DirectionWithCos(0.7f, 0.2f), wi = bsdf_test::DirectionWithCos(0.5f, 2.0f);
  for (const Vec2f uv : {Vec2f{0.25f, 0.25f}, Vec2f{0.75f, 0.25f}}) {
    const TextureSite site{&textures, {uv, {0, 0, 0}, 0}};
    const float w = BlendWeight(m.blend, ref.index(), site);
    EXPECT_EQ(w, uv.x < 0.5f ? TexturedFloat(m.blend.weight_texture, ref.index(), 0, site) : 0.0f);
    const Color3f f = BsdfEval(m, ref, wo, wi, site);
    const Color3f want = BsdfEval(m, a, wo, wi, site) * (1.0f - w) + BsdfEval(m, b, wo, wi, site) * w;
    EXPECT_EQ(f.r, want.r); EXPECT_EQ(f.g, want.g);
    EXPECT_EQ(BlendWeight(m.blend, plain.index(), site), 0.5f);
  }
}

// A rough conductor's textured αu, αv: the row evaluates as a constant row with the textures'
// values, bit for bit.
TEST(Mask, RoughConductorWithTexturedAlphaIsTheConstantRowAtTheSite) {
  TextureTable textures;
  const uint32_t tu = AddChecker(&textures, 0.05f, 0.3f);
  const uint32_t tv = AddChecker(&textures, 0.3f, 0.05f);
  Color3f eta, k;
  LookupConductorPreset("Cu", &eta, &k);
  MaterialTables m;
  const MaterialRef ref =
      m.AddTexturedRoughConductor(0.1f, 0.1f, tu, tv, kMicrofacetSampleVisible, eta, k, {1, 1, 1});
  Pcg32 rng(5, 5);
  for (const Vec2f uv : {Vec2f{0.25f, 0.25f}, Vec2f{0.75f, 0.25f}}) {
    const TextureSite site{&textures, {uv, {0, 0, 0}, 0}};
    MaterialTables c;
    const MaterialRef same = c.AddRoughConductor(
        TexturedFloat(m.conductor.alpha_texture, 0, 0, site),
        TexturedFloat(m.conductor.alpha_v_texture, 0, 0, site), kMicrofacetSampleVisible, eta, k,
        {1, 1, 1});
    EXPECT_NEAR(c.conductor.alpha[0], uv.x < 0.5f ? 0.05f : 0.3f, 1e-7f);
    for (int i = 0; i < 100; ++i) {
      const Vec3f wo = bsdf_test::RandomUpperDirection(rng), wi = bsdf_test::RandomUpperDirection(rng);
      EXPECT_EQ(BsdfEval(m, ref, wo, wi, site).r, BsdfEval(c, same, wo, wi).r);
      EXPECT_EQ(BsdfPdf(m, ref, wo, wi, site), BsdfPdf(c, same, wo, wi));
      BsdfSample s0, s1;
      const float u1 = rng.NextFloat();
      const Vec2f u2{rng.NextFloat(), rng.NextFloat()};
      EXPECT_EQ(BsdfSampleDirection(m, ref, wo, u1, u2, &s0, site),
                BsdfSampleDirection(c, same, wo, u1, u2, &s1));
      EXPECT_EQ(s0.wi.x, s1.wi.x); EXPECT_EQ(s0.weight.g, s1.weight.g);
    }
  }
}

// A rough dielectric's textured αu, αv: the row evaluates and samples as a constant row with the
// textures' values, bit for bit (reflection and refraction).
TEST(Mask, RoughDielectricWithTexturedAlphaIsTheConstantRowAtTheSite) {
  TextureTable textures;
  const uint32_t tu = AddChecker(&textures, 0.05f, 0.3f);
  const uint32_t tv = AddChecker(&textures, 0.3f, 0.05f);
  MaterialTables m;
  const MaterialRef ref = m.AddTexturedRoughDielectric(0.1f, 0.1f, tu, tv,
                                                       kMicrofacetGgx | kMicrofacetSampleVisible,
                                                       1.5f, 1.0f, {1, 1, 1}, {1, 1, 1});
  Pcg32 rng(7, 5);
  int refracted = 0;
  for (const Vec2f uv : {Vec2f{0.25f, 0.25f}, Vec2f{0.75f, 0.25f}}) {
    const TextureSite site{&textures, {uv, {0, 0, 0}, 0}};
    MaterialTables c;
    const MaterialRef same = c.AddRoughDielectric(
        TexturedFloat(m.rough_dielectric.alpha_texture, 0, 0, site),
        TexturedFloat(m.rough_dielectric.alpha_v_texture, 0, 0, site),
        kMicrofacetGgx | kMicrofacetSampleVisible, 1.5f, 1.0f);
    EXPECT_NEAR(c.rough_dielectric.alpha_u[0], uv.x < 0.5f ? 0.05f : 0.3f, 1e-7f);
    for (int i = 0; i < 200; ++i) {
      Vec3f wo = bsdf_test::RandomUpperDirection(rng), wi = bsdf_test::RandomUpperDirection(rng);
      if (i % 3 == 0) wi.z = -wi.z;
      if (i % 5 == 0) wo.z = -wo.z;
      EXPECT_EQ(BsdfEval(m, ref, wo, wi, site).r, BsdfEval(c, same, wo, wi).r);
      EXPECT_EQ(BsdfPdf(m, ref, wo, wi, site), BsdfPdf(c, same, wo, wi));
      BsdfSample s0, s1;
      const float u1 = rng.NextFloat();
      const Vec2f u2{rng.NextFloat(), rng.NextFloat()};
      EXPECT_EQ(BsdfSampleDirection(m, ref, wo, u1, u2, &s0, site),
                BsdfSampleDirection(c, same, wo, u1, u2, &s1));
      EXPECT_EQ(s0.wi.z, s1.wi.z);
      EXPECT_EQ(s0.weight.g, s1.weight.g);
      refracted += s0.wi.z * wo.z < 0;
    }
  }
  EXPECT_GT(refracted, 50);
}

}  // namespace
}  // namespace ptlab
