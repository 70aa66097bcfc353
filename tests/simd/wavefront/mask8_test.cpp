// simd::ShadeBatch against the oracle ptlab::ShadeBatch on every compiled Highway target for
// the rows helper `mask` added: Mitsuba `mask` rows (constant and textured opacity, nested
// diffuse, two-sided diffuse, textured diffuse, mirror, rough conductor), blend rows with a
// textured weight, and rough conductors with textured αu, αv. Random and adversarial inputs
// (opacity 0, 1, denormal, 1 − ulp, out-of-range texture values; u_lobe 0, 1 − ulp and equal
// to the opacity; wo below the surface, grazing).
//
// Contract: the opacity / weight / α (TexturedUnitFloatRows8, TexturedFloat8) and so the pick
// are bit-identical, hence the pass-through rows (wi, weight, pdf, eta, delta) and the delta
// flag; f and pdf_l are the nested kernels' times the same opacity: bit-identical over
// diffuse-type and delta children, ≤ 2e-5 relative over the rough conductor (its own
// contract); nested samples: weight ≤ 2e-5 relative of the oracle's, pdf ≤ 2e-5 relative of the
// oracle's pdf at the SIMD's own direction (the rough conductor: its own contract, 1e-4 +
// 4e-7/α²), wi as the nested kernel's (few ulp; a cosine-sampled z within 2e-3 where the two
// sides of a rounding boundary differ).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/conductor_presets.h"
#include "engine/bsdf/microfacet.h"
#include "engine/wavefront/bsdf.h"
#include "simd/dispatched_target.h"
#include "simd/wavefront/bsdf8.h"
#include "simd/targets.h"  // first: the same target policy as simd/
#include "tests/simd/for_each_target.h"

namespace ptlab {
namespace {

struct Out {
  std::vector<float> c[13];
  explicit Out(size_t size) {
    for (auto& v : c) v.assign(size, -7.0f);  // poison: every output must be written
  }
  ShadeOutputs View() {
    ShadeOutputs o;
    o.f = {c[0].data(), c[1].data(), c[2].data()};
    o.pdf_l = c[3].data();
    o.wi = {c[4].data(), c[5].data(), c[6].data()};
    o.weight = {c[7].data(), c[8].data(), c[9].data()};
    o.pdf = c[10].data(), o.eta = c[11].data(), o.delta = c[12].data();
    return o;
  }
};

bool Same(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }
bool Near(float a, float b, double rel) {
  return std::fabs(double(a) - b) <= rel * std::max(std::fabs(double(b)), 1e-30);
}

struct Fixture {
  TextureTable textures;
  MaterialTables m;
  std::vector<SurfaceInteraction> its;
  std::vector<uint32_t> entry;
  std::vector<float> wo_x, wo_y, wo_z, wl_x, wl_y, wl_z, ul, ux, uy;
  ShadeInputs In() const {
    ShadeInputs in;
    in.wo = {wo_x.data(), wo_y.data(), wo_z.data()};
    in.wl = {wl_x.data(), wl_y.data(), wl_z.data()};
    in.u_lobe = ul.data(), in.u_x = ux.data(), in.u_y = uy.data();
    in.texture = {&textures, its.data(), entry.data()};
    return in;
  }
};

// n rows of random shading points, directions and numbers; 1 in 4 u_lobe is a hard value (0,
// 1 − ulp, 0.5, or copied from a row's constant opacity to sit on the pick's boundary).
void FillRows(Fixture* f, size_t n, std::mt19937* rng, const std::vector<float>& boundary) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), wide(-3.0f, 4.0f);
  std::uniform_int_distribution<uint32_t> prim(0, 3);
  f->its.resize(2 * n), f->entry.resize(n);
  for (auto* v : {&f->wo_x, &f->wo_y, &f->wo_z, &f->wl_x, &f->wl_y, &f->wl_z, &f->ul, &f->ux,
                  &f->uy})
    v->resize(n);
  for (size_t i = 0; i < n; ++i) {
    f->entry[i] = uint32_t(2 * n - 1 - 2 * i);  // the shading points are not in row order
    SurfaceInteraction& s = f->its[f->entry[i]];
    s.uv = {wide(*rng), wide(*rng)};
    s.p = {wide(*rng), wide(*rng), wide(*rng)};
    s.prim = prim(*rng);
    const float a = unit(*rng) * 6.2831853f;
    float z = unit(*rng);
    if (i % 17 == 0) z = 1e-7f;  // grazing
    const float r = std::sqrt(std::max(0.0f, 1 - z * z));
    f->wo_x[i] = r * std::cos(a), f->wo_y[i] = r * std::sin(a), f->wo_z[i] = i % 5 == 0 ? -z : z;
    const float b = unit(*rng) * 6.2831853f, zl = unit(*rng), rl = std::sqrt(1 - zl * zl);
    f->wl_x[i] = rl * std::cos(b), f->wl_y[i] = rl * std::sin(b), f->wl_z[i] = i % 7 == 0 ? -zl : zl;
    f->ul[i] = unit(*rng), f->ux[i] = unit(*rng), f->uy[i] = unit(*rng);
    switch (i % 16) {
      case 1: f->ul[i] = 0.0f; break;
      case 2: f->ul[i] = 0x1.fffffep-1f; break;
      case 3: f->ul[i] = boundary[(i / 16) % boundary.size()]; break;
      default: break;
    }
  }
}

// Compares the SIMD rows with the oracle's under the contract above; `exact_eval(row)` says
// whether row's f and pdf_l must be bit-identical.
template <class ExactEval>
void Check(const Fixture& fx, MaterialTag tag, const std::vector<uint32_t>& index, const Out& want,
           const Out& got, const ExactEval& exact_eval, const char* what) {
  // A rough conductor row's samples: microfacet8_test.cpp's contract, 1e-4 + 4e-7/α²_min
  // relative (hwy's Sin/Cos in the visible-normal warp, amplified where α is small).
  const auto sample_rel = [&](size_t i) {
    if (tag != MaterialTag::kConductor) return 2e-5;
    const TextureSite site = RowTextureSite(fx.In().texture, i);
    const ConductorTable& t = fx.m.conductor;
    const uint32_t r = index[i];
    const double a = std::min(ClampMicrofacetAlpha(TexturedFloat(t.alpha_texture, r, t.alpha[r], site)),
                              ClampMicrofacetAlpha(TexturedFloat(t.alpha_v_texture, r, t.alpha_v[r], site)));
    return 1e-4 + 4e-7 / (a * a);
  };
  int failures = 0, passes = 0, nested = 0;
  const auto fail = [&](size_t i, const char* field, float g, float w) {
    if (++failures <= 10)
      ADD_FAILURE() << what << " row " << i << " (table row " << index[i] << "): " << field
                    << " " << g << " vs oracle " << w;
  };
  for (size_t i = 0; i < index.size(); ++i) {
    for (int c = 0; c < 4; ++c) {
      const bool ok = exact_eval(index[i]) ? Same(got.c[c][i], want.c[c][i])
                                           : Near(got.c[c][i], want.c[c][i], 2e-5);
      if (!ok) fail(i, c < 3 ? "f" : "pdf_l", got.c[c][i], want.c[c][i]);
    }
    // The lobe kind of a sample (meaningless where there is none: pdf 0).
    if (want.c[10][i] > 0 && !Same(got.c[12][i], want.c[12][i]))
      fail(i, "delta", got.c[12][i], want.c[12][i]);
    const bool through = tag == MaterialTag::kMask && want.c[10][i] > 0 &&
                         want.c[4][i] == -fx.wo_x[i] && want.c[5][i] == -fx.wo_y[i] &&
                         want.c[6][i] == -fx.wo_z[i] && want.c[7][i] == 1.0f;
    if (through) {
      ++passes;
      for (int c = 4; c < 12; ++c)
        if (!Same(got.c[c][i], want.c[c][i])) fail(i, "pass-through", got.c[c][i], want.c[c][i]);
      continue;
    }
    const bool v0 = want.c[10][i] > 0, v1 = got.c[10][i] > 0;
    if (v0 != v1) {  // only where the nested sample sits on its own rounding boundary
      const float z = v0 ? want.c[6][i] : got.c[6][i];
      if (!(std::fabs(z) <= 2e-3f)) fail(i, "sample validity", got.c[10][i], want.c[10][i]);
      continue;
    }
    if (!v0) continue;
    ++nested;
    if (got.c[12][i] != 0) {  // a delta nested sample: the oracle's numbers
      if (!Near(got.c[10][i], want.c[10][i], 2e-5)) fail(i, "pdf", got.c[10][i], want.c[10][i]);
      for (int c = 7; c < 10; ++c)
        if (!Near(got.c[c][i], want.c[c][i], 2e-5)) fail(i, "weight", got.c[c][i], want.c[c][i]);
    } else {
      const double rel = sample_rel(i);
      // The directions differ by the cosine warp's few ulp, which a small cos θi amplifies in
      // pdf ∝ cos θi: the pdf is checked against the oracle's at the SIMD's own wi; the weight
      // (the albedo, for the diffuse kinds) against the oracle sample's.
      const ShadeInputs in = fx.In();
      const TextureSite site = RowTextureSite(in.texture, i);
      const MaterialRef ref = MaterialRef::Make(tag, index[i]);
      const Vec3f wo{fx.wo_x[i], fx.wo_y[i], fx.wo_z[i]}, wi{got.c[4][i], got.c[5][i], got.c[6][i]};
      float opdf = 0;
      BsdfEvalPdf(fx.m, ref, wo, wi, &opdf, site);
      if (!(std::fabs(wi.z) > 1e-30f) || !(opdf > 0)) continue;
      if (!Near(got.c[10][i], opdf, rel)) fail(i, "pdf", got.c[10][i], opdf);
      for (int c = 7; c < 10; ++c)
        if (!Near(got.c[c][i], want.c[c][i], rel)) fail(i, "weight", got.c[c][i], want.c[c][i]);
    }
    for (int c = 4; c < 6; ++c)
      if (std::fabs(got.c[c][i] - want.c[c][i]) > 2e-6f) fail(i, "wi.xy", got.c[c][i], want.c[c][i]);
    const float z0 = want.c[6][i], z1 = got.c[6][i];
    if (!(std::fabs(z1 - z0) <= 2e-6f || std::fabs(z1 * z1 - z0 * z0) <= 4e-6f))
      fail(i, "wi.z", z1, z0);
    if (!Same(got.c[11][i], want.c[11][i])) fail(i, "eta", got.c[11][i], want.c[11][i]);
  }
  if (tag == MaterialTag::kMask) {
    EXPECT_GT(passes, int(index.size() / 10)) << what;
    EXPECT_GT(nested, int(index.size() / 10)) << what;
  }
}

void RunAndCheck(const Fixture& fx, MaterialTag tag, const std::vector<uint32_t>& index,
         const std::function<bool(uint32_t)>& exact_eval, const char* what) {
  const size_t n = index.size();
  Out want(n);
  ShadeBatch(fx.m, tag, index.data(), n, fx.In(), want.View());
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    Out got(n);
    simd::ShadeBatch(fx.m, tag, index.data(), n, fx.In(), got.View());
    Check(fx, tag, index, want, got, exact_eval, what);
  });
}

uint32_t AddTexture(TextureTable* t, TextureKind kind, uint32_t w, uint32_t h, size_t count,
                    std::mt19937* rng, float lo, float hi) {
  std::uniform_real_distribution<float> v(lo, hi);
  const uint32_t id = t->AddRow(kind, w, h, count);
  for (size_t k = 0; k < count; ++k) t->data[t->offset[id] + k] = v(*rng);
  return id;
}

TEST(Mask8, MaskRowsMatchTheOracleOnEveryTarget) {
  std::mt19937 rng(11);
  Fixture fx;
  TextureTable& t = fx.textures;
  // Opacity textures: a bitmap in [0, 1], a checkerboard and a face attribute partly outside
  // [0, 1] (clipped).
  const uint32_t bitmap = AddTexture(&t, TextureKind::kBitmap, 5, 3, 45, &rng, 0.0f, 1.0f);
  const uint32_t checker = AddTexture(&t, TextureKind::kCheckerboard, 1, 1, 6, &rng, -0.5f, 1.5f);
  const uint32_t face = AddTexture(&t, TextureKind::kFaceAttribute, 3, 4, 12, &rng, -1.0f, 2.0f);
  const uint32_t albedo = AddTexture(&t, TextureKind::kBitmap, 4, 4, 48, &rng, 0.0f, 1.0f);
  Color3f eta, k;
  LookupConductorPreset("Au", &eta, &k);
  MaterialTables& m = fx.m;
  const MaterialRef twosided = m.AddDiffuse({0.1f, 0.8f, 0.1f});
  m.two_sided.Set(twosided);
  // A two-sided textured diffuse: ShadeTwoSided passes the chunk's shading points on.
  const MaterialRef twosided_textured = m.AddTexturedDiffuse(albedo);
  m.two_sided.Set(twosided_textured);
  const MaterialRef kids[] = {m.AddDiffuse({0.8f, 0.5f, 0.2f}), twosided,
                              m.AddTexturedDiffuse(albedo), twosided_textured,
                              m.AddMirror({0.9f, 0.8f, 0.7f}),
                              m.AddRoughConductor(0.2f, 0.05f, kMicrofacetSampleVisible, eta, k,
                                                  {1, 1, 1})};
  const std::vector<float> opacities = {0.0f, 1e-40f, 0.3f, 0.5f, 0x1.fffffep-1f, 1.0f};
  std::vector<bool> exact;  // per mask row: f and pdf_l bit-identical (not the rough conductor)
  for (const MaterialRef kid : kids) {
    for (float o : opacities) m.AddMask(o, kid), exact.push_back(kid.tag() != MaterialTag::kConductor);
    for (uint32_t tex : {bitmap, checker, face})
      m.AddMask(0.5f, kid, tex), exact.push_back(kid.tag() != MaterialTag::kConductor);
  }
  const MaterialRef inner = m.AddMask(0.6f, kids[0]);  // a mask in a mask
  m.AddMask(0.5f, inner, checker), exact.push_back(true);
  const size_t n = 40000;
  FillRows(&fx, n, &rng, opacities);
  std::vector<uint32_t> index(n);
  std::uniform_int_distribution<uint32_t> row(0, uint32_t(m.mask.size() - 1));
  for (size_t i = 0; i < n; ++i) index[i] = row(rng);
  for (size_t i = 0; i < n; ++i)  // rows on the pick's boundary use their own opacity
    if (i % 16 == 3 && m.mask.opacity_texture[index[i]] == kNoTexture)
      fx.ul[i] = m.mask.opacity[index[i]];
  RunAndCheck(fx, MaterialTag::kMask, index, [&](uint32_t r) { return bool(exact[r]); }, "mask");
}

TEST(Mask8, TexturedBlendWeightAndRoughConductorAlphaMatchTheOracle) {
  std::mt19937 rng(5);
  Fixture fx;
  TextureTable& t = fx.textures;
  const uint32_t bitmap = AddTexture(&t, TextureKind::kBitmap, 5, 3, 45, &rng, 0.0f, 1.0f);
  const uint32_t checker = AddTexture(&t, TextureKind::kCheckerboard, 1, 1, 6, &rng, -0.5f, 1.5f);
  const uint32_t face = AddTexture(&t, TextureKind::kFaceAttribute, 3, 4, 12, &rng, -1.0f, 2.0f);
  const uint32_t albedo = AddTexture(&t, TextureKind::kBitmap, 4, 4, 48, &rng, 0.0f, 1.0f);
  const uint32_t rough = AddTexture(&t, TextureKind::kCheckerboard, 1, 1, 6, &rng, 0.0f, 0.6f);
  MaterialTables& m = fx.m;
  const MaterialRef a = m.AddDiffuse({0.0f, 0.5f, 0.5f}), b = m.AddTexturedDiffuse(albedo);
  const MaterialRef c = m.AddMirror({1, 1, 0});
  m.AddBlend(0.25f, a, b);
  for (uint32_t tex : {bitmap, checker, face}) m.AddBlend(0.5f, a, b, tex), m.AddBlend(0.5f, b, c, tex);
  const size_t n = 20000;
  FillRows(&fx, n, &rng, {0.25f, 0.5f});
  std::vector<uint32_t> index(n);
  std::uniform_int_distribution<uint32_t> row(0, uint32_t(m.blend.size() - 1));
  for (size_t i = 0; i < n; ++i) index[i] = row(rng);
  // The blend's non-delta samples carry the mixture's numbers (few ulp of the children's).
  RunAndCheck(fx, MaterialTag::kBlend, index, [](uint32_t) { return false; }, "blend");

  Color3f eta, k;
  LookupConductorPreset("Cu", &eta, &k);
  for (uint8_t flags = 0; flags < 4; ++flags) {
    m.AddRoughConductor(0.1f, 0.3f, flags, eta, k, {1, 1, 1});
    m.AddTexturedRoughConductor(0.1f, 0.1f, rough, kNoTexture, flags, eta, k, {1, 0.9f, 0.8f});
    m.AddTexturedRoughConductor(0.1f, 0.1f, kNoTexture, face, flags, eta, k, {1, 1, 1});
    m.AddTexturedRoughConductor(0.1f, 0.1f, rough, rough, flags, eta, k, {1, 1, 1});
  }
  std::uniform_int_distribution<uint32_t> crow(0, uint32_t(m.conductor.size() - 1));
  for (size_t i = 0; i < n; ++i) index[i] = crow(rng);
  RunAndCheck(fx, MaterialTag::kConductor, index, [](uint32_t) { return false; }, "rough conductor");
}

// A rough dielectric's textured αu, αv (TexturedFloat8): on every target each row is, bit for
// bit, what the same target gives for a constant row of the texture's values at its site (the
// constant rows hold the oracle's TexturedFloat, so this also checks that the SIMD luminance is
// the oracle's; the constant rows' contract against the oracle is microfacet8_test.cpp's).
TEST(Mask8, TexturedRoughDielectricAlphaIsTheConstantRowOnEveryTarget) {
  std::mt19937 rng(9);
  Fixture fx;
  TextureTable& t = fx.textures;
  const uint32_t rough = AddTexture(&t, TextureKind::kCheckerboard, 1, 1, 6, &rng, 0.0f, 0.6f);
  const uint32_t face = AddTexture(&t, TextureKind::kFaceAttribute, 3, 4, 12, &rng, -1.0f, 2.0f);
  const uint32_t bitmap = AddTexture(&t, TextureKind::kBitmap, 5, 3, 45, &rng, 0.0f, 1.2f);
  MaterialTables& m = fx.m;
  for (uint8_t flags = 0; flags < 4; ++flags) {
    m.AddRoughDielectric(0.1f, 0.3f, flags, 1.5f, 1.0f);
    m.AddTexturedRoughDielectric(0.1f, 0.1f, rough, kNoTexture, flags, 1.5f, 1.0f, {1, 1, 1},
                                 {1, 0.9f, 0.8f});
    m.AddTexturedRoughDielectric(0.1f, 0.1f, kNoTexture, face, flags, 1.33f, 1.0f, {1, 1, 1},
                                 {1, 1, 1});
    m.AddTexturedRoughDielectric(0.1f, 0.1f, bitmap, bitmap, flags, 1.0f / 1.5f, 1.0f,
                                 {0.9f, 1, 1}, {1, 1, 1});
  }
  const size_t n = 6000;
  FillRows(&fx, n, &rng, {0.5f});
  std::vector<uint32_t> index(n), own(n);
  std::uniform_int_distribution<uint32_t> row(0, uint32_t(m.rough_dielectric.size() - 1));
  // Row i of `constant` is table row index[i] with its α as the oracle reads it at row i's site.
  MaterialTables constant;
  const ShadeInputs in = fx.In();
  const RoughDielectricTable& rd = m.rough_dielectric;
  for (size_t i = 0; i < n; ++i) {
    const uint32_t r = index[i] = row(rng);
    const TextureSite site = RowTextureSite(in.texture, i);
    constant.AddRoughDielectric(TexturedFloat(rd.alpha_texture, r, rd.alpha_u[r], site),
                                TexturedFloat(rd.alpha_v_texture, r, rd.alpha_v[r], site),
                                rd.flags[r], rd.int_ior[r], rd.ext_ior[r],
                                {rd.reflectance_r[r], rd.reflectance_g[r], rd.reflectance_b[r]},
                                {rd.transmittance_r[r], rd.transmittance_g[r],
                                 rd.transmittance_b[r]});
    own[i] = uint32_t(i);
  }
  int textured_rows = 0;
  for (size_t i = 0; i < n; ++i)
    textured_rows += rd.alpha_texture[index[i]] != kNoTexture || rd.alpha_v_texture[index[i]] != kNoTexture;
  EXPECT_GT(textured_rows, int(n / 2));
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
    Out got(n), want(n);
    simd::ShadeBatch(m, MaterialTag::kRoughDielectric, index.data(), n, in, got.View());
    simd::ShadeBatch(constant, MaterialTag::kRoughDielectric, own.data(), n, in, want.View());
    int failures = 0;
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 12; ++c)
        if (!Same(got.c[c][i], want.c[c][i]) && ++failures <= 5)
          ADD_FAILURE() << target << " row " << i << " (table row " << index[i] << ") output "
                        << c << ": " << got.c[c][i] << " vs constant row " << want.c[c][i];
  });
}

}  // namespace
}  // namespace ptlab
