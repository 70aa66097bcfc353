// The SIMD twin of Mitsuba's `roughplastic` (simd/wavefront/plastic_rough8-inl.h, the plastic
// tag's rough rows) against its scalar oracle (engine/bsdf/plastic_rough.h through
// ptlab::ShadeBatch), on random and hard-case inputs, on every compiled Highway target.
#include "simd/targets.h"  // first: the target policy (must precede every hwy/ include)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/microfacet.h"
#include "engine/bsdf/plastic_precompute.h"
#include "engine/core/rng.h"
#include "engine/wavefront/bsdf.h"
#include "simd/dispatched_target.h"
#include "simd/wavefront/bsdf8.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"
#include "tests/simd/for_each_target.h"

namespace ptlab {
namespace {

// The contract the test holds each target to (per row; the oracle's value is o):
// - f(wo, wl), pdf(wo, wl): GGX rows |Δ| ≤ 4 ulp of o (+1e-37 absolute): the same IEEE
//   operations in the same order (the transmittance table's interpolation, 1/|wo + wi|, G1/cos,
//   the dielectric Fresnel, the lobe mixture); no transcendental enters. Beckmann rows
//   |Δ| ≤ 2e-5 |o| + 1e-30: hwy's Exp in D and Exp/erf in G1 differ from libm by an ulp, which
//   the exponent −tan²θ/α² amplifies by up to its magnitude (≤ ~100 where D > 1e-20).
// - validity of the sample (pdf > 0) equal, except where the oracle's or the SIMD's wi.z is
//   within 2e-3 of the horizon (as Shade8's contract for cosine samples: z = √(1 − x² − y²)
//   turns an ulp of x² + y² at the disk's rim into z ≈ 2.4e-4, and a z ≤ 0 on one side only). The lobe choice
//   u_lobe < P(specular) is exact (P(specular) is bit-identical), so the delta flag (0) and eta
//   (1) are equal everywhere.
// - the sampled wi: |Δ| ≤ 5e-5 per component: the cosine lobe's Sin/Cos are ≤ 3 ulp; the
//   visible-normal sampler adds Log/Exp/Sin/Cos and the Beckmann slope's 3 Newton steps,
//   whose erf⁻¹ is steep as u → 1 (the bound of microfacet8_test.cpp, whose sampler this is);
//   wi.z, where it differs by more, |Δ(z²)| ≤ 2e-4 (the rim's cancellation above: z² moves
//   by 2|x|Δx + 2|y|Δy). Where the sampler itself is ill-conditioned the bound adds 4 × the
//   oracle's own change of wi under a one-ulp change of u_x or u_y (OracleWiSensitivity): the
//   visible-normal sampler's z = √(1 − p1² − p2²) cancels as u_x → 1, and at α = 1e-4 with
//   grazing wo the un-stretched normal's tilt is a quotient of two such small terms (seen:
//   |Δwi| 1.5e-3 at cos θo = 2.4e-4, u_x = 0.99998 on the FMA targets, where hwy's Sin/Cos
//   round differently; the oracle moves by as much under one ulp of u).
// - where cos θo and cos θi ≥ 0.02, the sample's pdf and weight: |Δ| ≤ (1e-4 + 4e-7/α²) |o|
//   + 1e-30: wi differs by δ ≈ 2e-7 (above), which moves the half vector and so D by
//   ~2 δ tanθ/α² relatively (tanθ ≈ α at the lobe), and the pdf and weight mix D in; nearer
//   the horizon G1(wo)/cos θo amplifies δ by 1/cos: only finiteness is required there. A
//   weight channel is held to that bound relative to the row's largest channel: as η → 1 the
//   coating's Fresnel term ((η − 1)/2)² comes from c − √(η² − 1 + c²), which cancels, so a
//   channel that carries only the specular lobe (zero diffuse base) moves by δ c²/(η² − 1)
//   relatively (seen 9 % at η = 1 + 1e-6 on a channel of 5e-13).
// - everything finite, f, pdf, weight ≥ 0.
struct Rows {
  std::vector<uint32_t> index;
  std::vector<float> wo[3], wl[3], u_lobe, u_x, u_y;
  void Push(uint32_t row, const Vec3f& o, const Vec3f& l, float ul, float ux, float uy) {
    index.push_back(row);
    wo[0].push_back(o.x), wo[1].push_back(o.y), wo[2].push_back(o.z);
    wl[0].push_back(l.x), wl[1].push_back(l.y), wl[2].push_back(l.z);
    u_lobe.push_back(ul), u_x.push_back(ux), u_y.push_back(uy);
  }
  void PushRow(const Rows& r, size_t i) {
    Push(r.index[i], {r.wo[0][i], r.wo[1][i], r.wo[2][i]}, {r.wl[0][i], r.wl[1][i], r.wl[2][i]},
         r.u_lobe[i], r.u_x[i], r.u_y[i]);
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

struct Out {
  std::vector<float> v[13];  // f rgb, pdf_l, wi xyz, weight rgb, pdf, eta, delta
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
    o.delta = v[12].data();
    return o;
  }
};

struct Bound {
  std::string what;
  size_t checked = 0, failures = 0;
  double worst = 0, worst_simd = 0, worst_oracle = 0;
  size_t worst_i = 0;
  void Check(size_t i, double simd, double oracle, double rel, double abs) {
    ++checked;
    const double allowed = rel * std::fabs(oracle) + abs;
    const double ratio = std::isfinite(simd) ? std::fabs(simd - oracle) / allowed : 1e30;
    if (ratio > 1) ++failures;
    if (ratio > worst) worst = ratio, worst_i = i, worst_simd = simd, worst_oracle = oracle;
  }
  // |Δ| ≤ ulps ulp of the oracle's float value (plus a tiny absolute floor).
  void CheckUlp(size_t i, float simd, float oracle, int ulps) {
    const float ulp = std::nextafter(std::fabs(oracle), 3e38f) - std::fabs(oracle);
    Check(i, simd, oracle, 0, double(ulps) * ulp + 1e-37);
  }
  void Report(const char* target, const Rows& r) const {
    std::printf("[%s] %-34s n=%zu max|Δ|/allowed=%.3g\n", target, what.c_str(), checked, worst);
    EXPECT_EQ(failures, 0u) << what << " worst at " << worst_i << " ratio " << worst << ": simd "
                            << worst_simd << " oracle " << worst_oracle << "; row "
                            << r.index[worst_i] << " wo (" << r.wo[0][worst_i] << ", "
                            << r.wo[1][worst_i] << ", " << r.wo[2][worst_i] << ") u ("
                            << r.u_lobe[worst_i] << ", " << r.u_x[worst_i] << ", "
                            << r.u_y[worst_i] << ")";
  }
};

// Rough rows over the hard roughnesses, distributions, η (η → 1, η < 1 whose coating reflects
// almost all light back inside, so that R_int → 1 and the base's internal-scattering quotient
// is large, huge and tiny η) and both internal-scattering models; then random rows; then smooth
// rows (only for the mixed batch).
struct Fixture {
  MaterialTables m;
  std::vector<float> alpha;  // clamped, per plastic row
  uint32_t rough_rows = 0;
};

Fixture MakeFixtureOnce() {
  Fixture fx;
  Pcg32 rng(7, 39);
  int k = 0;
  const auto add = [&](const PlasticDesc& d) {
    fx.m.AddPlastic(*MakePlasticRow(d));
    fx.alpha.push_back(ClampMicrofacetAlpha(d.alpha));
  };
  for (float a : {1e-4f, 0.05f, 1.0f}) {
    for (CoatingDistribution dist : {CoatingDistribution::kBeckmann, CoatingDistribution::kGgx}) {
      for (float eta : {1.0f, 1.0f + 1e-6f, 1.5f, 1.0f / 1.5f, 0.05f, 20.0f}) {
        PlasticDesc d;
        d.distribution = dist, d.alpha = a, d.int_ior = eta, d.ext_ior = 1.0f;
        d.nonlinear = (k++ % 2) == 0;
        d.diffuse = {0.9f, 0.5f, k % 3 == 0 ? 0.0f : 0.2f};
        d.specular = {1.0f, 0.7f, k % 5 == 0 ? 0.0f : 1.0f};
        add(d);
      }
    }
  }
  for (int i = 0; i < 16; ++i) {
    PlasticDesc d;
    d.distribution = i % 2 ? CoatingDistribution::kGgx : CoatingDistribution::kBeckmann;
    d.alpha = bsdf_test::RandomAlpha(rng);
    d.int_ior = 1.0f + rng.NextFloat(), d.ext_ior = 1.0f + 0.2f * rng.NextFloat();
    d.nonlinear = i % 4 < 2;
    d.diffuse = {rng.NextFloat(), rng.NextFloat(), rng.NextFloat()};
    d.specular = {rng.NextFloat(), 1.0f, rng.NextFloat()};
    add(d);
  }
  fx.rough_rows = uint32_t(fx.m.plastic.size());
  for (int i = 0; i < 16; ++i) {  // smooth rows
    PlasticDesc d;
    d.int_ior = 1.0f + rng.NextFloat(), d.ext_ior = 1.0f, d.nonlinear = i % 2 == 0;
    d.diffuse = {rng.NextFloat(), rng.NextFloat(), rng.NextFloat()};
    add(d);
  }
  return fx;
}

// The rows' precomputation (T(μ), R_int by quadrature) takes ~0.1 s each: built once.
const Fixture& MakeFixture() {
  static const Fixture* fx = new Fixture(MakeFixtureOnce());
  return *fx;
}

Rows MakeRows(const Fixture& fx, uint32_t rows, size_t random_count) {
  Rows r;
  Pcg32 rng(21, 39);
  for (size_t i = 0; i < random_count; ++i) {
    const uint32_t row = std::min(rows - 1, uint32_t(rng.NextFloat() * rows));
    Vec3f wo = bsdf_test::RandomUpperDirection(rng);
    if (i % 8 == 0) wo.z = -wo.z;
    Vec3f wl = i % 2 ? bsdf_test::NearSpecularPartner(std::max(fx.alpha[row], 1e-3f), wo, rng)
                     : bsdf_test::RandomUpperDirection(rng);
    if (i % 12 == 1) wl.z = -wl.z;
    // Named draws: a call's arguments are evaluated in an unspecified order (GCC right to
    // left, clang left to right), which gave each compiler other rows.
    const float u_lobe = rng.NextFloat(), u_x = rng.NextFloat(), u_y = rng.NextFloat();
    r.Push(row, wo, wl, u_lobe, u_x, u_y);
  }
  const std::vector<Vec3f> dirs = bsdf_test::HardDirections(false);
  const std::vector<float> us = bsdf_test::HardUs();
  for (uint32_t row = 0; row < rows; row += 3)
    for (size_t a = 0; a < dirs.size(); ++a)
      for (size_t j = 0; j < us.size(); j += 2)
        r.Push(row, dirs[a], dirs[(a * 7 + j) % dirs.size()], us[(a + j) % us.size()], us[j],
               us[(j * 3 + a) % us.size()]);
  return r;
}

// The largest change of the oracle's sampled wi (component-wise) when u_x or u_y moves by one
// ulp: the sampler's own sensitivity to a rounding of its sample coordinates, through which a
// transcendental's ulp reaches wi.
double OracleWiSensitivity(const Fixture& fx, const Rows& r, size_t i, const Out& o0) {
  const MaterialRef ref = MaterialRef::Make(MaterialTag::kPlastic, r.index[i]);
  const Vec3f wo{r.wo[0][i], r.wo[1][i], r.wo[2][i]};
  double worst = 0;
  for (int k = 0; k < 4; ++k) {
    float ux = r.u_x[i], uy = r.u_y[i];
    float& u = k < 2 ? ux : uy;
    u = std::nextafter(u, k % 2 ? 2.0f : -1.0f);
    BsdfSample s;
    if (!BsdfSampleDirection(fx.m, ref, wo, r.u_lobe[i], {ux, uy}, &s)) continue;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(double(s.wi[c]) - o0.v[4 + c][i]));
  }
  return worst;
}

void Compare(const Fixture& fx, const Rows& r, const Out& o0, const Out& o1,
             const char* target) {
  Bound f_ggx{"GGX f"}, pl_ggx{"GGX pdf(wo,wl)"}, f_beck{"Beckmann f"},
      pl_beck{"Beckmann pdf(wo,wl)"}, wi{"sample wi.xy"}, wi_z{"sample wi.z² (|Δz| > 5e-5)"}, pdf{"sample pdf"}, w{"sample weight"};
  size_t mismatched = 0, valid = 0, conditioned = 0, ill_conditioned = 0;
  for (size_t i = 0; i < r.size(); ++i) {
    for (int c = 0; c < 13; ++c) ASSERT_TRUE(std::isfinite(o1.v[c][i])) << c << " at " << i;
    for (int c : {0, 1, 2, 3, 7, 8, 9, 10}) ASSERT_GE(o1.v[c][i], 0.0f) << c << " at " << i;
    const bool ggx = fx.m.plastic.distribution[r.index[i]] == uint8_t(CoatingDistribution::kGgx);
    for (int c = 0; c < 4; ++c) {
      if (ggx) {
        (c < 3 ? f_ggx : pl_ggx).CheckUlp(i, o1.v[c][i], o0.v[c][i], 4);
      } else {
        (c < 3 ? f_beck : pl_beck).Check(i, o1.v[c][i], o0.v[c][i], 2e-5, 1e-30);
      }
    }
    ASSERT_EQ(o1.v[11][i], o0.v[11][i]) << "eta at " << i;
    ASSERT_EQ(o1.v[12][i], 0.0f) << "delta at " << i;
    ASSERT_EQ(o0.v[12][i], 0.0f) << "delta at " << i;
    const bool v0 = o0.v[10][i] > 0, v1 = o1.v[10][i] > 0;
    if (v0 != v1) {
      ++mismatched;
      const float z = v0 ? o0.v[6][i] : o1.v[6][i];
      ASSERT_LE(std::fabs(z), 2e-3f)
          << "validity differs at " << i << ": row " << r.index[i] << " wo (" << r.wo[0][i]
          << ", " << r.wo[1][i] << ", " << r.wo[2][i] << ") u (" << r.u_lobe[i] << ", "
          << r.u_x[i] << ", " << r.u_y[i] << ") oracle pdf " << o0.v[10][i] << " wi ("
          << o0.v[4][i] << ", " << o0.v[5][i] << ", " << o0.v[6][i] << "), simd pdf "
          << o1.v[10][i] << " wi (" << o1.v[4][i] << ", " << o1.v[5][i] << ", " << o1.v[6][i]
          << ")";
      continue;
    }
    if (!v1) continue;
    ++valid;
    double dwi = 0;
    for (int c = 4; c < 7; ++c) dwi = std::max(dwi, std::fabs(double(o1.v[c][i]) - o0.v[c][i]));
    // An ill-conditioned sample (see the contract): the bound grows with the oracle's own
    // sensitivity, computed only for the rows that need it.
    const double cond = dwi > 5e-5 ? 4 * OracleWiSensitivity(fx, r, i, o0) : 0.0;
    ill_conditioned += cond > 0;
    for (int c = 4; c < 6; ++c) wi.Check(i, o1.v[c][i], o0.v[c][i], 0, 5e-5 + cond);
    const double z0 = o0.v[6][i], z1 = o1.v[6][i];
    if (std::fabs(z1 - z0) > 5e-5 + cond) wi_z.Check(i, z1 * z1, z0 * z0, 0, 2e-4);
    if (r.wo[2][i] < 0.02f || o1.v[6][i] < 0.02f) continue;  // near the horizon: finite only
    ++conditioned;
    const double a = fx.alpha[r.index[i]];
    const double rel = 1e-4 + 4e-7 / (a * a);
    pdf.Check(i, o1.v[10][i], o0.v[10][i], rel, 1e-30);
    const double w_max = std::max({o0.v[7][i], o0.v[8][i], o0.v[9][i]});
    for (int c = 7; c < 10; ++c) w.Check(i, o1.v[c][i], o0.v[c][i], rel, rel * w_max + 1e-30);
  }
  for (const Bound* b : {&f_ggx, &pl_ggx, &f_beck, &pl_beck, &wi, &wi_z, &pdf, &w}) b->Report(target, r);
  std::printf("[%s] %zu valid samples, %zu with |Δwi| > 5e-5 (bound widened by the oracle's "
              "sensitivity), %zu validity mismatches on the horizon\n",
              target, valid, ill_conditioned, mismatched);
  // The widening stays the exception (seen 0.3 %: most are wi.z at the rim, above).
  EXPECT_LT(ill_conditioned, valid / 100);
  // Each mismatch sits on the horizon (checked above); the hard cases put many rows there
  // (u = 0 or 1 − 2⁻²⁴ lands on the rim of the concentric disk), as in Shade8's contract.
  EXPECT_LT(mismatched, r.size() / 50);
  EXPECT_GT(valid, r.size() / 4);
  EXPECT_GT(conditioned, valid / 3);
}

TEST(PlasticRough8, ShadeBatchMatchesOracleOnEveryTarget) {
  const Fixture& fx = MakeFixture();
  const Rows r = MakeRows(fx, fx.rough_rows, size_t(1) << 16);
  Out o0(r.size());
  ptlab::ShadeBatch(fx.m, MaterialTag::kPlastic, r.index.data(), r.size(), r.In(),
                    o0.Outputs());
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
    Out o1(r.size());
    simd::ShadeBatch(fx.m, MaterialTag::kPlastic, r.index.data(), r.size(), r.In(),
                     o1.Outputs());
    Compare(fx, r, o0, o1, target);
  });
}

// A batch mixing smooth, Beckmann and GGX rows (ShadePlasticRows groups them by distribution,
// ForEachBlockGrouped, and a block that still mixes them runs both kernels and merges lanes):
// every row's outputs are bit for bit those of the row shaded alone, on every target.
TEST(PlasticRough8, MixedBatchEqualsRowsAlone) {
  const Fixture& fx = MakeFixture();
  const Rows all = MakeRows(fx, uint32_t(fx.m.plastic.size()), 4096);
  Rows r;
  for (size_t i = 0; i < 4096; ++i) r.PushRow(all, i);
  size_t smooth = 0;
  for (const uint32_t row : r.index) smooth += row >= fx.rough_rows;
  ASSERT_GT(smooth, r.size() / 20);  // the batch mixes smooth and rough rows
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
    Out batch(r.size());
    simd::ShadeBatch(fx.m, MaterialTag::kPlastic, r.index.data(), r.size(), r.In(),
                     batch.Outputs());
    size_t differ = 0;
    for (size_t i = 0; i < r.size(); ++i) {
      Rows one;
      one.PushRow(r, i);
      Out alone(1);
      simd::ShadeBatch(fx.m, MaterialTag::kPlastic, one.index.data(), 1, one.In(),
                       alone.Outputs());
      for (int c = 0; c < 13; ++c)
        differ += std::memcmp(&alone.v[c][0], &batch.v[c][i], sizeof(float)) != 0;
    }
    EXPECT_EQ(differ, 0u) << target;
  });
}

// kern: a plastic table whose rows all have one coating (smooth, Beckmann or GGX) and is no
// longer than the batch skips the grouping (and, rough, the per-block coating gathers:
// ShadePlasticRows' one-coating path); the same rows in a table that also holds the other
// coatings go through the general path. Every row's outputs must be the same bits, on every target.
TEST(PlasticRough8, OneCoatingTableEqualsMixedTable) {
  const Fixture& fx = MakeFixture();
  const PlasticTable& all = fx.m.plastic;
  for (CoatingDistribution dist : {CoatingDistribution::kSmooth, CoatingDistribution::kBeckmann,
                                   CoatingDistribution::kGgx}) {
    MaterialTables one, mixed;  // mixed: the same rows first, then every other row
    std::vector<float> alpha;
    for (size_t k = 0; k < all.size(); ++k) {
      if (all.Row(k).distribution != dist) continue;
      one.AddPlastic(all.Row(k)), mixed.AddPlastic(all.Row(k));
      alpha.push_back(fx.alpha[k]);
    }
    const uint32_t rows = uint32_t(one.plastic.size());
    ASSERT_GT(rows, 8u);
    for (size_t k = 0; k < all.size(); ++k)
      if (all.Row(k).distribution != dist) mixed.AddPlastic(all.Row(k));
    Fixture sub;
    sub.alpha = alpha;
    const Rows r = MakeRows(sub, rows, 2000);
    ASSERT_GE(r.size(), one.plastic.size());  // the one-coating path's condition
    test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
      Out a(r.size()), b(r.size());
      simd::ShadeBatch(one, MaterialTag::kPlastic, r.index.data(), r.size(), r.In(), a.Outputs());
      simd::ShadeBatch(mixed, MaterialTag::kPlastic, r.index.data(), r.size(), r.In(),
                       b.Outputs());
      size_t differ = 0;
      for (int c = 0; c < 13; ++c)
        differ += std::memcmp(a.v[c].data(), b.v[c].data(), r.size() * sizeof(float)) != 0;
      EXPECT_EQ(differ, 0u) << target << " coating " << int(dist);
    });
  }
}

}  // namespace
}  // namespace ptlab
