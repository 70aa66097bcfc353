// Tests of the microfacet distributions: erf forms, D and visible-normal normalisation, G1,
// hard inputs, and (StatMicrofacet) the samplers against their pdf by the χ² lab.
#include "engine/bsdf/microfacet.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/core/rng.h"
#include "tests/engine/bsdf/bsdf_test_inputs.h"
#include "tools/chi2/chi2.h"
#include "tools/chi2/subjects.h"

namespace ptlab {
namespace {

constexpr MicrofacetType kTypes[] = {MicrofacetType::kBeckmann, MicrofacetType::kGgx};

const char* Name(MicrofacetType t) { return t == MicrofacetType::kGgx ? "ggx" : "beckmann"; }

// ∫ f(m) dω_m over the upper hemisphere: midpoint rule in (θ, φ), θ resolved finely near the
// pole where narrow lobes live (θ = (π/2) t², t uniform).
template <typename F>
double IntegrateHemisphere(F f, int nt, int np) {
  double sum = 0;
  for (int i = 0; i < nt; ++i) {
    const double t = (i + 0.5) / nt;
    const double theta = 0.5 * M_PI * t * t, dtheta = M_PI * t / nt;
    for (int j = 0; j < np; ++j) {
      const double phi = (j + 0.5) * 2 * M_PI / np;
      const Vec3f m{float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                    float(std::cos(theta))};
      sum += double(f(m)) * std::sin(theta) * dtheta * (2 * M_PI / np);
    }
  }
  return sum;
}

TEST(Microfacet, ErfFormsMatchTheLibrary) {
  double worst_erf = 0, worst_inv = 0;
  for (int i = -4000; i <= 4000; ++i) {
    const float x = i * 1e-3f;
    worst_erf = std::max(worst_erf, std::fabs(double(ErfApprox(x)) - std::erf(double(x))));
  }
  for (int i = -999; i <= 999; ++i) {
    const float y = i * 1e-3f;
    const double x = ErfInvApprox(y);
    // erf(erf⁻¹(y)) = y: the error in y relative to the slope of erf at x.
    const double slope = 2 / std::sqrt(M_PI) * std::exp(-x * x);
    worst_inv = std::max(worst_inv, std::fabs(std::erf(x) - y) / slope / std::max(1.0, std::fabs(x)));
  }
  // A&S 7.1.26 is within 1.5e-7; its float evaluation (1 − p·e^(−x²)) adds a few ulp of 1
  // (measured worst 4.1e-7).
  EXPECT_LT(worst_erf, 5e-7);
  EXPECT_LT(worst_inv, 2e-6);
  EXPECT_EQ(ErfApprox(INFINITY), 1.0f);
  EXPECT_EQ(ErfApprox(-INFINITY), -1.0f);
  EXPECT_TRUE(std::isfinite(ErfInvApprox(1.0f)));
  EXPECT_TRUE(std::isfinite(ErfInvApprox(-1.0f)));
  EXPECT_TRUE(std::isfinite(ErfInvApprox(NAN)));
}

TEST(Microfacet, DCosIntegratesToOne) {
  for (MicrofacetType type : kTypes) {
    for (auto [au, av] : {std::pair{0.05f, 0.05f}, {0.3f, 0.3f}, {1.0f, 1.0f}, {0.05f, 0.5f},
                          {0.6f, 0.1f}}) {
      const Microfacet d = MakeMicrofacet(type, au, av);
      // GGX's long tail: at α = 1 the mass beyond θ = 89.9° is ~1e-6.
      const double integral = IntegrateHemisphere(
          [&](const Vec3f& m) { return MicrofacetD(d, m) * m.z; }, 1500, 360);
      EXPECT_NEAR(integral, 1.0, 2e-3) << Name(type) << " " << au << " " << av;
    }
  }
}

TEST(Microfacet, VisibleNormalDensityIntegratesToOne) {  // 1200 × 240 cells per integral
  for (MicrofacetType type : kTypes) {
    for (auto [au, av] : {std::pair{0.1f, 0.1f}, {0.5f, 0.5f}, {1.0f, 1.0f}, {0.1f, 0.6f}}) {
      const Microfacet d = MakeMicrofacet(type, au, av, true);
      for (float theta_deg : {0.0f, 40.0f, 75.0f, 89.0f}) {
        const float t = theta_deg * kPi / 180;
        const Vec3f w{std::sin(t) * std::cos(0.4f), std::sin(t) * std::sin(0.4f), std::cos(t)};
        const double integral = IntegrateHemisphere(
            [&](const Vec3f& m) { return MicrofacetPdf(d, w, m); }, 1200, 240);
        EXPECT_NEAR(integral, 1.0, 2e-3) << Name(type) << " " << au << " " << av << " θ "
                                         << theta_deg;
      }
    }
  }
}

TEST(Microfacet, G1ClosedFormsAndOrientation) {
  for (float alpha : {0.05f, 0.3f, 1.0f}) {
    for (float c : {1e-3f, 0.1f, 0.5f, 0.9f, 1.0f}) {
      const Vec3f v = bsdf_test::DirectionWithCos(c, 0.0f);
      const Vec3f up{0, 0, 1};
      const double tan_t = std::sqrt(1.0 - double(c) * c) / c;
      // GGX: 2 / (1 + √(1 + α² tan²)).
      const double ggx = 2 / (1 + std::sqrt(1 + alpha * alpha * tan_t * tan_t));
      EXPECT_NEAR(MicrofacetG1(MakeMicrofacet(MicrofacetType::kGgx, alpha, alpha), v, up), ggx,
                  1e-6);
      // Beckmann, exact Smith: a = 1/(α tan θ), Λ = (erf a − 1)/2 + e^(−a²)/(2a√π).
      const double a = 1 / (alpha * tan_t);
      const double lambda = c == 1.0f ? 0 : (std::erf(a) - 1) / 2 + std::exp(-a * a) / (2 * a * std::sqrt(M_PI));
      const float g = MicrofacetG1(MakeMicrofacet(MicrofacetType::kBeckmann, alpha, alpha), v, up);
      EXPECT_NEAR(g, 1 / (1 + lambda), 1e-6) << alpha << " " << c;
      // Mitsuba's rational approximation is within 0.35 %.
      const double b = a;
      const double rational =
          b >= 1.6 ? 1 : (3.535 * b + 2.181 * b * b) / (1 + 2.276 * b + 2.577 * b * b);
      EXPECT_NEAR(g, rational, 0.0036 * rational + 1e-7);
    }
  }
  // Anisotropic: G1 depends on the roughness along v's azimuth only.
  const Microfacet aniso = MakeMicrofacet(MicrofacetType::kGgx, 0.1f, 0.8f);
  const Vec3f vx = bsdf_test::DirectionWithCos(0.3f, 0.0f), vy = bsdf_test::DirectionWithCos(0.3f, kPi / 2);
  const Vec3f up{0, 0, 1};
  EXPECT_FLOAT_EQ(MicrofacetG1(aniso, vx, up),
                  MicrofacetG1(MakeMicrofacet(MicrofacetType::kGgx, 0.1f, 0.1f), vx, up));
  EXPECT_NEAR(MicrofacetG1(aniso, vy, up),
              MicrofacetG1(MakeMicrofacet(MicrofacetType::kGgx, 0.8f, 0.8f), vy, up), 1e-6f);
  // The back of a microfacet is never visible; below the surface the roles swap.
  const Vec3f m = Normalize(Vec3f{1, 0, 0.2f});
  const Vec3f v{-0.9f, 0, std::sqrt(1 - 0.81f)};
  const Microfacet d = MakeMicrofacet(MicrofacetType::kBeckmann, 0.5f, 0.5f);
  EXPECT_EQ(MicrofacetG1(d, v, m), 0.0f);
  EXPECT_GT(MicrofacetG1(d, Vec3f{0.9f, 0, -v.z}, Vec3f{-m.x, -m.y, -m.z}), 0.0f);
  EXPECT_EQ(MicrofacetG(d, v, up, m), 0.0f);
}

TEST(Microfacet, DPeakAndAnisotropy) {
  for (MicrofacetType type : kTypes) {
    const Microfacet d = MakeMicrofacet(type, 0.2f, 0.5f);
    EXPECT_FLOAT_EQ(MicrofacetD(d, {0, 0, 1}), 1.0f / (kPi * 0.2f * 0.5f));
    // Stretching: a normal tilted along x by slope 0.2 t equals one tilted along y by 0.5 t.
    const Vec3f mx = Normalize(Vec3f{0.2f * 0.7f, 0, 1}), my = Normalize(Vec3f{0, 0.5f * 0.7f, 1});
    const float scale = std::pow(my.z / mx.z, 4.0f);  // D ∝ 1/cos⁴θ at equal stretched slope
    EXPECT_NEAR(MicrofacetD(d, mx), MicrofacetD(d, my) * scale, 1e-5f * MicrofacetD(d, mx));
    EXPECT_EQ(MicrofacetD(d, {0.3f, 0, -0.9f}), 0.0f);
  }
  // α → 1e-4: the peak stays finite.
  EXPECT_TRUE(std::isfinite(MicrofacetD(MakeMicrofacet(MicrofacetType::kGgx, 0, 0), {0, 0, 1})));
}

// Every (type, α, visible, w, u) of the hard-case lists: a unit m above the surface with the
// pdf MicrofacetPdf gives it, or pdf 0; never NaN or Inf.
TEST(Microfacet, HardInputsSampleFiniteNormals) {
  const std::vector<float> alphas = {0.0f, 1e-4f, 1e-3f, 0.05f, 0.5f, 1.0f, 2.0f, 1e30f, NAN};
  int sampled = 0, total = 0;
  for (MicrofacetType type : kTypes) {
    for (bool visible : {false, true}) {
      for (float au : alphas) {
        for (float ratio : {1.0f, 100.0f, 0.01f}) {
          const Microfacet d = MakeMicrofacet(type, au, au * ratio, visible);
          for (const Vec3f& w : bsdf_test::HardDirections(false)) {
            for (float ux : bsdf_test::HardUs()) {
              for (float uy : {0.0f, 0.3f, kOneMinusEpsilon}) {
                float pdf = -1;
                const Vec3f m = SampleMicrofacet(d, w, {ux, uy}, &pdf);
                ++total;
                ASSERT_TRUE(std::isfinite(pdf) && pdf >= 0);
                ASSERT_TRUE(std::isfinite(m.x) && std::isfinite(m.y) && std::isfinite(m.z));
                if (!(w.z > 0)) {
                  EXPECT_EQ(pdf, 0.0f);
                  continue;
                }
                if (pdf == 0) continue;
                ++sampled;
                EXPECT_NEAR(Length(m), 1.0f, 1e-5f);
                EXPECT_GT(m.z, 0.0f);
                EXPECT_EQ(pdf, MicrofacetPdf(d, w, m));
                const float g1 = MicrofacetG1(d, w, m);
                EXPECT_TRUE(g1 >= 0 && g1 <= 1);
              }
            }
          }
        }
      }
    }
  }
  EXPECT_GT(sampled, total / 3);
}

// Sampler against pdf: the χ² lab (tools/chi2) on the hemisphere of normals, 10⁵ samples,
// family-wise α = 0.01 over the run's subjects (Šidák).
struct Case {
  MicrofacetType type;
  float au, av;
  bool visible;
  float theta_deg, phi_deg;
};

TEST(StatMicrofacet, SamplersMatchTheirPdf) {
  const std::vector<Case> cases = {
      {MicrofacetType::kBeckmann, 0.3f, 0.3f, true, 0, 0},
      {MicrofacetType::kBeckmann, 0.3f, 0.3f, true, 60, 30},
      {MicrofacetType::kBeckmann, 0.8f, 0.8f, true, 85, 200},
      {MicrofacetType::kBeckmann, 0.2f, 0.7f, true, 50, 70},
      {MicrofacetType::kBeckmann, 0.4f, 0.4f, false, 30, 0},
      {MicrofacetType::kBeckmann, 0.6f, 0.15f, false, 30, 0},
      {MicrofacetType::kGgx, 0.3f, 0.3f, true, 0, 0},
      {MicrofacetType::kGgx, 0.3f, 0.3f, true, 60, 30},
      {MicrofacetType::kGgx, 0.8f, 0.8f, true, 85, 200},
      {MicrofacetType::kGgx, 0.7f, 0.2f, true, 50, 70},
      {MicrofacetType::kGgx, 0.4f, 0.4f, false, 30, 0},
      {MicrofacetType::kGgx, 0.15f, 0.6f, false, 30, 0},
  };
  Chi2Options options;
  options.samples = 100000;
  options.res = 25;
  options.test_count = int(cases.size());
  for (const Case& c : cases) {
    const Microfacet d = MakeMicrofacet(c.type, c.au, c.av, c.visible);
    const float t = c.theta_deg * kPi / 180, p = c.phi_deg * kPi / 180;
    const Vec3f w{std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
    const std::string name = std::string("microfacet/") + Name(c.type) + (c.visible ? "_vis" : "") +
                             "_" + std::to_string(c.au) + "_" + std::to_string(c.av) + "_t" +
                             std::to_string(int(c.theta_deg));
    Chi2Subject s = DirectionWarpSubject(
        name, Chi2Domain::Hemisphere(),
        [d, w](const Vec2f& u) {
          float pdf;
          return SampleMicrofacet(d, w, u, &pdf);
        },
        [d, w](const Vec3f& m) { return MicrofacetPdf(d, w, m); });
    const Chi2Result r = RunChi2Test(s, options);
    EXPECT_TRUE(r.pass) << name << ": p = " << r.p_value << ", coarse p = " << r.coarse_p_value
                        << ", ∫pdf = " << r.pdf_integral
                        << (r.failures.empty() ? "" : ", " + r.failures[0]);
  }
}

}  // namespace
}  // namespace ptlab
