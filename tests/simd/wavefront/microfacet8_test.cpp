// SIMD twins of the Mitsuba microfacet models (simd/wavefront/rough_conductor8-inl.h,
// rough_dielectric8-inl.h, the smooth conductor in ShadeMirror) against their scalar oracle
// (ptlab::ShadeBatch), on random and hard-case inputs, on every compiled Highway target.
#include "simd/targets.h"  // first: the target policy (must precede every hwy/ include)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/conductor_presets.h"
#include "engine/bsdf/microfacet.h"
#include "engine/core/rng.h"
#include "engine/wavefront/bsdf.h"
#include "simd/dispatched_target.h"
#include "simd/wavefront/bsdf8.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"
#include "tests/simd/for_each_target.h"

namespace ptlab {
namespace {

// The contract the test holds each target to (per row; the oracle's value is o):
// - f(wo, wl), pdf(wo, wl): |Δ| ≤ 2e-5 |o| + 1e-30 (the same operations; only exp/log differ
//   by an ulp);
// - validity of the sample (pdf > 0) equal, except on a decision boundary: |wi.z| ≤ 1e-4, or
//   |u_lobe − F| ≤ 1e-4 for the reflect/refract choice of the dielectric;
// - the sampled wi: |Δ| ≤ 5e-5 per component (hwy's Log/Exp/Sin/Cos in the normal sampler and
//   3 Newton steps of the Beckmann visible-slope inversion, whose erf⁻¹ is steep as u → 1;
//   seen 2.3e-5); eta equal;
// - where |cos θo| and |cos θi| ≥ 0.02 and (refraction) |wo + η_r wi| ≥ 0.1, the sample's
//   pdf and weight: |Δ| ≤ (1e-4 + 4e-7 / α²_min) |o| + 1e-30 (1e-4: hwy's Sin/Cos of
//   2π u near 2π are off by ~4e-7 absolute, a tilt of the normal; seen 4.6e-5), α_min the smaller
//   clamped roughness: a δ ≈ 2e-7 change of the normal changes D by ~2 δ tanθ/α² relatively,
//   and tanθ ≈ α at the lobe, so rows near α = 1e-4 are allowed more (the pdf of a sample is
//   that of its normal, as Mitsuba; the conductor recomputes it from wi, which the same bound
//   covers). Closer to the horizon a normal's rounding moves the pdf by ~δ/|cos| (the
//   visible-normal density has G1(wo)/cos θo, refraction's Jacobian a cancelling
//   (wo·m + η wi·m)² = |wo + η_r wi|², which vanishes as η → 1 for light passing straight
//   through): there only finiteness is required (the random cosines are log-uniform down to
//   1e-4, so such rows are many; the contract is checked on more than 1/3 of the samples);
// - a row whose sample misses the two bounds above must sit where the oracle itself is
//   ill-conditioned: there the SIMD may differ by as much as the oracle moves when the sines
//   and cosines it takes move by hwy's and libm's error bounds (OracleSpread). Such rows are
//   few (< 1 in 1000). Seen: GGX with αu = 1, αv = 100, wo.z = 0.038 (stretched cos θo 5e-4),
//   u_x = 0.99922 (the edge of the visible disk, where pz = √(1 − p1² − p2²) cancels): one ulp
//   of cos 2πu_y moves the oracle's wi by 7e-5, and there the non-FMA targets' hwy::Cos and
//   Sin (faithful, as libm's) are one ulp from libm's;
// - everything finite, f, pdf, weight ≥ 0.
struct Rows {
  std::vector<uint32_t> index;
  std::vector<float> wo[3], wl[3], u_lobe, u_x, u_y;
  std::vector<float> alpha_min;  // per row
  void Push(uint32_t row, float a_min, const Vec3f& o, const Vec3f& l, float ul, float ux,
            float uy) {
    index.push_back(row), alpha_min.push_back(a_min);
    wo[0].push_back(o.x), wo[1].push_back(o.y), wo[2].push_back(o.z);
    wl[0].push_back(l.x), wl[1].push_back(l.y), wl[2].push_back(l.z);
    u_lobe.push_back(ul), u_x.push_back(ux), u_y.push_back(uy);
  }
  size_t size() const { return index.size(); }
  ShadeInputs In() const {
    ShadeInputs in;
    in.wo = {wo[0].data(), wo[1].data(), wo[2].data()};
    in.wl = {wl[0].data(), wl[1].data(), wl[2].data()};
    in.u_lobe = u_lobe.data(), in.u_x = u_x.data(), in.u_y = u_y.data();
    return in;
  }
};

struct Bound {
  std::string what;
  size_t checked = 0, failures = 0;
  double worst = 0, worst_simd = 0, worst_oracle = 0;
  size_t worst_i = 0;
  void Check(size_t i, double simd, double oracle, double rel, double abs, double spread = 0) {
    ++checked;
    const double allowed = rel * std::fabs(oracle) + abs + spread;
    const double ratio = std::isfinite(simd) ? std::fabs(simd - oracle) / allowed : 1e30;
    if (ratio > 1) ++failures;
    if (ratio > worst) worst = ratio, worst_i = i, worst_simd = simd, worst_oracle = oracle;
  }
  void Report(const char* target, const Rows& r) const {
    std::printf("[%s] %-32s n=%zu max|Δ|/allowed=%.3g\n", target, what.c_str(), checked, worst);
    EXPECT_EQ(failures, 0u) << what << " worst at " << worst_i << " ratio " << worst << ": simd "
                            << worst_simd << " oracle " << worst_oracle << "; row "
                            << r.index[worst_i] << " α_min " << r.alpha_min[worst_i] << " wo ("
                            << r.wo[0][worst_i] << ", " << r.wo[1][worst_i] << ", "
                            << r.wo[2][worst_i] << ") u (" << r.u_lobe[worst_i] << ", "
                            << r.u_x[worst_i] << ", " << r.u_y[worst_i] << ")";
  }
};

struct Out {
  std::vector<float> v[12];
  explicit Out(size_t n) {
    for (auto& c : v) c.assign(n, -7.0f);
  }
  ShadeOutputs Outputs() {
    ShadeOutputs o;
    o.f = {v[0].data(), v[1].data(), v[2].data()};
    o.pdf_l = v[3].data();
    o.wi = {v[4].data(), v[5].data(), v[6].data()};
    o.weight = {v[7].data(), v[8].data(), v[9].data()};
    o.pdf = v[10].data();
    o.eta = v[11].data();
    return o;
  }
};

// The tables: the conductor in its Mitsuba form, the rough dielectric, the smooth conductor.
struct Fixture {
  MaterialTables m;
  std::vector<float> cond_amin, diel_amin, mirror_amin;
};

float AMin(float au, float av) {
  return std::min(ClampMicrofacetAlpha(au), ClampMicrofacetAlpha(av));
}

Fixture MakeFixture() {
  Fixture fx;
  Pcg32 rng(5, 11);
  const char* names[] = {"Au", "Ag", "Al", "Cu", "Fe", "Na", "Si", "none"};
  for (int i = 0; i < 96; ++i) {
    const float au = bsdf_test::RandomAlpha(rng);
    const float av = i % 3 == 0 ? au : (i % 3 == 1 ? bsdf_test::RandomAlpha(rng) : au * 100.0f);
    Color3f e, k;
    LookupConductorPreset(names[i % 8], &e, &k);
    fx.m.AddRoughConductor(au, av, uint8_t(i % 4), e, k,
                           {rng.NextFloat(), 1.0f, rng.NextFloat()});
    fx.cond_amin.push_back(AMin(au, av));
    const float eta = std::pow(10.0f, rng.NextFloat() - 0.5f);
    fx.m.AddRoughDielectric(au, av, uint8_t(i % 4), eta, 1.0f, {1, rng.NextFloat(), 1},
                            {rng.NextFloat(), 1, 1});
    fx.diel_amin.push_back(AMin(au, av));
    fx.m.AddSmoothConductor(e, k, {1, rng.NextFloat(), 1});
    fx.mirror_amin.push_back(1);
  }
  for (float a : bsdf_test::HardAlphas()) {
    for (uint8_t flags = 0; flags < 4; ++flags) {
      fx.m.AddRoughConductor(a, a * 100.0f, flags, {0.2f, 0.9f, 1.1f}, {3.9f, 2.4f, 2.1f},
                             {1, 1, 1});
      fx.cond_amin.push_back(AMin(a, a * 100.0f));
      for (float eta : bsdf_test::HardEtas()) {
        fx.m.AddRoughDielectric(a, a, flags, eta, 1.0f);
        fx.diel_amin.push_back(AMin(a, a));
      }
    }
  }
  fx.m.AddMirror();  // a plain row in the Fresnel-column form
  fx.mirror_amin.push_back(1);
  return fx;
}

Rows MakeRows(const std::vector<float>& amin, MaterialTag tag, size_t random_count) {
  Rows r;
  Pcg32 rng(21, 3 + int(tag));
  const uint32_t rows = uint32_t(amin.size());
  for (size_t i = 0; i < random_count; ++i) {
    const uint32_t row = std::min(rows - 1, uint32_t(rng.NextFloat() * rows));
    Vec3f wo = bsdf_test::RandomUpperDirection(rng);
    if (i % 4 == 0) wo.z = -wo.z;
    Vec3f wl = i % 2 ? bsdf_test::NearSpecularPartner(std::max(amin[row], 1e-3f), wo, rng)
                     : bsdf_test::RandomUpperDirection(rng);
    if (i % 6 == 1) wl.z = -wl.z;  // transmission pairs for the dielectric
    // Drawn in named steps: the order of a call's arguments is unspecified (GCC evaluates
    // them right to left, clang left to right), so draws inside the call gave each compiler
    // other rows.
    const float u_lobe = rng.NextFloat(), u_x = rng.NextFloat(), u_y = rng.NextFloat();
    r.Push(row, amin[row], wo, wl, u_lobe, u_x, u_y);
  }
  const std::vector<Vec3f> dirs = bsdf_test::HardDirections(false);
  const std::vector<float> us = bsdf_test::HardUs();
  for (uint32_t row = 0; row < rows; row += 5)
    for (size_t a = 0; a < dirs.size(); ++a)
      for (size_t j = 0; j < us.size(); j += 2)
        r.Push(row, amin[row], dirs[a], dirs[(a * 7 + j) % dirs.size()], us[(a + j) % us.size()],
               us[j], us[(j * 3 + a) % us.size()]);
  return r;
}

// Whether the oracle, with u_lobe moved by ±1e-4, gives the SIMD's validity (valid) and side
// of wi (wi_z): the row sits on the reflect/refract boundary u_lobe ≈ F.
bool NearLobeBoundary(const Fixture& fx, MaterialTag tag, const Rows& r, size_t i, bool valid,
                      float wi_z) {
  const MaterialRef ref = MaterialRef::Make(tag, r.index[i]);
  const Vec3f wo{r.wo[0][i], r.wo[1][i], r.wo[2][i]};
  for (float du : {-1e-4f, 1e-4f}) {
    BsdfSample s;
    const bool ok =
        BsdfSampleDirection(fx.m, ref, wo, r.u_lobe[i] + du, {r.u_x[i], r.u_y[i]}, &s);
    if (ok != valid) continue;
    if (!ok || (s.wi.z * wo.z > 0) == (wi_z * wo.z > 0)) return true;
  }
  return false;
}

bool Within(double simd, double oracle, double rel, double abs) {
  return std::fabs(simd - oracle) <= rel * std::fabs(oracle) + abs;
}

// How far the oracle's sample (wi, pdf, weight) moves when its point (cos 2πu_y, sin 2πu_y) of
// radius √u_x moves by δ = 4√2 · 2⁻²⁴ along or across the circle: hwy::Cos and Sin are within
// 3 ulp of the true value, libm's within 1, so their (cos, sin) pairs differ by at most 4 ulp
// each, δ in length (max(|cos|, |sin|) ≥ 1/√2, an ulp 2⁻²⁴ there). Across: u_x · (1 ± 2δ);
// along: u_y ± δ / 2π. Nudges that change the sample's validity or side are left out.
struct SampleSpread {
  double wi[3] = {}, pdf = 0, weight[3] = {};
};

SampleSpread OracleSpread(const Fixture& fx, MaterialTag tag, const Rows& r, size_t i,
                          const Out& o0) {
  SampleSpread s;
  const MaterialRef ref = MaterialRef::Make(tag, r.index[i]);
  const Vec3f wo{r.wo[0][i], r.wo[1][i], r.wo[2][i]};
  const float ux = r.u_x[i], uy = r.u_y[i];
  const float delta = 4.0f * std::sqrt(2.0f) * 0x1p-24f, along = delta / (2.0f * kPi);
  const Vec2f nudged[] = {{ux * (1.0f - 2.0f * delta), uy},
                          {ux * (1.0f + 2.0f * delta), uy},
                          {ux, uy - along},
                          {ux, uy + along}};
  for (const Vec2f& u : nudged) {
    BsdfSample b;
    if (!BsdfSampleDirection(fx.m, ref, wo, r.u_lobe[i], u, &b) || !(b.pdf > 0)) continue;
    if ((b.wi.z * wo.z > 0) != (o0.v[6][i] * wo.z > 0)) continue;
    const float wi[3] = {b.wi.x, b.wi.y, b.wi.z}, weight[3] = {b.weight.r, b.weight.g, b.weight.b};
    for (int c = 0; c < 3; ++c) {
      s.wi[c] = std::max(s.wi[c], std::fabs(double(wi[c]) - o0.v[4 + c][i]));
      s.weight[c] = std::max(s.weight[c], std::fabs(double(weight[c]) - o0.v[7 + c][i]));
    }
    s.pdf = std::max(s.pdf, std::fabs(double(b.pdf) - o0.v[10][i]));
  }
  return s;
}

void Compare(const Fixture& fx, MaterialTag tag, const Rows& r, const Out& o0, const Out& o1,
             const char* target) {
  const bool dielectric = tag == MaterialTag::kRoughDielectric;
  const std::string name = dielectric ? "rough dielectric"
                           : tag == MaterialTag::kMirror ? "smooth conductor"
                                                         : "rough conductor";
  Bound f{name + " f"}, pl{name + " pdf(wo,wl)"}, wi{name + " wi"}, pdf{name + " sample pdf"},
      w{name + " sample weight"};
  size_t mismatched = 0, valid = 0, conditioned = 0, ill_conditioned = 0;
  for (size_t i = 0; i < r.size(); ++i) {
    for (int c = 0; c < 12; ++c) ASSERT_TRUE(std::isfinite(o1.v[c][i])) << name << " " << i;
    for (int c : {0, 1, 2, 3, 7, 8, 9, 10}) ASSERT_GE(o1.v[c][i], 0.0f) << name << " " << i;
    for (int c = 0; c < 3; ++c) f.Check(i, o1.v[c][i], o0.v[c][i], 2e-5, 1e-30);
    pl.Check(i, o1.v[3][i], o0.v[3][i], 2e-5, 1e-30);
    const bool v0 = o0.v[10][i] > 0, v1 = o1.v[10][i] > 0;
    if (v0 != v1) {
      ++mismatched;
      const float z = v0 ? o0.v[6][i] : o1.v[6][i];
      bool boundary = std::fabs(z) <= 1e-4f;
      if (dielectric) boundary = boundary || NearLobeBoundary(fx, tag, r, i, v1, o1.v[6][i]);
      ASSERT_TRUE(boundary) << name << ": validity differs at " << i << " (wi.z " << z << ")";
      continue;
    }
    if (!v1) continue;
    ++valid;
    const bool side0 = o0.v[6][i] * r.wo[2][i] > 0, side1 = o1.v[6][i] * r.wo[2][i] > 0;
    if (side0 != side1) {  // the dielectric's lobe choice on its boundary u_lobe ≈ F
      ASSERT_TRUE(dielectric && NearLobeBoundary(fx, tag, r, i, true, o1.v[6][i]))
          << name << ": lobe differs at " << i;
      ++mismatched;
      continue;
    }
    EXPECT_EQ(o1.v[11][i], o0.v[11][i]) << name << " eta at " << i;
    // Grazing rows and near pass-through refraction: finiteness only (see the contract).
    bool graze = std::fabs(r.wo[2][i]) < 0.02f || std::fabs(o1.v[6][i]) < 0.02f;
    if (!graze && dielectric && o0.v[6][i] * r.wo[2][i] < 0) {
      const auto& t = fx.m.rough_dielectric;
      const float eta = t.int_ior[r.index[i]] / t.ext_ior[r.index[i]];
      const float eta_r = r.wo[2][i] > 0 ? eta : 1.0f / eta;
      const Vec3f sum{r.wo[0][i] + eta_r * o0.v[4][i], r.wo[1][i] + eta_r * o0.v[5][i],
                      r.wo[2][i] + eta_r * o0.v[6][i]};
      graze = !(Length(sum) >= 0.1f);
    }
    const double rel = 1e-4 + 4e-7 / (double(r.alpha_min[i]) * r.alpha_min[i]);
    const double pdf_rel = tag == MaterialTag::kMirror ? 2e-6 : rel;
    bool within = true;
    for (int c = 4; c < 7; ++c) within = within && Within(o1.v[c][i], o0.v[c][i], 0, 5e-5);
    if (!graze) {
      within = within && Within(o1.v[10][i], o0.v[10][i], pdf_rel, 1e-30);
      for (int c = 7; c < 10; ++c) within = within && Within(o1.v[c][i], o0.v[c][i], rel, 1e-20);
    }
    // Only where a bound is missed: the oracle's own spread under the trig functions' error.
    const SampleSpread sp = within ? SampleSpread{} : OracleSpread(fx, tag, r, i, o0);
    ill_conditioned += !within;
    for (int c = 4; c < 7; ++c) wi.Check(i, o1.v[c][i], o0.v[c][i], 0, 5e-5, sp.wi[c - 4]);
    if (graze) continue;
    ++conditioned;
    pdf.Check(i, o1.v[10][i], o0.v[10][i], pdf_rel, 1e-30, sp.pdf);
    for (int c = 7; c < 10; ++c) w.Check(i, o1.v[c][i], o0.v[c][i], rel, 1e-20, sp.weight[c - 7]);
  }
  for (const Bound* b : {&f, &pl, &wi, &pdf, &w}) b->Report(target, r);
  std::printf("[%s] %-32s %zu of %zu rows within the oracle's spread only\n", target, name.c_str(),
              ill_conditioned, r.size());
  EXPECT_LT(ill_conditioned, r.size() / 1000) << name;
  EXPECT_LT(mismatched, r.size() / 50) << name;
  EXPECT_GT(valid, r.size() / 5) << name;
  EXPECT_GT(conditioned, valid / 3) << name;
}

TEST(Microfacet8, ShadeBatchMatchesOracleOnEveryTarget) {
  const Fixture fx = MakeFixture();
  const struct {
    MaterialTag tag;
    const std::vector<float>* amin;
  } cases[] = {{MaterialTag::kConductor, &fx.cond_amin},
               {MaterialTag::kRoughDielectric, &fx.diel_amin},
               {MaterialTag::kMirror, &fx.mirror_amin}};
  for (const auto& c : cases) {
    const Rows r = MakeRows(*c.amin, c.tag, size_t(1) << 16);
    Out o0(r.size());
    ptlab::ShadeBatch(fx.m, c.tag, r.index.data(), r.size(), r.In(), o0.Outputs());
    test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
      Out o1(r.size());
      simd::ShadeBatch(fx.m, c.tag, r.index.data(), r.size(), r.In(), o1.Outputs());
      Compare(fx, c.tag, r, o0, o1, target);
    });
  }
}

// A batch mixing Beckmann and GGX rows, visible and plain sampling (simd::ShadeBatch groups its
// rows by those flags before the 8-wide blocks, ForEachBlockGrouped): every row's outputs are
// bit for bit those of the row shaded alone (a block of one key, no regrouping), on every target.
TEST(Microfacet8, RoughDielectricMixedBatchEqualsRowsAlone) {
  const Fixture fx = MakeFixture();
  const MaterialTag tag = MaterialTag::kRoughDielectric;
  // The random rows of MakeRows (its hard cases come after them, in order, unmixed).
  const Rows all = MakeRows(fx.diel_amin, tag, 4096);
  Rows r;
  for (size_t i = 0; i < 4096; ++i)
    r.Push(all.index[i], all.alpha_min[i], {all.wo[0][i], all.wo[1][i], all.wo[2][i]},
           {all.wl[0][i], all.wl[1][i], all.wl[2][i]}, all.u_lobe[i], all.u_x[i], all.u_y[i]);
  size_t ggx = 0;
  for (const uint32_t row : r.index) ggx += fx.m.rough_dielectric.flags[row] & kMicrofacetGgx;
  ASSERT_GT(ggx, r.size() / 4);  // the batch mixes the distributions
  ASSERT_LT(ggx, r.size() * 3 / 4);
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
    Out batch(r.size());
    simd::ShadeBatch(fx.m, tag, r.index.data(), r.size(), r.In(), batch.Outputs());
    size_t differ = 0;
    for (size_t i = 0; i < r.size(); ++i) {
      Rows one;
      one.Push(r.index[i], r.alpha_min[i], {r.wo[0][i], r.wo[1][i], r.wo[2][i]},
               {r.wl[0][i], r.wl[1][i], r.wl[2][i]}, r.u_lobe[i], r.u_x[i], r.u_y[i]);
      Out alone(1);
      simd::ShadeBatch(fx.m, tag, one.index.data(), 1, one.In(), alone.Outputs());
      for (int c = 0; c < 12; ++c)
        differ += std::memcmp(&alone.v[c][0], &batch.v[c][i], sizeof(float)) != 0;
    }
    EXPECT_EQ(differ, 0u) << target;
  });
}

}  // namespace
}  // namespace ptlab
