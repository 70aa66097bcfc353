// normal: the normalmap / bumpmap wrappers (engine/bsdf/perturbed_frame.h): the identity map
// is Mitsuba's uv-aligned frame, a bump ramp tilts the normal as computed by hand, the
// shadowing term's values, the side rule, and finite orthonormal frames for adversarial input.
#include "engine/bsdf/perturbed_frame.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/conductor_presets.h"
#include "engine/core/rng.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"

namespace ptlab {
namespace {

// One perturbed row over one triangle (prim 0) whose tangents and shading frame the test sets.
struct PerturbedRow {
  MaterialTables m;
  TextureTable textures;
  Frame frame;  // world shading frame
  Vec3f ng{0, 0, 1};
  void SetTangents(const Vec3f& du, const Vec3f& dv) {
    ShadingPerturbations& p = m.perturbation;
    p.dp_du_x = {du.x}, p.dp_du_y = {du.y}, p.dp_du_z = {du.z};
    p.dp_dv_x = {dv.x}, p.dp_dv_y = {dv.y}, p.dp_dv_z = {dv.z};
  }
  uint32_t Constant(const Color3f& c) {
    const uint32_t id = textures.AddRow(TextureKind::kCheckerboard, 1, 1, 6);
    float* d = &textures.data[textures.offset[id]];
    d[0] = d[3] = c.r, d[1] = d[4] = c.g, d[2] = d[5] = c.b;
    return id;
  }
  TextureSite Site(const Vec2f& uv = {0.3f, 0.6f}) const {
    TextureSite s;
    s.textures = &textures;
    s.at.uv = uv, s.at.prim = 0;
    s.frame = &frame, s.ng = &ng;
    return s;
  }
};

bool Finite(const Vec3f& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Normal map (0.5, 0.5, 1) = n = (0, 0, 1): the row evaluated in Mitsuba's frame of the
// surface, whose s is ∂p/∂u in the tangent plane (an anisotropic conductor sees the rotation).
TEST(PerturbedFrame, IdentityNormalMapIsTheUvAlignedFrame) {
  PerturbedRow s;
  Color3f eta, k;
  LookupConductorPreset("Al", &eta, &k);
  const MaterialRef row = s.m.AddRoughConductor(0.25f, 0.05f, kMicrofacetGgx | kMicrofacetSampleVisible,
                                                eta, k, {1, 1, 1});
  const MaterialRef plain = s.m.AddRoughConductor(0.25f, 0.05f, kMicrofacetGgx | kMicrofacetSampleVisible,
                                                  eta, k, {1, 1, 1});
  ASSERT_TRUE(s.m.perturbation.Add(row, PerturbationKind::kNormalMap, s.Constant({0.5f, 0.5f, 1}), 1));
  const float phi = 0.7f;
  s.SetTangents({std::cos(phi) * 2, std::sin(phi) * 2, 0.4f}, {0, 0, 0});
  const Vec3f s0{std::cos(phi), std::sin(phi), 0}, t0{-std::sin(phi), std::cos(phi), 0};
  const auto rotate = [&](const Vec3f& w) { return Vec3f{Dot(w, s0), Dot(w, t0), w.z}; };
  Pcg32 rng(5, 3);
  int nonzero = 0;
  for (int i = 0; i < 500; ++i) {
    // Named draws (a call's arguments are evaluated in an unspecified order).
    const float co = 0.05f + 0.95f * rng.NextFloat(), po = 6.28f * rng.NextFloat();
    const float ci = 0.05f + 0.95f * rng.NextFloat(), pi = 6.28f * rng.NextFloat();
    const Vec3f wo = bsdf_test::DirectionWithCos(co, po);
    const Vec3f wi = bsdf_test::DirectionWithCos(ci, pi);
    const Color3f f = BsdfEval(s.m, row, wo, wi, s.Site());
    const Color3f g = BsdfEval(s.m, plain, rotate(wo), rotate(wi));
    const float pf = BsdfPdf(s.m, row, wo, wi, s.Site()), pg = BsdfPdf(s.m, plain, rotate(wo), rotate(wi));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], g[c], 1e-5f * std::max(1.0f, g[c])) << i;
    EXPECT_NEAR(pf, pg, 1e-5f * std::max(1.0f, pg)) << i;
    nonzero += g.r > 0;
  }
  EXPECT_GT(nonzero, 400);
}

// Bump map h = scale · L with L rising by 1 per texel along u on a 2 x 1 clamped bitmap:
// ∂h/∂u = 2 scale; with ∂p/∂u = x, ∂p/∂v = y: n ∝ (1, 0, 2 scale) × (0, 1, 0) = (−2 scale, 0, 1).
TEST(PerturbedFrame, BumpRampTiltsTheNormalByHand) {
  PerturbedRow s;
  const uint32_t id = s.textures.AddRow(TextureKind::kBitmap, 2, 1, 6);
  for (int c = 0; c < 3; ++c) s.textures.data[s.textures.offset[id] + 3 + c] = 1.0f;
  s.textures.wrap[id] = uint8_t(TextureWrap::kClamp);
  const MaterialRef row = s.m.AddDiffuse({0.5f, 0.5f, 0.5f});
  const float scale = 0.25f;
  ASSERT_TRUE(s.m.perturbation.Add(row, PerturbationKind::kBumpMap, id, scale));
  s.SetTangents({1, 0, 0}, {0, 1, 0});
  const Frame p = PerturbedFrame(s.m, 0, Vec3f{0, 0, 1}, s.Site({0.5f, 0.5f}));
  const float len = std::sqrt(1 + 4 * scale * scale);
  EXPECT_NEAR(p.n.x, -2 * scale / len, 1e-5f);
  EXPECT_NEAR(p.n.y, 0, 1e-6f);
  EXPECT_NEAR(p.n.z, 1 / len, 1e-5f);
  // A constant height leaves the frame's normal alone.
  PerturbedRow flat;
  const MaterialRef r2 = flat.m.AddDiffuse({0.5f, 0.5f, 0.5f});
  ASSERT_TRUE(flat.m.perturbation.Add(r2, PerturbationKind::kBumpMap, flat.Constant({0.7f, 0.7f, 0.7f}), 1));
  flat.SetTangents({1, 0, 0.3f}, {0, 2, -0.1f});
  const Frame q = PerturbedFrame(flat.m, 0, Vec3f{0, 0, 1}, flat.Site());
  EXPECT_NEAR(q.n.z, 1.0f, 1e-6f);
}

TEST(PerturbedFrame, ShadowTerminatorValues) {
  EXPECT_EQ(ShadowTerminator({0, 0, 1}, bsdf_test::DirectionWithCos(0.01f, 1)), 1.0f);
  // n at 45°: tan² = 1, α² = 1/8; w at 60°: tan² = 3.
  const float r = std::sqrt(0.5f);
  const float g = ShadowTerminator({r, 0, r}, bsdf_test::DirectionWithCos(0.5f, 2));
  EXPECT_NEAR(g, 2.0f / (1.0f + std::sqrt(1.0f + 3.0f / 8.0f)), 1e-5f);
  EXPECT_EQ(ShadowTerminator({r, 0, r}, {1, 0, 0}), 0.0f);
  EXPECT_EQ(ShadowTerminator({1, 0, 0}, {0, 0, 1}), 1.0f);  // tan²θ(w) = 0
}

// A wi above the shading frame but below the perturbed one (or the reverse) is no direction of
// the wrapped row: f = 0, pdf = 0.
TEST(PerturbedFrame, DirectionsOnDifferentSidesGetNothing) {
  PerturbedRow s;
  const MaterialRef row = s.m.AddDiffuse({0.5f, 0.5f, 0.5f});
  // n = normalize(1, 0, 1) in tangent space (texture (1, 0.5, 1)).
  ASSERT_TRUE(s.m.perturbation.Add(row, PerturbationKind::kNormalMap, s.Constant({1, 0.5f, 1}), 1));
  s.SetTangents({1, 0, 0}, {0, 1, 0});
  const Vec3f wo{0, 0, 1};
  const Vec3f wi = Normalize(Vec3f{-1, 0, 0.5f});  // above z, below n
  EXPECT_EQ(BsdfEval(s.m, row, wo, wi, s.Site()).r, 0.0f);
  EXPECT_EQ(BsdfPdf(s.m, row, wo, wi, s.Site()), 0.0f);
  const Vec3f wj = Normalize(Vec3f{1, 0, 0.5f});  // above both
  EXPECT_GT(BsdfEval(s.m, row, wo, wj, s.Site()).r, 0.0f);
  // Sampled directions are above both frames.
  Pcg32 rng(9, 9);
  for (int i = 0; i < 1000; ++i) {
    BsdfSample b;
    if (!BsdfSampleDirection(s.m, row, wo, rng.NextFloat(), {rng.NextFloat(), rng.NextFloat()}, &b, s.Site()))
      continue;
    EXPECT_GT(b.wi.z, 0.0f);
    EXPECT_GT(b.wi.x + b.wi.z, 0.0f);  // the perturbed normal's side
  }
}

// Adversarial texels (a zero normal, normals in the tangent plane or along -z, NaN-free
// extremes), tangents (zero, along the normal, huge), bump scales (0, 1e30) and directions
// (grazing, below): every frame orthonormal and finite, every value finite and ≥ 0.
TEST(PerturbedFrame, AdversarialInputsGiveFiniteOrthonormalFrames) {
  const std::vector<Color3f> texels = {{0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 1}, {1, 0.5f, 0.5f},
                                       {0.5f, 0.5f, 0},    {0, 0, 0},       {1, 1, 1},
                                       {1e30f, -1e30f, 0.5f}, {0.5f, 0.5f, 0.5000001f}};
  const std::vector<std::pair<Vec3f, Vec3f>> tangents = {
      {{1, 0, 0}, {0, 1, 0}}, {{0, 0, 0}, {0, 0, 0}}, {{0, 0, 1}, {0, 0, 2}},
      {{1e30f, 0, 0}, {0, 1e30f, 0}}, {{1e-30f, 0, 0}, {0, 1e-30f, 0}}, {{1, 0, 0}, {1, 0, 0}}};
  const std::vector<float> cosines = {1.0f, 0.5f, 1e-4f, 0.0f, -1e-4f, -0.5f, -1.0f};
  Pcg32 rng(11, 4);
  for (int kind = 0; kind < 2; ++kind) {
    for (const Color3f& texel : texels) {
      for (const auto& [du, dv] : tangents) {
        for (const float scale : {0.0f, 0.02f, 1e30f}) {
          PerturbedRow s;
          const MaterialRef row = s.m.AddDiffuse({0.5f, 0.5f, 0.5f});
          uint32_t id;
          if (kind == 0) {
            id = s.Constant(texel);
          } else {  // a 2 x 2 bitmap of texel-scaled luminances: a gradient
            id = s.textures.AddRow(TextureKind::kBitmap, 2, 2, 12);
            for (int j = 0; j < 12; ++j)
              s.textures.data[s.textures.offset[id] + j] = j % 3 == 0 ? texel.r : texel.b * float(j);
          }
          ASSERT_TRUE(s.m.perturbation.Add(row, kind == 0 ? PerturbationKind::kNormalMap : PerturbationKind::kBumpMap,
                                           id, kind == 0 ? 1.0f : scale));
          s.SetTangents(du, dv);
          for (const float c : cosines) {
            const Vec3f wo = bsdf_test::DirectionWithCos(c, 1.3f);
            const Frame p = PerturbedFrame(s.m, 0, wo, s.Site({0.3f, 0.7f}));
            ASSERT_TRUE(Finite(p.n) && Finite(p.s) && Finite(p.t));
            EXPECT_NEAR(Dot(p.n, p.n), 1.0f, 1e-5f);
            EXPECT_NEAR(Dot(p.s, p.s), 1.0f, 1e-5f);
            EXPECT_NEAR(Dot(p.n, p.s), 0.0f, 1e-5f);
            EXPECT_NEAR(Dot(p.n, p.t), 0.0f, 1e-5f);
            for (int i = 0; i < 20; ++i) {
              const float cos_i = 2 * rng.NextFloat() - 1, phi = 6.28f * rng.NextFloat();
              const Vec3f wi = bsdf_test::DirectionWithCos(cos_i, phi);
              float pdf;
              const Color3f f = BsdfEvalPdf(s.m, row, wo, wi, &pdf, s.Site({0.3f, 0.7f}));
              ASSERT_TRUE(std::isfinite(f.r) && f.r >= 0 && std::isfinite(pdf) && pdf >= 0);
              BsdfSample b;
              if (BsdfSampleDirection(s.m, row, wo, rng.NextFloat(), {rng.NextFloat(), rng.NextFloat()}, &b,
                                      s.Site({0.3f, 0.7f}))) {
                ASSERT_TRUE(Finite(b.wi) && std::isfinite(b.weight.r) && b.weight.r >= 0 && std::isfinite(b.pdf));
              }
            }
          }
        }
      }
    }
  }
}

// Sampling against the pdf: the share of draws that give a sample equals ∫ pdf dω over the
// sphere (both are the nested lobe's mass on the directions the side rule keeps), for a tilted
// normal map over a diffuse and a 5:2 anisotropic GGX conductor, and a bump ramp over a
// diffuse. Quadrature on a 600 × 1200 grid in (cos θ, φ) (midpoints); 100,000 draws, fixed
// seed; |share − ∫| ≤ 5σ + 2e-3 (the grid's error on these smooth lobes is below 1e-3).
TEST(PerturbedFrame, SampleShareIsTheIntegralOfThePdf) {
  PerturbedRow s;
  Color3f eta, k;
  LookupConductorPreset("Al", &eta, &k);
  const MaterialRef diffuse = s.m.AddDiffuse({0.5f, 0.5f, 0.5f});
  const MaterialRef metal = s.m.AddRoughConductor(0.25f, 0.1f, kMicrofacetGgx | kMicrofacetSampleVisible,
                                                  eta, k, {1, 1, 1});
  const MaterialRef bumped = s.m.AddDiffuse({0.5f, 0.5f, 0.5f});
  const uint32_t tilt = s.Constant({0.85f, 0.35f, 0.8f});
  ASSERT_TRUE(s.m.perturbation.Add(diffuse, PerturbationKind::kNormalMap, tilt, 1));
  ASSERT_TRUE(s.m.perturbation.Add(metal, PerturbationKind::kNormalMap, tilt, 1));
  const uint32_t ramp = s.textures.AddRow(TextureKind::kBitmap, 2, 1, 6);
  for (int c = 0; c < 3; ++c) s.textures.data[s.textures.offset[ramp] + 3 + c] = 1.0f;
  s.textures.wrap[ramp] = uint8_t(TextureWrap::kClamp);
  ASSERT_TRUE(s.m.perturbation.Add(bumped, PerturbationKind::kBumpMap, ramp, 0.4f));
  s.SetTangents({0.8f, 0.6f, 0.1f}, {-0.6f, 0.8f, 0.0f});
  const TextureSite site = s.Site({0.5f, 0.5f});
  for (const MaterialRef ref : {diffuse, metal, bumped}) {
    for (const float c : {0.9f, 0.4f}) {
      const Vec3f wo = bsdf_test::DirectionWithCos(c, 2.5f);
      constexpr int kT = 600, kP = 1200;
      double integral = 0;
      for (int i = 0; i < kT; ++i) {
        const float z = -1.0f + 2.0f * (float(i) + 0.5f) / kT;
        for (int j = 0; j < kP; ++j) {
          const float phi = 6.2831853f * (float(j) + 0.5f) / kP;
          const float r = std::sqrt(std::max(0.0f, 1 - z * z));
          integral += BsdfPdf(s.m, ref, wo, {r * std::cos(phi), r * std::sin(phi), z}, site);
        }
      }
      integral *= (2.0 / kT) * (6.283185307179586 / kP);
      Pcg32 rng(41, uint64_t(ref.bits));
      constexpr int kN = 100000;
      int hits = 0;
      for (int i = 0; i < kN; ++i) {
        BsdfSample b;
        hits += BsdfSampleDirection(s.m, ref, wo, rng.NextFloat(), {rng.NextFloat(), rng.NextFloat()},
                                    &b, site);
      }
      const double share = double(hits) / kN;
      const double sigma = std::sqrt(std::max(share * (1 - share), 1e-6) / kN);
      EXPECT_NEAR(share, integral, 5 * sigma + 2e-3)
          << "tag " << int(ref.tag()) << " row " << ref.index() << " cos θo " << c;
      std::printf("tag %d row %u cos %.1f: sampled share %.4f, ∫ pdf %.4f\n", int(ref.tag()),
                  ref.index(), c, share, integral);
    }
  }
}

}  // namespace
}  // namespace ptlab
