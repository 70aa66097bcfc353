// The SIMD twin of Mitsuba's principled BSDF (simd/wavefront/principled8-inl.h) against its
// scalar oracle (ptlab::ShadeBatch → engine/bsdf/principled.h), on random and hard-case inputs
// and textured parameters, on every compiled Highway target.
#include "simd/targets.h"  // first: the target policy (must precede every hwy/ include)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/principled.h"
#include "engine/bsdf/principled_thin.h"
#include "engine/core/rng.h"
#include "engine/wavefront/bsdf.h"
#include "simd/dispatched_target.h"
#include "simd/wavefront/bsdf8.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"
#include "tests/simd/for_each_target.h"

namespace ptlab {
namespace {

// The contract each target is held to (per row; the oracle's value is o):
// - f(wo, wl), pdf(wo, wl): |Δ| ≤ 2e-5 |o| + 1e-30 (the oracle's operations in its order; only
//   hwy's Log in the clearcoat's GTR1 D differs, by an ulp of log α²);
// - validity of the sample (pdf > 0) and its lobe equal, except on a decision boundary: |wi.z|
//   ≤ 1e-4 (2e-3 where (u_x, u_y) is on the rim of the concentric disk, whose cosine warp
//   cancels: see OnDiskRim), or the oracle with u_lobe moved by ±1e-4 gives the SIMD's sample (the lobe
//   probabilities depend on F(wo·m) of the sampled normal, which hwy's Sin/Cos move);
// - the sample is one of the oracle's model: its pdf and weight are within 2e-5 relative of
//   the oracle's BsdfEvalPdf at the SIMD's wi (f |cos θi| / pdf), on every valid sample;
// - the sampled wi: |Δ| ≤ 5e-5 per component, plus 4e-7/(1 − u_x) + 1e-7/(1 − u_y) where the
//   samplers cancel (see WiBound) (hwy's Sin/Cos in the GGX visible-normal, cosine
//   and GTR1 samplers, Exp·Log for GTR1's std::pow; on the disk's rim wi.z² within 4e-6);
//   eta equal;
// - where |cos θo| and |cos θi| ≥ 0.02 and (refraction) |wo + η_r wi| ≥ 0.1, the sample's pdf
//   and weight: |Δ| ≤ (1e-4 + 4e-7 / α²_min) |o| + 1e-30, α_min the smallest roughness of the
//   row's lobes (GGX αu, αv; GTR1's α where the clearcoat is on), as in microfacet8_test.cpp: a
//   δ ≈ 2e-7 tilt of a normal changes D by ~2 δ tanθ/α² relatively; closer to the horizon or
//   to light passing straight through, finiteness only;
// - everything finite, f, pdf, weight ≥ 0.
struct Rows {
  std::vector<uint32_t> index, entry;
  std::vector<float> wo[3], wl[3], u_lobe, u_x, u_y;
  void Push(uint32_t row, const Vec3f& o, const Vec3f& l, float ul, float ux, float uy) {
    index.push_back(row), entry.push_back(uint32_t(entry.size()));
    wo[0].push_back(o.x), wo[1].push_back(o.y), wo[2].push_back(o.z);
    wl[0].push_back(l.x), wl[1].push_back(l.y), wl[2].push_back(l.z);
    u_lobe.push_back(ul), u_x.push_back(ux), u_y.push_back(uy);
  }
  size_t size() const { return index.size(); }
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
  void Report(const char* target, const Rows& r) const {
    std::printf("[%s] %-32s n=%zu max|Δ|/allowed=%.3g\n", target, what.c_str(), checked, worst);
    EXPECT_EQ(failures, 0u) << what << " worst at " << worst_i << " ratio " << worst << ": simd "
                            << worst_simd << " oracle " << worst_oracle << "; row "
                            << r.index[worst_i] << " wo (" << r.wo[0][worst_i] << ", "
                            << r.wo[1][worst_i] << ", " << r.wo[2][worst_i] << ") u ("
                            << r.u_lobe[worst_i] << ", " << r.u_x[worst_i] << ", "
                            << r.u_y[worst_i] << ")";
  }
};

struct Out {
  std::vector<float> v[12];
  explicit Out(size_t n) {
    for (auto& c : v) c.assign(n, -7.0f);  // poison: every output must be written
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

struct Fixture {
  MaterialTag tag = MaterialTag::kPrincipled;  // or kPrincipledThin: the rows are in both
  Scene scene;  // only its textures
  MaterialTables m;
  const PrincipledTable& table() const {
    return tag == MaterialTag::kPrincipled ? m.principled : m.principled_thin;
  }
  void Add(const PrincipledRow& row) { m.AddPrincipled(row), m.AddPrincipled(row, true); }
  std::vector<SurfaceInteraction> its;
  Rows rows;
  ShadeInputs In() const {
    ShadeInputs in;
    in.wo = {rows.wo[0].data(), rows.wo[1].data(), rows.wo[2].data()};
    in.wl = {rows.wl[0].data(), rows.wl[1].data(), rows.wl[2].data()};
    in.u_lobe = rows.u_lobe.data(), in.u_x = rows.u_x.data(), in.u_y = rows.u_y.data();
    in.texture = {&scene.textures, its.data(), rows.entry.data()};
    return in;
  }
};

// Random rows (some parameters at exactly 0 or 1), one row per hard combination (roughness → 0
// and 1, metallic and specular transmission 0/1, η = 1, 1 + 1e-6, 1.5, 1/1.5, the clamps'
// ends), and rows whose parameters are textures (values outside [0, 1] included: clamped).
void AddRows(Fixture* fx) {
  Pcg32 rng(17, 3);
  TextureTable& t = fx->scene.textures;
  const uint32_t bitmap = t.AddRow(TextureKind::kBitmap, 5, 3, 45);
  for (int k = 0; k < 45; ++k) t.data[t.offset[bitmap] + k] = rng.NextFloat();
  const uint32_t checker = t.AddRow(TextureKind::kCheckerboard, 1, 1, 6);
  for (int k = 0; k < 6; ++k) t.data[t.offset[checker] + k] = k < 3 ? 0.0f : 1.0f;
  const uint32_t face = t.AddRow(TextureKind::kFaceAttribute, 3, 4, 12);
  for (int k = 0; k < 12; ++k) t.data[t.offset[face] + k] = 3.0f * rng.NextFloat() - 1.0f;
  const auto unit = [&](int i, int k) {
    const int s = (i + k) % 7;
    return s == 0 ? 0.0f : s == 1 ? 1.0f : rng.NextFloat();
  };
  for (int i = 0; i < 96; ++i) {
    PrincipledRow row;
    row.base_color = {rng.NextFloat(), rng.NextFloat(), i % 9 == 0 ? 0.0f : rng.NextFloat()};
    for (int k = 0; k < kPrincipledDiffTrans; ++k) row.value[k] = unit(i, k);
    row.value[kPrincipledDiffTrans] = 2.0f * unit(i, kPrincipledDiffTrans);
    const float eta = 1.0f + 1.5f * rng.NextFloat();
    row.value[kPrincipledEta] = i % 5 == 0 ? 1.0f / eta : eta;
    fx->Add(row);
  }
  const float etas[] = {1.0f, 1.0f + 1e-6f, 1.5f, 1.0f / 1.5f, 1e-30f, 1e30f};
  for (float roughness : {0.0f, 1e-3f, 0.05f, 0.5f, 1.0f})
    for (float metallic : {0.0f, 1.0f})
      for (float spec_trans : {0.0f, 1.0f})
        for (float eta : etas) {
          PrincipledRow row;
          row.base_color = {0.9f, 0.5f, 0.1f};
          row.value[kPrincipledRoughness] = roughness;
          row.value[kPrincipledAnisotropic] = roughness == 0.5f ? 1.0f : 0.0f;
          row.value[kPrincipledMetallic] = metallic;
          row.value[kPrincipledSpecTrans] = spec_trans;
          row.value[kPrincipledSpecTint] = 0.5f;
          row.value[kPrincipledSheen] = 1.0f, row.value[kPrincipledSheenTint] = 0.5f;
          row.value[kPrincipledClearcoat] = eta == 1.5f ? 0.0f : 1.0f;
          row.value[kPrincipledClearcoatGloss] = roughness;
          row.value[kPrincipledFlatness] = spec_trans;
          row.value[kPrincipledEta] = eta;
          row.value[kPrincipledDiffTrans] = 2.0f * metallic;  // principledthin's
          fx->Add(row);
        }
  for (int i = 0; i < 12; ++i) {
    PrincipledRow row;
    row.base_color_texture = i % 2 ? bitmap : face;
    row.texture[kPrincipledRoughness] = i % 3 == 0 ? checker : face;
    row.texture[kPrincipledMetallic] = i % 4 == 1 ? bitmap : kNoTexture;
    row.texture[kPrincipledSpecTrans] = i % 4 == 2 ? checker : face;
    row.texture[kPrincipledClearcoat] = bitmap;
    row.texture[kPrincipledSheen] = i % 2 ? kNoTexture : face;
    row.texture[kPrincipledAnisotropic] = i % 3 == 1 ? bitmap : kNoTexture;
    row.texture[kPrincipledDiffTrans] = i % 2 ? face : kNoTexture;
    row.value[kPrincipledEta] = 1.0f + 0.1f * float(i);
    fx->Add(row);
  }
}

void AddInputs(Fixture* fx, size_t random_count) {
  Pcg32 rng(23, 9);
  const uint32_t rows = uint32_t(fx->table().size());
  for (size_t i = 0; i < random_count; ++i) {
    const uint32_t row = std::min(rows - 1, uint32_t(rng.NextFloat() * rows));
    Vec3f wo = bsdf_test::RandomUpperDirection(rng);
    if (i % 4 == 0) wo.z = -wo.z;
    Vec3f wl = i % 2 ? bsdf_test::NearSpecularPartner(bsdf_test::RandomAlpha(rng), wo, rng)
                     : bsdf_test::RandomUpperDirection(rng);
    if (i % 6 == 1) wl.z = -wl.z;  // transmission pairs
    // Named draws: a call's arguments are evaluated in an unspecified order (GCC right to
    // left, clang left to right), which gave each compiler other rows.
    const float u_lobe = rng.NextFloat(), u_x = rng.NextFloat(), u_y = rng.NextFloat();
    fx->rows.Push(row, wo, wl, u_lobe, u_x, u_y);
  }
  const std::vector<Vec3f> dirs = bsdf_test::HardDirections(false);
  const std::vector<float> us = bsdf_test::HardUs();
  for (uint32_t row = 0; row < rows; row += 3)
    for (size_t a = 0; a < dirs.size(); ++a)
      for (size_t j = 0; j < us.size(); j += 2)
        fx->rows.Push(row, dirs[a], dirs[(a * 7 + j) % dirs.size()], us[(a + j) % us.size()],
                      us[j], us[(j * 3 + a) % us.size()]);
  // One shading point per input row (uv, p, primitive for the textures).
  fx->its.resize(fx->rows.size());
  for (SurfaceInteraction& s : fx->its) {
    s.uv = {3.0f * rng.NextFloat() - 1.0f, 3.0f * rng.NextFloat() - 1.0f};
    s.p = {rng.NextFloat(), rng.NextFloat(), rng.NextFloat()};
    s.prim = uint32_t(rng.NextFloat() * 10.0f);
  }
}

// The smallest roughness of row i's lobes at its shading point.
float AlphaMin(const Fixture& fx, size_t i) {
  const PrincipledParams p =
      PrincipledAt(fx.table(), fx.rows.index[i], RowTextureSite(fx.In().texture, i));
  const Microfacet d = principled_internal::PrincipledDistribution(p.roughness, p.anisotropic);
  float a = std::min(d.alpha_u, d.alpha_v);
  if (fx.tag == MaterialTag::kPrincipledThin) {
    const Microfacet t = principled_internal::ThinTransmissionDistribution(p);
    return std::min(a, std::min(t.alpha_u, t.alpha_v));
  }
  if (p.clearcoat > 0) a = std::min(a, principled_internal::ClearcoatAlpha(p.clearcoat_gloss));
  return a;
}

// Whether (u_x, u_y) maps to the rim of the concentric disk (a cosine-hemisphere sample there
// has z = √(1 − x² − y²) of a cancelling difference: hwy's Sin/Cos move it by up to ~2e-3).
bool OnDiskRim(const Rows& r, size_t i) {
  return std::max(std::fabs(2.0f * r.u_x[i] - 1.0f), std::fabs(2.0f * r.u_y[i] - 1.0f)) >
         1.0f - 1e-6f;
}

// The bound on |Δwi| per component: 5e-5, plus what the samplers' cancellations amplify.
// GGX visible normals: the disk radius √u_x → 1 leaves the stretched normal z = √(1 − p1² −
// p2²) of a cancelling difference, so hwy's Sin/Cos error ε ≈ 4e-7 becomes a relative error
// ε/(1 − u_x) of z and tilts the normal by at most half that (the tilt's derivative w.r.t. ln z
// is sin θ cos θ ≤ 1/2), wi twice the normal: 4e-7/(1 − u_x) (seen: 1.5e-4 at 1 − u_x =
// 5.6e-4). GTR1: 1 − α^(2(1 − u_y)) ≈ (1 − u_y)|ln α²| cancels against hwy's Exp·Log
// (~2e-7 absolute), |ln α²| ≥ 4.6: ≤ 1e-7/(1 − u_y) on wi.
double WiBound(const Rows& r, size_t i) {
  const double gx = 1.0 - double(r.u_x[i]), gy = 1.0 - double(r.u_y[i]);
  return 5e-5 + 4e-7 / std::max(gx, 1e-30) + 1e-7 / std::max(gy, 1e-30);
}

// Whether the oracle, with u_lobe moved by ±1e-4, gives the SIMD's sample: its validity and
// (valid) its wi within 5e-5 (the row sits on a lobe boundary).
bool NearLobeBoundary(const Fixture& fx, size_t i, bool valid, const Out& o1) {
  const Rows& r = fx.rows;
  const MaterialRef ref = MaterialRef::Make(fx.tag, r.index[i]);
  const Vec3f wo{r.wo[0][i], r.wo[1][i], r.wo[2][i]};
  for (float du : {-1e-4f, 1e-4f}) {
    BsdfSample s;
    const bool ok = BsdfSampleDirection(fx.m, ref, wo, r.u_lobe[i] + du, {r.u_x[i], r.u_y[i]},
                                        &s, RowTextureSite(fx.In().texture, i));
    if (ok != valid) continue;
    if (!ok) return true;
    if (std::fabs(s.wi.x - o1.v[4][i]) <= 5e-5f && std::fabs(s.wi.y - o1.v[5][i]) <= 5e-5f &&
        std::fabs(s.wi.z - o1.v[6][i]) <= 5e-5f)
      return true;
  }
  return false;
}

std::string Describe(const Fixture& fx, const Out& o0, const Out& o1, size_t i) {
  const Rows& r = fx.rows;
  char buf[1024];
  const PrincipledParams p =
      PrincipledAt(fx.table(), r.index[i], RowTextureSite(fx.In().texture, i));
  std::snprintf(buf, sizeof(buf),
                "; row %u (rough %g aniso %g metal %g st %g cc %g gloss %g eta %g) wo (%a, %a, "
                "%a) u (%a, %a, %a); oracle wi (%g %g %g) pdf %g w %g; simd wi (%g %g %g) pdf "
                "%g w %g",
                r.index[i], p.roughness, p.anisotropic, p.metallic, p.spec_trans, p.clearcoat,
                p.clearcoat_gloss, p.eta, r.wo[0][i], r.wo[1][i], r.wo[2][i], r.u_lobe[i],
                r.u_x[i], r.u_y[i], o0.v[4][i], o0.v[5][i], o0.v[6][i], o0.v[10][i], o0.v[7][i],
                o1.v[4][i], o1.v[5][i], o1.v[6][i], o1.v[10][i], o1.v[7][i]);
  return buf;
}

void Compare(const Fixture& fx, const Out& o0, const Out& o1, const char* target) {
  const Rows& r = fx.rows;
  const std::string name = fx.tag == MaterialTag::kPrincipled ? "principled" : "principledthin";
  Bound f{name + " f"}, pl{name + " pdf(wo,wl)"}, wi{name + " wi"}, pdf{name + " sample pdf"},
      w{name + " sample weight"}, own_pdf{name + " sample pdf at its wi"},
      own_w{name + " sample weight at its wi"};
  size_t mismatched = 0, valid = 0, conditioned = 0, refracted = 0, textured = 0, rim = 0,
         rim_flips = 0;
  for (size_t i = 0; i < r.size(); ++i) {
    for (int c = 0; c < 12; ++c) ASSERT_TRUE(std::isfinite(o1.v[c][i])) << name << " " << i;
    for (int c : {0, 1, 2, 3, 7, 8, 9, 10}) ASSERT_GE(o1.v[c][i], 0.0f) << name << " " << i;
    for (int c = 0; c < 3; ++c) f.Check(i, o1.v[c][i], o0.v[c][i], 2e-5, 1e-30);
    pl.Check(i, o1.v[3][i], o0.v[3][i], 2e-5, 1e-30);
    const bool v0 = o0.v[10][i] > 0, v1 = o1.v[10][i] > 0;
    if (v0 != v1) {
      const float z = v0 ? o0.v[6][i] : o1.v[6][i];
      if (OnDiskRim(r, i) && std::fabs(z) <= 2e-3f) {  // the cosine warp's rim (hard-case u)
        ++rim_flips;
        continue;
      }
      ++mismatched;
      ASSERT_TRUE(std::fabs(z) <= 1e-4f || NearLobeBoundary(fx, i, v1, o1))
          << name << ": validity differs at " << i << " (wi.z " << z << ")"
          << Describe(fx, o0, o1, i);
      continue;
    }
    if (!v1) continue;
    ++valid;
    // On the rim of the concentric disk the cosine warp's z = √(1 − x² − y²) cancels: there
    // z² is compared (as bsdf8_test.cpp does for every cosine-hemisphere sample).
    const float z0 = o0.v[6][i], z1 = o1.v[6][i];
    const bool z_ok = std::fabs(z1 - z0) <= 5e-5f ||
                      (OnDiskRim(r, i) && std::fabs(z1 * z1 - z0 * z0) <= 4e-6f);
    bool same = z_ok;
    for (int c = 4; c < 6; ++c) same = same && std::fabs(o1.v[c][i] - o0.v[c][i]) <= 5e-5f;
    if (!same && NearLobeBoundary(fx, i, true, o1)) {  // another lobe on its boundary
      ++mismatched;
      continue;
    }
    // The SIMD's sample is one of the oracle's model: its pdf and weight are the oracle's
    // at the SIMD's wi (the same operations as f and pdf(wo, wl) above).
    {
      const MaterialRef ref = MaterialRef::Make(fx.tag, r.index[i]);
      const Vec3f wo{r.wo[0][i], r.wo[1][i], r.wo[2][i]};
      const Vec3f w1{o1.v[4][i], o1.v[5][i], o1.v[6][i]};
      const TextureSite site = RowTextureSite(fx.In().texture, i);
      float opdf;
      const Color3f of = BsdfEvalPdf(fx.m, ref, wo, w1, &opdf, site);
      own_pdf.Check(i, o1.v[10][i], opdf, 2e-5, 1e-30);
      for (int c = 0; c < 3; ++c)
        own_w.Check(i, o1.v[7 + c][i], of[c] * (std::fabs(w1.z) / opdf), 2e-5, 1e-30);
    }
    const double wi_abs = WiBound(r, i);
    rim += wi_abs > 1e-3;
    for (int c = 4; c < 6; ++c) wi.Check(i, o1.v[c][i], o0.v[c][i], 0, wi_abs);
    wi.Check(i, z_ok ? z0 : z1, z0, 0, wi_abs);
    EXPECT_EQ(o1.v[11][i], o0.v[11][i]) << name << " eta at " << i;
    const bool refraction = o0.v[6][i] * r.wo[2][i] < 0;
    refracted += refraction;
    if (!fx.table().base_color_texture.empty() &&
        fx.table().base_color_texture[r.index[i]] != kNoTexture)
      ++textured;
    // Grazing rows and near pass-through refraction: finiteness only (see the contract).
    if (std::fabs(r.wo[2][i]) < 0.02f || std::fabs(o1.v[6][i]) < 0.02f) continue;
    if (refraction && fx.tag == MaterialTag::kPrincipled) {  // thin: η = 1, no bending
      const float eta = o0.v[11][i];
      const Vec3f sum{r.wo[0][i] + eta * o0.v[4][i], r.wo[1][i] + eta * o0.v[5][i],
                      r.wo[2][i] + eta * o0.v[6][i]};
      if (!(Length(sum) >= 0.1f)) continue;
    }
    ++conditioned;
    const double a = AlphaMin(fx, i);
    const double rel = 1e-4 + 4e-7 / (a * a);
    pdf.Check(i, o1.v[10][i], o0.v[10][i], rel, 1e-30);
    for (int c = 7; c < 10; ++c) w.Check(i, o1.v[c][i], o0.v[c][i], rel, 1e-20);
  }
  for (const Bound* b : {&f, &pl, &own_pdf, &own_w, &wi, &pdf, &w}) b->Report(target, r);
  std::printf("[%s] %s samples: valid %zu, refracted %zu, textured %zu, conditioned %zu, "
              "on a boundary %zu (on the disk's rim %zu), wi bound > 1e-3 %zu\n",
              target, name.c_str(), valid, refracted, textured, conditioned, mismatched, rim_flips, rim);
  EXPECT_LT(mismatched, r.size() / 200) << name;
  EXPECT_LT(rim_flips, r.size() / 20) << name;
  EXPECT_GT(valid, r.size() / 5) << name;
  EXPECT_GT(refracted, valid / 20) << name;
  EXPECT_GT(textured, valid / 100) << name;
  EXPECT_GT(conditioned, valid / 3) << name;
}

void CheckAgainstOracle(MaterialTag tag) {
  Fixture fx;
  fx.tag = tag;
  AddRows(&fx);
  AddInputs(&fx, size_t(1) << 16);
  const ShadeInputs in = fx.In();
  const size_t n = fx.rows.size();
  Out o0(n);
  ptlab::ShadeBatch(fx.m, tag, fx.rows.index.data(), n, in, o0.Outputs());
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
    Out o1(n);
    simd::ShadeBatch(fx.m, tag, fx.rows.index.data(), n, in, o1.Outputs());
    Compare(fx, o0, o1, target);
  });
}

TEST(Principled8, ShadeBatchMatchesOracleOnEveryTarget) {
  CheckAgainstOracle(MaterialTag::kPrincipled);
}

TEST(Principled8, ThinShadeBatchMatchesOracleOnEveryTarget) {
  CheckAgainstOracle(MaterialTag::kPrincipledThin);
}

// Non-unit, huge, denormal and zero directions (outside the preconditions): every output of
// every target finite, f, pdf and weight ≥ 0.
TEST(Principled8, NonUnitAndHugeInputsStayFinite) {
  for (MaterialTag tag : {MaterialTag::kPrincipled, MaterialTag::kPrincipledThin}) {
    Fixture fx;
    fx.tag = tag;
    AddRows(&fx);
    const std::vector<Vec3f> dirs = bsdf_test::HardDirections(/*with_non_unit=*/true);
    const std::vector<float> us = bsdf_test::HardUs();
    const uint32_t rows = uint32_t(fx.table().size());
    for (uint32_t row = 0; row < rows; row += 2)
      for (size_t a = dirs.size() - 4; a < dirs.size(); ++a)
        for (size_t j = 0; j < dirs.size(); j += 3)
          fx.rows.Push(row, dirs[a], dirs[j], us[j % us.size()], us[(j + a) % us.size()],
                       us[(3 * j + a) % us.size()]);
    fx.its.resize(fx.rows.size());
    const size_t n = fx.rows.size();
    test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
      Out o(n);
      simd::ShadeBatch(fx.m, tag, fx.rows.index.data(), n, fx.In(), o.Outputs());
      for (size_t i = 0; i < n; ++i) {
        for (int c = 0; c < 12; ++c) ASSERT_TRUE(std::isfinite(o.v[c][i])) << target << " " << i;
        for (int c : {0, 1, 2, 3, 7, 8, 9, 10}) ASSERT_GE(o.v[c][i], 0.0f) << target << " " << i;
      }
    });
  }
}

// Evaluation alone (no sample inputs) and a partial last block give the rows of a full run.
TEST(Principled8, EvalOnlyAndPartialBlocksMatchFullRuns) {
  for (MaterialTag tag : {MaterialTag::kPrincipled, MaterialTag::kPrincipledThin}) {
    Fixture fx;
    fx.tag = tag;
    AddRows(&fx);
    AddInputs(&fx, 1000);
    ShadeInputs in = fx.In();
    const size_t n = 1003;  // not a multiple of 8
    Out full(n), part(n);
    simd::ShadeBatch(fx.m, tag, fx.rows.index.data(), n, in, full.Outputs());
    in.u_lobe = in.u_x = in.u_y = nullptr;
    ShadeOutputs o = part.Outputs();
    simd::ShadeBatch(fx.m, tag, fx.rows.index.data(), n, in, o);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 4; ++c) ASSERT_EQ(part.v[c][i], full.v[c][i]) << c << " " << i;
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(part.v[10][i], -7.0f) << "sample written at " << i;
  }
}

}  // namespace
}  // namespace ptlab
