// SIMD shading vs its scalar oracle, on every compiled Highway target, random + hard-case inputs.
// clang-format off
#include "simd/targets.h"  // first: the target policy (must precede every hwy/ include)
// clang-format on
#include "simd/wavefront/bsdf8.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/conductor_presets.h"
#include "engine/bsdf/fresnel.h"
#include "engine/bsdf/plastic.h"
#include "engine/bsdf/plastic_precompute.h"
#include "engine/bsdf/plastic_rough.h"  // plastic8
#include "engine/core/rng.h"
#include "hwy/targets.h"
#include "simd/dispatched_target.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"
#include "tests/simd/for_each_target.h"

namespace ptlab {
namespace {

using bsdf_test::DirectionWithCos;

// Runs fn once per compiled target supported by this CPU, with dispatch pinned to it.
template <class Fn>
void ForEachTarget(Fn&& fn) {
  test::ForEachTarget(simd::DispatchedTargetName, fn);
}

// |simd − oracle| ≤ rel |oracle| + abs, with the worst violation (or closest call) kept.
struct Contract {
  std::string what;
  double rel, abs;
  size_t checked = 0, failures = 0;
  double worst = 0;    // max error / allowed
  double max_rel = 0;  // max relative error where |oracle| > 1e-20, for the log
  size_t worst_i = 0;
  double worst_simd = 0, worst_oracle = 0;

  void Check(size_t i, double simd, double oracle) {
    ++checked;
    const double err = std::fabs(simd - oracle);
    const double allowed = rel * std::fabs(oracle) + abs;
    const double ratio = std::isfinite(simd) && std::isfinite(oracle) ? err / allowed : 1e30;
    if (std::fabs(oracle) > 1e-20) max_rel = std::max(max_rel, err / std::fabs(oracle));
    if (ratio > 1) ++failures;
    if (ratio > worst || !(ratio == ratio)) {
      worst = ratio, worst_i = i, worst_simd = simd, worst_oracle = oracle;
    }
  }
  void Report(const char* target) const {
    std::printf("[%s] %-28s n=%zu  max|Δ|/allowed=%.3g  max rel=%.3g\n", target, what.c_str(),
                checked, worst, max_rel);
    EXPECT_EQ(failures, 0u) << what << ": worst at input " << worst_i << ": simd " << worst_simd
                            << " oracle " << worst_oracle << " (error/allowed " << worst << ")";
  }
};

// SoA direction storage.
struct Dirs {
  std::vector<float> x, y, z;
  void Push(const Vec3f& v) { x.push_back(v.x), y.push_back(v.y), z.push_back(v.z); }
  void Resize(size_t n) { x.resize(n), y.resize(n), z.resize(n); }
  Vec3f operator[](size_t i) const { return {x[i], y[i], z[i]}; }
  DirectionArrays View() const { return {x.data(), y.data(), z.data()}; }
  DirectionOutArrays Out() { return {x.data(), y.data(), z.data()}; }
  size_t size() const { return x.size(); }
};

constexpr size_t kRandomCount = size_t(1) << 20;

// ------------------------------------------------------------------------------ Beckmann

struct BeckmannInputs {
  std::vector<float> alpha;
  Dirs wo, wi;
};

BeckmannInputs MakeBeckmannInputs() {
  BeckmannInputs in;
  Pcg32 rng(2024, 1);
  for (size_t i = 0; i < kRandomCount; ++i) {
    const float alpha = bsdf_test::RandomAlpha(rng);
    const Vec3f wo = bsdf_test::RandomUpperDirection(rng);
    Vec3f wi;
    switch (i % 4) {
      case 0:
      case 1:
        wi = bsdf_test::NearSpecularPartner(alpha, wo, rng);
        break;
      case 2:
        wi = bsdf_test::RandomUpperDirection(rng);
        break;
      default: {
        const float u1 = rng.NextFloat();
        wi = SampleUniformSphere({u1, rng.NextFloat()});
      }
    }
    in.alpha.push_back(alpha), in.wo.Push(wo), in.wi.Push(wi);
  }
  const std::vector<Vec3f> dirs = bsdf_test::HardDirections();
  for (float alpha : bsdf_test::HardAlphas())
    for (const Vec3f& wo : dirs)
      for (const Vec3f& wi : dirs) in.alpha.push_back(alpha), in.wo.Push(wo), in.wi.Push(wi);
  return in;
}

TEST(Shade8, BeckmannEvalPdfMatchesOracleOnEveryTarget) {
  const BeckmannInputs in = MakeBeckmannInputs();
  const size_t n = in.alpha.size();
  std::vector<float> d0(n), pdf0(n), d1(n), pdf1(n);
  ptlab::BeckmannEvalPdfBatch(in.alpha.data(), in.wo.View(), in.wi.View(), n, d0.data(),
                              pdf0.data());
  size_t nonzero = 0;
  for (size_t i = 0; i < n; ++i) nonzero += d0[i] > 0;
  EXPECT_GT(nonzero, n / 3);  // the inputs exercise the interesting region
  ForEachTarget([&](const char* target) {
    simd::BeckmannEvalPdfBatch(in.alpha.data(), in.wo.View(), in.wi.View(), n, d1.data(),
                               pdf1.data());
    Contract cd{"Beckmann D", 1e-5, 1e-30}, cp{"Beckmann pdf", 1e-5, 1e-30};
    for (size_t i = 0; i < n; ++i) {
      ASSERT_TRUE(std::isfinite(d1[i]) && d1[i] >= 0 && std::isfinite(pdf1[i]) && pdf1[i] >= 0)
          << i;
      cd.Check(i, d1[i], d0[i]);
      cp.Check(i, pdf1[i], pdf0[i]);
    }
    cd.Report(target);
    cp.Report(target);
  });
}

TEST(Shade8, SampleBeckmannReflectionMatchesOracleOnEveryTarget) {
  std::vector<float> alpha, ux, uy;
  Dirs wo;
  Pcg32 rng(99, 3);
  for (size_t i = 0; i < kRandomCount / 4; ++i) {
    alpha.push_back(bsdf_test::RandomAlpha(rng));
    wo.Push(bsdf_test::RandomUpperDirection(rng));
    const float a = rng.NextFloat();
    ux.push_back(a), uy.push_back(rng.NextFloat());
  }
  const size_t random_count = alpha.size();
  for (float a : bsdf_test::HardAlphas())
    for (const Vec3f& o : bsdf_test::HardDirections(/*with_non_unit=*/false))
      for (float u1 : bsdf_test::HardUs())
        for (float u2 : bsdf_test::HardUs())
          alpha.push_back(a), wo.Push(o), ux.push_back(u1), uy.push_back(u2);
  const size_t n = alpha.size();
  Dirs wi0, wi1;
  wi0.Resize(n), wi1.Resize(n);
  std::vector<float> pdf0(n), pdf1(n);
  ptlab::SampleBeckmannReflectionBatch(alpha.data(), wo.View(), ux.data(), uy.data(), n, wi0.Out(),
                                       pdf0.data());
  ForEachTarget([&](const char* target) {
    simd::SampleBeckmannReflectionBatch(alpha.data(), wo.View(), ux.data(), uy.data(), n, wi1.Out(),
                                        pdf1.data());
    Contract cw{"Beckmann sample wi", 0, 2e-6}, cp{"Beckmann sample pdf", 1e-5, 1e-30};
    size_t mismatched_validity = 0;
    for (size_t i = 0; i < n; ++i) {
      ASSERT_TRUE(std::isfinite(pdf1[i]) && pdf1[i] >= 0) << i;
      const bool v0 = pdf0[i] > 0, v1 = pdf1[i] > 0;
      if (v0 != v1) {
        ++mismatched_validity;
        ASSERT_LE(std::fabs(v0 ? wi0.z[i] : wi1.z[i]), 2e-6f) << "validity differs at " << i;
        continue;
      }
      if (!v1) continue;
      cw.Check(i, wi1.x[i], wi0.x[i]), cw.Check(i, wi1.y[i], wi0.y[i]);
      cw.Check(i, wi1.z[i], wi0.z[i]);
      cp.Check(i, pdf1[i], BeckmannReflectionPdf(alpha[i], wo[i], wi1[i]));
    }
    cw.Report(target);
    cp.Report(target);
    EXPECT_LT(mismatched_validity, 10u);
  });
  size_t valid = 0;
  for (size_t i = 0; i < random_count; ++i) valid += pdf0[i] > 0;
  EXPECT_GT(valid, random_count / 2);
}

// ------------------------------------------------------------------------------ Fresnel

TEST(Shade8, ConductorFresnelMatchesOracleOnEveryTarget) {
  std::vector<float> cos_i, eta, k;
  std::vector<bool> preset;
  Pcg32 rng(5, 77);
  for (size_t i = 0; i < kRandomCount; ++i) {
    cos_i.push_back(i % 3 ? 2.0f * rng.NextFloat() - 1.0f
                          : std::pow(10.0f, -6.0f * rng.NextFloat()));
    eta.push_back(std::pow(10.0f, 4.0f * rng.NextFloat() - 2.0f));
    k.push_back(i % 10 == 0 ? 0.0f : std::pow(10.0f, 5.0f * rng.NextFloat() - 3.0f));
    preset.push_back(false);
  }
  for (const char* name : {"Au", "Ag", "Al", "Cu", "Fe", "Na", "Si"}) {
    Color3f e, kk;
    LookupConductorPreset(name, &e, &kk);
    for (int c = 0; c < 3; ++c)
      for (int j = 0; j <= 10000; ++j)
        cos_i.push_back(j / 10000.0f), eta.push_back(e[c]), k.push_back(kk[c]),
            preset.push_back(true);
  }
  const float hard_ior[] = {0.0f, 1e-40f, 1e-6f, 0.05f, 0.2f, 1.0f, 1.5f, 3.0f, 10.0f, 1e4f, 1e30f};
  for (float c : bsdf_test::HardCosines())
    for (float e : hard_ior)
      for (float kk : hard_ior)
        cos_i.push_back(c), eta.push_back(e), k.push_back(kk), preset.push_back(false);
  // η, κ ~ 1e-23 at normal incidence: t is float's least denormal and |z| underflows to 0 (a
  // random search found these; the quotient ek / a was ∞ and the result NaN before).
  const float tiny_pairs[][2] = {
      {3.84846e-23f, 2.24301e-23f}, {4.06811e-23f, 2.1011e-23f}, {6.0064e-23f, 3.97018e-23f}};
  for (const auto& p : tiny_pairs)
    cos_i.push_back(1.0f), eta.push_back(p[0]), k.push_back(p[1]), preset.push_back(false);
  // η = 1 with κ and cos θ tiny: Rs's squares are denormal (its quotient was 1.032).
  cos_i.push_back(2.07785e-22f), eta.push_back(1.0f), k.push_back(1.28374e-35f);
  cos_i.push_back(1.92215e-20f), eta.push_back(1.0f), k.push_back(5.76979e-27f);
  preset.push_back(false), preset.push_back(false);
  const size_t n = cos_i.size();
  std::vector<float> f0(n), f1(n);
  ptlab::ConductorFresnelBatch(cos_i.data(), eta.data(), k.data(), n, f0.data());
  ForEachTarget([&](const char* target) {
    simd::ConductorFresnelBatch(cos_i.data(), eta.data(), k.data(), n, f1.data());
    Contract all{"conductor Fresnel", 0, 2e-6}, presets{"conductor Fresnel presets", 1e-5, 0};
    for (size_t i = 0; i < n; ++i) {
      ASSERT_TRUE(f1[i] >= 0 && f1[i] <= 1.0f) << i << " " << f1[i];
      ASSERT_TRUE(f0[i] >= 0 && f0[i] <= 1.0f) << i << " " << f0[i];
      all.Check(i, f1[i], f0[i]);
      if (preset[i]) presets.Check(i, f1[i], f0[i]);
    }
    all.Report(target);
    presets.Report(target);
  });
}

TEST(Shade8, DielectricFresnelMatchesOracleOnEveryTarget) {
  std::vector<float> cos_i, eta;
  Pcg32 rng(6, 1);
  for (size_t i = 0; i < kRandomCount; ++i) {
    cos_i.push_back(2.0f * rng.NextFloat() - 1.0f);
    eta.push_back(std::pow(10.0f, rng.NextFloat() - 0.5f));
  }
  for (float e : bsdf_test::HardEtas()) {
    for (float c : bsdf_test::HardCosines()) cos_i.push_back(c), eta.push_back(e);
    // Around the critical angle, from the denser side.
    const float rel = e < 1 ? e : 1.0f / e;
    const float crit = std::sqrt((1.0f - rel) * (1.0f + rel));
    const float sign = e < 1 ? 1.0f : -1.0f;
    for (int j = -50; j <= 50; ++j) {
      cos_i.push_back(sign * std::nextafter(crit, j < 0 ? 0.0f : 2.0f) * (1.0f + j * 1e-7f));
      eta.push_back(e);
    }
  }
  const size_t n = cos_i.size();
  std::vector<float> f0(n), ct0(n), f1(n), ct1(n);
  ptlab::DielectricFresnelBatch(cos_i.data(), eta.data(), n, f0.data(), ct0.data());
  ForEachTarget([&](const char* target) {
    simd::DielectricFresnelBatch(cos_i.data(), eta.data(), n, f1.data(), ct1.data());
    Contract cf{"dielectric Fresnel F", 0, 1e-6}, ct{"dielectric Fresnel cos_t", 0, 1e-6};
    for (size_t i = 0; i < n; ++i) {
      ASSERT_TRUE(f1[i] >= 0 && f1[i] <= 1.0f && ct1[i] >= 0 && ct1[i] <= 1.0f) << i;
      cf.Check(i, f1[i], f0[i]);
      ct.Check(i, ct1[i], ct0[i]);
    }
    cf.Report(target);
    ct.Report(target);
  });
}

// ------------------------------------------------------------------------------ shade step

// Random rows plus one row per hard parameter combination, for every model.
void AddMaterialRows(MaterialTables* m, Pcg32& rng) {
  for (int i = 0; i < 64; ++i) {
    const float r = rng.NextFloat(), g = rng.NextFloat();
    m->AddDiffuse({r, g, rng.NextFloat()});
    m->AddMirror(i % 2 == 0 ? Color3f{1, 1, 1} : Color3f{r, g, rng.NextFloat()});
    const float eta = std::pow(10.0f, rng.NextFloat() - 0.5f);
    const uint8_t flags = static_cast<uint8_t>(i % 4);  // both options, alone and together
    m->AddDielectric(eta, 1.0f, flags);
    const char* names[] = {"Au", "Ag", "Al", "Cu", "Fe", "Na", "Si", "none"};
    Color3f e, k;
    LookupConductorPreset(names[i % 8], &e, &k);
    m->AddConductor(bsdf_test::RandomAlpha(rng), e, k);
    const float kd = rng.NextFloat();
    m->AddRoughPlastic(bsdf_test::RandomAlpha(rng), 1.0f + rng.NextFloat(), 1.0f,
                       {kd, kd * rng.NextFloat(), kd * 0.5f});
  }
  for (float eta : bsdf_test::HardEtas()) {
    m->AddDielectric(eta, 1.0f, kDielectricSchlick);
    m->AddDielectric(eta, 1.0f, kDielectricRefractOnly | kDielectricScaleRadiance);
    m->AddTintedDielectric(eta, 1.0f, kDielectricSchlick, {1.0f, 0.9f, 0.8f}, {0.75f, 0.75f, 1.0f});
  }
  for (float alpha : bsdf_test::HardAlphas()) {
    Color3f e, k;
    LookupConductorPreset("Cu", &e, &k);
    m->AddConductor(alpha, e, k);
    m->AddConductor(alpha, {1e30f, 0.0f, 1e-40f}, {0.0f, 1e30f, 1e-40f});
    m->AddRoughPlastic(alpha, 1.5046f, 1.000277f, {0.5f, 0.5f, 0.5f});
    m->AddRoughPlastic(alpha, 1.5f, 1.0f, {0.0f, 0.0f, 0.0f});
    m->AddDiffuse({alpha, alpha, alpha});
  }
  // matB: smooth plastics (random and hard η, both models), thin dielectrics, blends of every
  // kind of child, and two-sided rows of several tags (their wo below the surface flips).
  for (int i = 0; i < 32; ++i) {
    PlasticDesc d;
    d.int_ior = 1.0f + rng.NextFloat(), d.ext_ior = 1.0f, d.nonlinear = i % 2 == 0;
    d.diffuse = {rng.NextFloat(), rng.NextFloat(), rng.NextFloat()};
    d.specular = {rng.NextFloat(), 1.0f, rng.NextFloat()};
    const MaterialRef p = m->AddPlastic(*MakePlasticRow(d));
    if (i % 4 == 1) m->two_sided.Set(p);
    m->AddThinDielectric(std::pow(10.0f, rng.NextFloat() - 0.5f), {rng.NextFloat(), 1.0f, 0.5f},
                         {1.0f, rng.NextFloat(), 0.25f});
  }
  for (float eta : bsdf_test::HardEtas()) {
    PlasticDesc d;
    d.int_ior = eta, d.ext_ior = 1.0f;
    m->AddPlastic(*MakePlasticRow(d));
    d.diffuse = {0, 0, 0};
    m->AddPlastic(*MakePlasticRow(d));
    m->AddThinDielectric(eta);
  }
  for (float alpha : {1e-4f, 0.05f, 0.5f, 1.0f}) {  // rough rows (plastic8: their SIMD twin)
    PlasticDesc d;
    d.distribution = alpha < 0.1f ? CoatingDistribution::kGgx : CoatingDistribution::kBeckmann;
    d.alpha = alpha, d.int_ior = 1.5f, d.ext_ior = 1.0f, d.diffuse = {0.2f, 0.5f, 0.9f};
    m->AddPlastic(*MakePlasticRow(d));
  }
  const uint32_t plastics = uint32_t(m->plastic.size());
  for (int i = 0; i < 24; ++i) {
    const float w = i < 3 ? float(i) * 0.5f : rng.NextFloat();
    const auto pick = [&](int k) {
      switch (k % 5) {
        case 0:
          return MaterialRef::Make(MaterialTag::kDiffuse, uint32_t(i));
        case 1:
          return MaterialRef::Make(MaterialTag::kMirror, 0);
        case 2:
          return MaterialRef::Make(MaterialTag::kPlastic, uint32_t(i) % plastics);
        case 3:
          return MaterialRef::Make(MaterialTag::kConductor, uint32_t(i));
        default:
          return MaterialRef::Make(MaterialTag::kThinDielectric, uint32_t(i));
      }
    };
    const MaterialRef b = m->AddBlend(w, pick(i), pick(i / 5 + 1));
    if (i % 6 == 5) m->two_sided.Set(b);
  }
  m->AddBlend(0.5f, MaterialRef::Make(MaterialTag::kBlend, 3),
              MaterialRef::Make(MaterialTag::kBlend, 7));  // nested
  for (uint32_t row : {1u, 5u, 9u}) m->two_sided.Set(MaterialRef::Make(MaterialTag::kDiffuse, row));
  // matA: rough dielectric rows (own stream, so the rows above stay as they were); their
  // samples are checked under their own contract in microfacet8_test.cpp.
  Pcg32 mrng(77, 5);
  for (int i = 0; i < 64; ++i) {
    const float alpha = bsdf_test::RandomAlpha(mrng);
    const float alpha_v = i % 3 == 0 ? alpha : bsdf_test::RandomAlpha(mrng);
    const float eta = std::pow(10.0f, mrng.NextFloat() - 0.5f);
    m->AddRoughDielectric(alpha, alpha_v, uint8_t(i % 4), eta, 1.0f, {1, 1, 1},
                          {mrng.NextFloat(), 1, 1});
  }
  for (float alpha : bsdf_test::HardAlphas())
    for (float eta : bsdf_test::HardEtas())
      m->AddRoughDielectric(alpha, alpha * 100.0f, kMicrofacetSampleVisible, eta, 1.0f);
}

size_t RowCount(const MaterialTables& m, MaterialTag tag) {
  switch (tag) {
    case MaterialTag::kDiffuse:
      return m.diffuse.size();
    case MaterialTag::kMirror:
      return m.mirror.size();
    case MaterialTag::kDielectric:
      return m.dielectric.size();
    case MaterialTag::kConductor:
      return m.conductor.size();
    case MaterialTag::kRoughPlastic:
      return m.rough_plastic.size();
    // matB
    case MaterialTag::kPlastic:
      return m.plastic.size();
    case MaterialTag::kThinDielectric:
      return m.thin_dielectric.size();
    case MaterialTag::kBlend:
      return m.blend.size();
    case MaterialTag::kMask:  // mask: its own test (mask8_test.cpp)
      return m.mask.size();
    case MaterialTag::kRoughDielectric:  // matA
      return m.rough_dielectric.size();
    // principled: AddMaterialRows adds none (0 rows: skipped here); the twin has its own test
    // and contract (principled8_test.cpp: refraction, eta ≠ 1, sampler cancellations).
    case MaterialTag::kPrincipled:
      return m.principled.size();
    case MaterialTag::kPrincipledThin:
      return m.principled_thin.size();
  }
  return 0;
}

struct ShadeData {
  std::vector<uint32_t> index;
  Dirs wo, wl;
  std::vector<float> u_lobe, u_x, u_y;
  ShadeInputs View() const {
    ShadeInputs in;
    in.wo = wo.View(), in.wl = wl.View();
    in.u_lobe = u_lobe.data(), in.u_x = u_x.data(), in.u_y = u_y.data();
    return in;
  }
};

struct ShadeResult {
  std::vector<float> f[3], pdf_l, weight[3], pdf, eta, delta;
  Dirs wi;
  explicit ShadeResult(size_t n) {
    for (auto* v :
         {&f[0], &f[1], &f[2], &pdf_l, &weight[0], &weight[1], &weight[2], &pdf, &eta, &delta})
      v->assign(n, -7.0f);  // poison: every output must be written
    wi.Resize(n);
  }
  ShadeOutputs Out() {
    ShadeOutputs o;
    o.f = {f[0].data(), f[1].data(), f[2].data()};
    o.pdf_l = pdf_l.data();
    o.wi = wi.Out();
    o.weight = {weight[0].data(), weight[1].data(), weight[2].data()};
    o.pdf = pdf.data();
    o.eta = eta.data();
    o.delta = delta.data();
    return o;
  }
};

ShadeData MakeShadeData(const MaterialTables& m, MaterialTag tag, size_t random_count) {
  ShadeData s;
  Pcg32 rng(1234, 7 + static_cast<int>(tag));
  const uint32_t rows = static_cast<uint32_t>(RowCount(m, tag));
  for (size_t i = 0; i < random_count; ++i) {
    s.index.push_back(std::min(rows - 1, uint32_t(rng.NextFloat() * rows)));
    Vec3f wo = bsdf_test::RandomUpperDirection(rng);
    if (i % 8 == 0) wo.z = -wo.z;  // from inside / below
    s.wo.Push(wo);
    s.wl.Push(i % 2 ? bsdf_test::NearSpecularPartner(bsdf_test::RandomAlpha(rng), wo, rng)
                    : bsdf_test::RandomUpperDirection(rng));
    const float a = rng.NextFloat(), b = rng.NextFloat();
    s.u_lobe.push_back(a), s.u_x.push_back(b), s.u_y.push_back(rng.NextFloat());
  }
  const std::vector<Vec3f> dirs = bsdf_test::HardDirections(/*with_non_unit=*/false);
  const std::vector<float> us = bsdf_test::HardUs();
  for (uint32_t row = 0; row < rows; row += 3)
    for (size_t a = 0; a < dirs.size(); ++a)
      for (size_t j = 0; j < us.size(); ++j) {
        s.index.push_back(row);
        s.wo.Push(dirs[a]);
        s.wl.Push(dirs[(a * 7 + j) % dirs.size()]);
        s.u_lobe.push_back(us[(a + j) % us.size()]);
        s.u_x.push_back(us[j]);
        s.u_y.push_back(us[(j * 3 + a) % us.size()]);
      }
  return s;
}

// Checks simd::ShadeBatch output r1 against the oracle's r0 under the ShadeBatch contract.
void CheckShadeContract(const MaterialTables& m, MaterialTag tag, const ShadeData& s,
                        const ShadeResult& r0, const ShadeResult& r1, const char* target) {
  const char* names[] = {
      "diffuse",          "mirror", "dielectric", "conductor",       "rough plastic",
      "rough dielectric", "mask",   "plastic",    "thin dielectric", "blend"};
  const std::string name = names[static_cast<int>(tag)];
  Contract f{name + " f(wo,wl)", 2e-5, 1e-30}, pl{name + " pdf(wo,wl)", 2e-5, 1e-30};
  const bool delta = IsDeltaMaterial(tag);
  Contract wxy{name + " sample wi.xy", 0, 2e-6};
  Contract pdf{name + " sample pdf", delta ? 0 : 2e-5, delta ? 2e-6 : 1e-30};
  Contract w{name + " sample weight", 2e-5, 1e-20};
  size_t mismatched = 0, valid = 0;
  for (size_t i = 0; i < s.index.size(); ++i) {
    const MaterialRef ref = MaterialRef::Make(tag, s.index[i]);
    const Vec3f wo = s.wo[i];
    for (int c = 0; c < 3; ++c) {
      ASSERT_TRUE(std::isfinite(r1.f[c][i]) && r1.f[c][i] >= 0) << name << " " << i;
      ASSERT_TRUE(std::isfinite(r1.weight[c][i]) && r1.weight[c][i] >= 0) << name << " " << i;
      f.Check(i, r1.f[c][i], r0.f[c][i]);
    }
    ASSERT_TRUE(std::isfinite(r1.pdf[i]) && r1.pdf[i] >= 0 && std::isfinite(r1.pdf_l[i]) &&
                r1.pdf_l[i] >= 0 && std::isfinite(r1.eta[i]) && r1.eta[i] > 0)
        << name << " " << i;
    pl.Check(i, r1.pdf_l[i], r0.pdf_l[i]);
    // matA: the rough dielectric's samples, whose pdf is that of the sampled normal, are
    // checked under their own contract in microfacet8_test.cpp.
    if (tag == MaterialTag::kRoughDielectric) continue;
    // plastic8: the plastic tag's rough rows sample visible normals (microfacet8): their samples
    // are checked under that sampler's contract in plastic_rough8_test.cpp.
    if (tag == MaterialTag::kPlastic && PlasticRowIsRough(m.plastic, s.index[i])) continue;
    const bool v0 = r0.pdf[i] > 0, v1 = r1.pdf[i] > 0;
    // Whether this row's sample came from cosine-hemisphere sampling (z from sqrt(1 − r²)).
    bool cosine = tag == MaterialTag::kDiffuse;
    if (tag == MaterialTag::kRoughPlastic) {
      const auto& t = m.rough_plastic;
      const uint32_t k = s.index[i];
      const float ks =
          std::clamp(1.0f - std::max(t.kd_r[k], std::max(t.kd_g[k], t.kd_b[k])), 0.0f, 1.0f);
      cosine = !(s.u_lobe[i] < ks);
    }
    if (tag == MaterialTag::kPlastic || tag == MaterialTag::kBlend) cosine = true;  // matB
    const float z_tol = cosine ? 2e-3f : 2e-6f;
    if (v0 != v1) {
      ++mismatched;
      ASSERT_LE(std::fabs(v0 ? r0.wi.z[i] : r1.wi.z[i]), z_tol)
          << name << ": validity differs at " << i;
      continue;
    }
    if (!v1) continue;
    ++valid;
    const bool reflected0 = r0.wi.z[i] * wo.z >= 0, reflected1 = r1.wi.z[i] * wo.z >= 0;
    if (tag == MaterialTag::kDielectric && reflected0 != reflected1) {
      // Reflection on one path, refraction on the other: only where u_lobe ≈ F.
      ++mismatched;
      const float fresnel0 = reflected0 ? r0.pdf[i] : 1.0f - r0.pdf[i];
      ASSERT_NEAR(s.u_lobe[i], fresnel0, 2e-6f) << "lobe differs at " << i;
      continue;
    }
    wxy.Check(i, r1.wi.x[i], r0.wi.x[i]);
    wxy.Check(i, r1.wi.y[i], r0.wi.y[i]);
    const float z0 = r0.wi.z[i], z1 = r1.wi.z[i];
    EXPECT_TRUE(std::fabs(z1 - z0) <= 2e-6f || std::fabs(z1 * z1 - z0 * z0) <= 4e-6f)
        << name << " wi.z at " << i << ": " << z1 << " vs " << z0;
    const Vec3f wi = r1.wi[i];
    // matB: the lobe kind is bit-identical (the lobe choice is), and a delta sample of a model
    // that mixes lobes is checked as a delta model's.
    ASSERT_EQ(r1.delta[i], r0.delta[i]) << name << " delta flag at " << i;
    if (delta || r0.delta[i] != 0) {
      pdf.Check(i, r1.pdf[i], r0.pdf[i]);
      for (int c = 0; c < 3; ++c) w.Check(i, r1.weight[c][i], r0.weight[c][i]);
      EXPECT_FLOAT_EQ(r1.eta[i], r0.eta[i]) << name << " " << i;
      continue;
    }
    EXPECT_EQ(r1.eta[i], 1.0f);
    // matB: a two-sided row with wo below is shaded as its mirror image.
    const bool flip = m.two_sided.Of(ref) && wo.z < 0;
    const float oz = flip ? -wo.z : wo.z, iz = flip ? -wi.z : wi.z;
    // Below cos θ = 1e-30 the pdf and weight pass through denormals: finiteness only.
    if (oz < 1e-30f || iz < 1e-30f) continue;
    const float opdf = BsdfPdf(m, ref, wo, wi);
    const Color3f of = BsdfEval(m, ref, wo, wi);
    pdf.Check(i, r1.pdf[i], opdf);
    for (int c = 0; c < 3; ++c) w.Check(i, r1.weight[c][i], of[c] * iz / opdf);
  }
  for (const Contract* c : {&f, &pl, &wxy, &pdf, &w}) c->Report(target);
  if (tag == MaterialTag::kRoughDielectric) return;  // matA: see above
  // Each mismatch was checked to sit on a decision boundary above; the hard cases put many
  // rows exactly there (u = 0 or 1 − 2⁻²⁴ lands on the rim of the concentric disk).
  EXPECT_LT(mismatched, s.index.size() / 50) << name;
  EXPECT_GT(valid, s.index.size() / 4) << name;
}

TEST(Shade8, ShadeBatchMatchesOracleForEveryMaterialOnEveryTarget) {
  MaterialTables m;
  Pcg32 rng(31, 4);
  AddMaterialRows(&m, rng);
  // 2^18 random rows per material (1.3·10⁶ over the five: the render's BSDF stage runs this
  // kernel) plus the hard cases of every row.
  for (int t = 0; t < kMaterialTagCount; ++t) {
    const MaterialTag tag = static_cast<MaterialTag>(t);
    if (RowCount(m, tag) == 0) continue;  // another branch's tag
    const ShadeData s = MakeShadeData(m, tag, size_t(1) << 18);
    const size_t n = s.index.size();
    ShadeResult r0(n);
    ptlab::ShadeBatch(m, tag, s.index.data(), n, s.View(), r0.Out());
    ForEachTarget([&](const char* target) {
      ShadeResult r1(n);
      simd::ShadeBatch(m, tag, s.index.data(), n, s.View(), r1.Out());
      CheckShadeContract(m, tag, s, r0, r1, target);
    });
  }
}

// kern: a blend batch whose rows all have one first-child kind and one second-child kind takes
// ShadeBlend's direct path (the children's kernels on the rows as they are, each picked child
// sampled over every row); a batch mixing child kinds regroups the rows by child tag. Each row's
// outputs must be the same bits either way: the uniform rows are shaded alone and again
// interleaved with rows of other child kinds, on every target, for batches where both children
// are picked, only the first (w = 0) and only the second (w = 1); the uniform batch is also
// checked against the oracle under the ShadeBatch contract.
TEST(Shade8, BlendOfUniformChildKindsEqualsRowsInAMixedBatch) {
  MaterialTables m;
  Pcg32 rng(31, 4);
  AddMaterialRows(&m, rng);
  const uint32_t mixed_rows = uint32_t(m.blend.size());  // blends of every kind of child
  const uint32_t plastics = uint32_t(m.plastic.size());
  for (int i = 0; i < 24; ++i) {
    const float w = i == 0 ? 0.0f : i == 1 ? 1.0f : rng.NextFloat();
    const MaterialRef b =
        m.AddBlend(w, MaterialRef::Make(MaterialTag::kDiffuse, uint32_t(i)),
                   MaterialRef::Make(MaterialTag::kPlastic, uint32_t(i * 7) % plastics));
    if (i % 6 == 5) m.two_sided.Set(b);
  }
  const uint32_t uniform_rows = uint32_t(m.blend.size()) - mixed_rows;
  // Enough random rows that the hard cases (every third row's grid of grazing directions and
  // extreme u, all cosine-lobe children here) stay below the contract's 1 in 50 rows whose
  // validity may differ on a decision boundary.
  const ShadeData base = MakeShadeData(m, MaterialTag::kBlend, size_t(1) << 16);
  // rows(k): all uniform rows (k = 2), only the w = 0 row (k = 0), only the w = 1 row (k = 1).
  for (int k : {2, 0, 1}) {
    ShadeData s = base;
    for (uint32_t& row : s.index) row = mixed_rows + (k == 2 ? row % uniform_rows : uint32_t(k));
    const size_t n = s.index.size();
    ShadeData mix;  // row i of s at 2i, a row with other child kinds at 2i + 1
    for (size_t i = 0; i < n; ++i) {
      for (uint32_t row : {s.index[i], uint32_t(i % mixed_rows)}) {
        mix.index.push_back(row);
        mix.wo.Push(s.wo[i]), mix.wl.Push(s.wl[i]);
        mix.u_lobe.push_back(s.u_lobe[i]), mix.u_x.push_back(s.u_x[i]);
        mix.u_y.push_back(s.u_y[i]);
      }
    }
    ShadeResult r0(n);
    ptlab::ShadeBatch(m, MaterialTag::kBlend, s.index.data(), n, s.View(), r0.Out());
    ForEachTarget([&](const char* target) {
      ShadeResult alone(n), mixed(2 * n);
      simd::ShadeBatch(m, MaterialTag::kBlend, s.index.data(), n, s.View(), alone.Out());
      simd::ShadeBatch(m, MaterialTag::kBlend, mix.index.data(), 2 * n, mix.View(), mixed.Out());
      for (size_t i = 0; i < n; ++i) {
        const size_t j = 2 * i;
        const auto same = [](float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; };
        for (int c = 0; c < 3; ++c) {
          ASSERT_TRUE(same(alone.f[c][i], mixed.f[c][j])) << target << " k " << k << " row " << i;
          ASSERT_TRUE(same(alone.weight[c][i], mixed.weight[c][j])) << target << " row " << i;
        }
        ASSERT_TRUE(same(alone.pdf_l[i], mixed.pdf_l[j])) << target << " row " << i;
        ASSERT_TRUE(same(alone.wi.x[i], mixed.wi.x[j]) && same(alone.wi.y[i], mixed.wi.y[j]) &&
                    same(alone.wi.z[i], mixed.wi.z[j]))
            << target << " row " << i;
        ASSERT_TRUE(same(alone.pdf[i], mixed.pdf[j]) && same(alone.eta[i], mixed.eta[j]) &&
                    same(alone.delta[i], mixed.delta[j]))
            << target << " row " << i;
      }
      if (k == 2) CheckShadeContract(m, MaterialTag::kBlend, s, r0, alone, target);
    });
  }
}

TEST(Shade8, WhiteFurnaceOfUnitFresnelConductorIsAtMostOne) {
  // The conductor's albedo with F = 1 (Mitsuba's "none"), as the mean SIMD sample weight over a
  // stratified grid of the sampling square, on every target.
  MaterialTables m;
  const float alphas[] = {1e-3f, 0.05f, 0.5f, 1.0f, 2.0f};
  for (float a : alphas) m.AddConductor(a, {0, 0, 0}, {1, 1, 1});
  const float degrees[] = {0.0f, 45.0f, 80.0f, 89.0f, 89.9f};
  const int grid = 128;
  ShadeData s;
  for (uint32_t row = 0; row < 5; ++row)
    for (float deg : degrees)
      for (int i = 0; i < grid; ++i)
        for (int j = 0; j < grid; ++j) {
          s.index.push_back(row);
          s.wo.Push(DirectionWithCos(std::cos(Radians(deg)), 0.3f));
          s.u_lobe.push_back(0.5f), s.u_x.push_back((i + 0.5f) / grid);
          s.u_y.push_back((j + 0.5f) / grid);
        }
  const size_t n = s.index.size();
  ShadeInputs in = s.View();
  in.wl = {};
  ForEachTarget([&](const char* target) {
    ShadeResult r(n);
    simd::ShadeBatch(m, MaterialTag::kConductor, s.index.data(), n, in, r.Out());
    double worst = 0;
    for (size_t c = 0; c < 25; ++c) {
      double sum = 0;
      for (int k = 0; k < grid * grid; ++k) sum += r.weight[1][c * grid * grid + k];
      const double albedo = sum / (grid * grid);
      worst = std::max(worst, albedo);
      EXPECT_LE(albedo, 1.0 + 1e-3) << "alpha " << alphas[c / 5] << " theta " << degrees[c % 5];
      EXPECT_GE(albedo, 0.0);
    }
    std::printf("[%s] white furnace, F = 1: max albedo %.6f\n", target, worst);
  });
}

TEST(Shade8, NonUnitAndHugeInputsStayFinite) {
  MaterialTables m;
  Pcg32 rng(3, 3);
  AddMaterialRows(&m, rng);
  const std::vector<Vec3f> dirs = bsdf_test::HardDirections(/*with_non_unit=*/true);
  ForEachTarget([&](const char*) {
    for (int t = 0; t < kMaterialTagCount; ++t) {
      const MaterialTag tag = static_cast<MaterialTag>(t);
      if (RowCount(m, tag) == 0) continue;  // another branch's tag
      ShadeData s;
      for (uint32_t row = 0; row < RowCount(m, tag); row += 5)
        for (const Vec3f& wo : dirs)
          for (const Vec3f& wl : {dirs[0], dirs.back(), dirs[dirs.size() - 3]}) {
            s.index.push_back(row), s.wo.Push(wo), s.wl.Push(wl);
            s.u_lobe.push_back(0.5f), s.u_x.push_back(kOneMinusEpsilon), s.u_y.push_back(0.0f);
          }
      const size_t n = s.index.size();
      ShadeResult r(n);
      simd::ShadeBatch(m, tag, s.index.data(), n, s.View(), r.Out());
      for (size_t i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) {
          ASSERT_TRUE(std::isfinite(r.f[c][i]) && r.f[c][i] >= 0) << t << " " << i;
          ASSERT_TRUE(std::isfinite(r.weight[c][i])) << t << " " << i;
        }
        ASSERT_TRUE(std::isfinite(r.pdf[i]) && r.pdf[i] >= 0 && std::isfinite(r.pdf_l[i]) &&
                    r.pdf_l[i] >= 0 && std::isfinite(r.wi.x[i]) && std::isfinite(r.wi.y[i]) &&
                    std::isfinite(r.wi.z[i]))
            << t << " " << i;
      }
    }
  });
}

TEST(Shade8, PartialBlocksAndEvallessCallsMatchFullRuns) {
  MaterialTables m;
  Pcg32 rng(8, 8);
  AddMaterialRows(&m, rng);
  ForEachTarget([&](const char*) {
    for (int t = 0; t < kMaterialTagCount; ++t) {
      const MaterialTag tag = static_cast<MaterialTag>(t);
      if (RowCount(m, tag) == 0) continue;  // another branch's tag
      const ShadeData s = MakeShadeData(m, tag, 40);
      ShadeResult full(40);
      simd::ShadeBatch(m, tag, s.index.data(), 40, s.View(), full.Out());
      for (size_t n : {0, 1, 3, 7, 8, 9, 15, 17, 33}) {
        ShadeResult part(n + 1);
        ShadeInputs in = s.View();
        if (n % 2) in.wl = {};  // no evaluation: f and pdf_l stay untouched
        simd::ShadeBatch(m, tag, s.index.data(), n, in, part.Out());
        for (size_t i = 0; i < n; ++i) {
          ASSERT_EQ(part.wi.x[i], full.wi.x[i]) << t << " " << n << " " << i;
          ASSERT_EQ(part.wi.z[i], full.wi.z[i]) << t << " " << n << " " << i;
          ASSERT_EQ(part.weight[1][i], full.weight[1][i]) << t << " " << n << " " << i;
          ASSERT_EQ(part.pdf[i], full.pdf[i]) << t << " " << n << " " << i;
          if (n % 2) {
            ASSERT_EQ(part.f[0][i], -7.0f);
          } else {
            ASSERT_EQ(part.f[2][i], full.f[2][i]);
            ASSERT_EQ(part.pdf_l[i], full.pdf_l[i]);
          }
        }
        ASSERT_EQ(part.pdf[n], -7.0f) << "wrote past n";
      }
    }
  });
}

// Evaluation only (u_lobe null): f and pdf_l bit-identical to a full run's on every target and
// for the oracle, the sample outputs neither written (poison kept) nor needed (null pointers).
TEST(Shade8, SamplelessCallsEvaluateOnly) {
  MaterialTables m;
  Pcg32 rng(9, 3);
  AddMaterialRows(&m, rng);
  const auto check = [&](auto&& batch) {
    for (int t = 0; t < kMaterialTagCount; ++t) {
      const MaterialTag tag = static_cast<MaterialTag>(t);
      if (RowCount(m, tag) == 0) continue;  // another branch's tag
      const ShadeData s = MakeShadeData(m, tag, 40);
      ShadeResult full(40);
      batch(m, tag, s.index.data(), 40, s.View(), full.Out());
      for (size_t n : {0, 1, 3, 7, 8, 9, 15, 17, 33, 40}) {
        ShadeInputs in = s.View();
        in.u_lobe = nullptr, in.u_x = nullptr, in.u_y = nullptr;
        ShadeResult part(n + 1);
        batch(m, tag, s.index.data(), n, in, part.Out());
        for (size_t i = 0; i < n; ++i) {
          for (int c = 0; c < 3; ++c) ASSERT_EQ(part.f[c][i], full.f[c][i]) << t << " " << i;
          ASSERT_EQ(part.pdf_l[i], full.pdf_l[i]) << t << " " << n << " " << i;
          ASSERT_EQ(part.pdf[i], -7.0f) << t << " " << n << " " << i;
          ASSERT_EQ(part.weight[0][i], -7.0f) << t << " " << n << " " << i;
          ASSERT_EQ(part.eta[i], -7.0f) << t << " " << n << " " << i;
        }
        ASSERT_EQ(part.pdf_l[n], -7.0f) << "wrote past n";
        ShadeOutputs eval_only;
        eval_only.f = {part.f[0].data(), part.f[1].data(), part.f[2].data()};
        eval_only.pdf_l = part.pdf_l.data();
        batch(m, tag, s.index.data(), n, in, eval_only);  // no sample columns at all
      }
    }
  };
  check([](auto&&... a) { ptlab::ShadeBatch(a...); });
  ForEachTarget([&](const char*) { check([](auto&&... a) { simd::ShadeBatch(a...); }); });
}

TEST(Shade8, ShadeHitsPartitionsByMaterial) {
  MaterialTables m;
  Pcg32 rng(4, 2);
  AddMaterialRows(&m, rng);
  // Hits over all tags (no rough plastic at all in the second half) and some misses.
  const size_t n = 1000;
  std::vector<MaterialRef> refs;
  ShadeData s = MakeShadeData(m, MaterialTag::kDiffuse, n);
  for (size_t i = 0; i < n; ++i) {
    const int t = i % 13 == 0 ? 15 : int(rng.NextFloat() * (i < n / 2 ? 5 : 4));
    const MaterialTag tag = static_cast<MaterialTag>(std::min(t, 4));
    refs.push_back(t == 15 ? MaterialRef::None()
                           : MaterialRef::Make(tag, uint32_t(rng.NextFloat() * RowCount(m, tag))));
  }
  MaterialPartition part;
  PartitionByMaterial(refs.data(), n, &part);
  size_t grouped = 0;
  for (int t = 0; t < kMaterialTagCount; ++t) {
    const MaterialTag tag = static_cast<MaterialTag>(t);
    grouped += part.Count(tag);
    for (uint32_t k = part.begin[t]; k < part.begin[t + 1]; ++k) {
      ASSERT_EQ(refs[part.slot[k]].tag(), tag);
      ASSERT_EQ(refs[part.slot[k]].index(), part.index[k]);
      if (k > part.begin[t]) {
        ASSERT_LT(part.slot[k - 1], part.slot[k]);  // stable
      }
    }
  }
  EXPECT_EQ(grouped, n - (n + 12) / 13);

  ShadeScratch scratch;
  ShadeResult scalar(n), vec(n);
  ptlab::ShadeHits(m, refs.data(), n, s.View(), scalar.Out(), &scratch);
  // The scalar stage is exactly the per-hit dispatch.
  for (size_t i = 0; i < n; ++i) {
    const Vec3f wo = s.wo[i];
    if (!refs[i].valid()) {
      ASSERT_EQ(scalar.pdf[i], 0.0f);
      ASSERT_EQ(scalar.f[0][i], 0.0f);
      ASSERT_EQ(scalar.eta[i], 1.0f);
      continue;
    }
    ASSERT_EQ(scalar.f[1][i], BsdfEval(m, refs[i], wo, s.wl[i]).g) << i;
    ASSERT_EQ(scalar.pdf_l[i], BsdfPdf(m, refs[i], wo, s.wl[i])) << i;
    BsdfSample bs;
    const bool ok = BsdfSampleDirection(m, refs[i], wo, s.u_lobe[i], {s.u_x[i], s.u_y[i]}, &bs);
    ASSERT_EQ(scalar.pdf[i], ok ? bs.pdf : 0.0f) << i;
  }
  ForEachTarget([&](const char*) {
    simd::ShadeHits(m, refs.data(), n, s.View(), vec.Out(), &scratch);
    // The SIMD stage is exactly simd::ShadeBatch on each hit's own row.
    for (size_t i = 0; i < n; ++i) {
      if (!refs[i].valid()) {
        ASSERT_EQ(vec.pdf[i], 0.0f);
        ASSERT_EQ(vec.weight[2][i], 0.0f);
        ASSERT_EQ(vec.eta[i], 1.0f);
        continue;
      }
      ShadeData one;
      one.index = {refs[i].index()};
      one.wo.Push(s.wo[i]), one.wl.Push(s.wl[i]);
      one.u_lobe = {s.u_lobe[i]}, one.u_x = {s.u_x[i]}, one.u_y = {s.u_y[i]};
      ShadeResult r(1);
      simd::ShadeBatch(m, refs[i].tag(), one.index.data(), 1, one.View(), r.Out());
      ASSERT_EQ(vec.f[0][i], r.f[0][0]) << i;
      ASSERT_EQ(vec.pdf_l[i], r.pdf_l[0]) << i;
      ASSERT_EQ(vec.wi.y[i], r.wi.y[0]) << i;
      ASSERT_EQ(vec.weight[1][i], r.weight[1][0]) << i;
      ASSERT_EQ(vec.pdf[i], r.pdf[0]) << i;
      ASSERT_EQ(vec.eta[i], r.eta[0]) << i;
    }
  });
}

// All hits of one material: ShadeHits runs the batch on the arrays themselves (no gather or
// scatter), with the same results as the per-hit dispatch (scalar) and as simd::ShadeBatch
// over the rows (SIMD).
TEST(Shade8, ShadeHitsOfOneMaterialRunsOnTheInputArrays) {
  MaterialTables m;
  Pcg32 rng(8, 3);
  AddMaterialRows(&m, rng);
  const size_t n = 333;
  for (int t = 0; t < kMaterialTagCount; ++t) {
    const MaterialTag tag = static_cast<MaterialTag>(t);
    if (RowCount(m, tag) == 0) continue;  // another branch's tag
    const ShadeData s = MakeShadeData(m, tag, n);
    const size_t rows = s.index.size();
    std::vector<MaterialRef> refs;
    for (size_t i = 0; i < rows; ++i) refs.push_back(MaterialRef::Make(tag, s.index[i]));
    ShadeScratch scratch;
    ShadeResult scalar(rows), direct(rows);
    ptlab::ShadeHits(m, refs.data(), rows, s.View(), scalar.Out(), &scratch);
    for (size_t i = 0; i < rows; ++i) {
      BsdfSample bs;
      const bool ok =
          BsdfSampleDirection(m, refs[i], s.wo[i], s.u_lobe[i], {s.u_x[i], s.u_y[i]}, &bs);
      ASSERT_EQ(scalar.pdf[i], ok ? bs.pdf : 0.0f) << i;
      ASSERT_EQ(scalar.f[0][i], BsdfEval(m, refs[i], s.wo[i], s.wl[i]).r) << i;
    }
    ForEachTarget([&](const char*) {
      ShadeResult vec(rows);
      simd::ShadeHits(m, refs.data(), rows, s.View(), vec.Out(), &scratch);
      simd::ShadeBatch(m, tag, s.index.data(), rows, s.View(), direct.Out());
      for (size_t i = 0; i < rows; ++i) {
        ASSERT_EQ(vec.pdf[i], direct.pdf[i]) << i;
        ASSERT_EQ(vec.wi.x[i], direct.wi.x[i]) << i;
        ASSERT_EQ(vec.weight[0][i], direct.weight[0][i]) << i;
        ASSERT_EQ(vec.f[2][i], direct.f[2][i]) << i;
      }
    });
  }
}

}  // namespace
}  // namespace ptlab
