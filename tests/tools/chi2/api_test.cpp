// The public API (ptlab/chi2.h): same results as the lab's own test, clear errors on bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/core/vec.h"
#include "ptlab/chi2.h"
#include "tools/chi2/chi2.h"
#include "tools/chi2/subjects.h"

namespace ptlab {
namespace {

constexpr float kPiF = 3.14159265f;

// docs/chi2.md's example lobe: sampler and pdf, float arithmetic.
chi2::Point SamplePowerCosine(float u0, float u1, float n) {
  const float z = std::pow(u0, 1.0f / (n + 1.0f)), r = std::sqrt(std::fmax(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPiF * u1;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
double PowerCosinePdf(float z, float n) {
  return z > 0 ? (n + 1.0f) / (2.0f * kPiF) * std::pow(z, n) : 0.0f;
}

chi2::Subject PowerCosine(float n_pdf, double scale) {
  chi2::Subject s;
  s.name = "power_cosine_n10";
  s.domain = chi2::Domain::Hemisphere();
  s.sample = [](const float* u, int64_t count, int dims, chi2::Point* p) {
    for (int64_t i = 0; i < count; ++i) p[i] = SamplePowerCosine(u[i * dims], u[i * dims + 1], 10);
    return chi2::Status::Ok();
  };
  s.pdf = [=](const chi2::Point* w, int64_t count, double* d) {
    for (int64_t i = 0; i < count; ++i) d[i] = scale * PowerCosinePdf(w[i].z, n_pdf);
    return chi2::Status::Ok();
  };
  return s;
}

// The route through the public API equals ptlab's own chi2 on a registered subject of the same
// name (same uniforms, same points, same pdf values): bit-identical χ², p and cells.
TEST(StatChi2Api, SameResultAsTheLabsOwnTest) {
  const Chi2Subject internal = DirectionWarpSubject(
      "power_cosine_n10", Chi2Domain::Hemisphere(),
      [](const Vec2f& u) {
        const chi2::Point p = SamplePowerCosine(u.x, u.y, 10);
        return Vec3f{p.x, p.y, p.z};
      },
      [](const Vec3f& w) { return float(PowerCosinePdf(w.z, 10)); });
  Chi2Options io;
  io.samples = 200000;
  io.res = 25;
  const Chi2Result a = RunChi2Test(internal, io);
  chi2::Options o;
  o.samples = io.samples;
  o.res = io.res;
  chi2::Result b;
  const chi2::Status st = chi2::Test(PowerCosine(10, 1.0), o, &b);
  ASSERT_TRUE(st.ok()) << st.message();
  EXPECT_EQ(a.chi2, b.chi2);
  EXPECT_EQ(a.p_value, b.p_value);
  EXPECT_EQ(a.dof, b.dof);
  EXPECT_EQ(a.observed, b.observed);
  EXPECT_EQ(a.expected, b.expected);
  EXPECT_TRUE(a.pass);
  EXPECT_TRUE(b.passed);
}

// α = 0.01; the broken variants of docs/chi2.md are rejected for the reason they are broken.
TEST(StatChi2Api, BrokenVariantsFail) {
  chi2::Options o;
  o.samples = 200000;
  o.res = 25;
  chi2::Result r;
  ASSERT_TRUE(chi2::Test(PowerCosine(10, 0.5), o, &r).ok());
  EXPECT_FALSE(r.passed);
  EXPECT_NEAR(r.pdf_integral, 0.5, 1e-4);
  ASSERT_TRUE(chi2::Test(PowerCosine(11, 1.0), o, &r).ok());
  EXPECT_FALSE(r.passed);
  EXPECT_NEAR(r.pdf_integral, 1.0, 1e-4);
  EXPECT_LT(r.p_value, 1e-6);
}

chi2::Status RunWith(const chi2::Subject& s, chi2::Options o = {}) {
  o.samples = std::min<int64_t>(o.samples, 5000);
  o.res = std::min(o.res, 8);
  chi2::Result r;
  return chi2::Test(s, o, &r);
}

TEST(Chi2ApiBadInput, SamplesThatAreNotFiniteOrOutsideTheDomain) {
  chi2::Subject s = PowerCosine(10, 1.0);
  const chi2::SampleFn good = s.sample;
  s.sample = [good](const float* u, int64_t n, int dims, chi2::Point* p) {
    good(u, n, dims, p);
    p[7].y = std::nanf("");
    return chi2::Status::Ok();
  };
  chi2::Status st = RunWith(s);
  EXPECT_FALSE(st.ok());
  EXPECT_NE(st.message().find("not finite"), std::string::npos) << st.message();
  s.sample = [good](const float* u, int64_t n, int dims, chi2::Point* p) {
    good(u, n, dims, p);
    p[3].z = -p[3].z;
    return chi2::Status::Ok();
  };
  st = RunWith(s);
  EXPECT_NE(st.message().find("sample 3 is"), std::string::npos) << st.message();
  EXPECT_NE(st.message().find("outside the domain hemisphere"), std::string::npos);
}

TEST(Chi2ApiBadInput, CallablesThatFail) {
  chi2::Subject s = PowerCosine(10, 1.0);
  s.pdf = [](const chi2::Point*, int64_t, double*) {
    return chi2::Status::Error("density table not loaded");
  };
  chi2::Status st = RunWith(s);
  EXPECT_EQ(st.message(), "the pdf failed: density table not loaded");
  s = PowerCosine(10, 1.0);
  s.sample = [](const float*, int64_t, int, chi2::Point*) { return chi2::Status::Error("boom"); };
  EXPECT_EQ(RunWith(s).message(), "the sampler failed: boom");
  s.sample = nullptr;
  EXPECT_EQ(RunWith(s).message(), "the subject has no sample function");
}

// A pdf that is noise within cells never lets the adaptive integration settle: it stops at its
// budget of evaluated points (kMaxBatchPdfPoints) with a failure that says so, instead of
// keeping every point (fuzz_chi2_api found 1.9 GB and rising from 18 KB of input).
TEST(Chi2ApiBadInput, NoisePdfStopsAtTheIntegrationBudget) {
  std::vector<chi2::Point> points(1000, chi2::Point{0.5f, 0.5f, 0.0f});
  uint64_t state = 1;
  const chi2::PdfFn noise = [&state](const chi2::Point*, int64_t n, double* out) {
    for (int64_t i = 0; i < n; ++i) {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      out[i] = double(state >> 40) / double(1 << 24);  // in [0, 1), no two points alike
    }
    return chi2::Status::Ok();
  };
  chi2::Options options;
  options.res = 8;
  options.coarse_blocks = 0;
  chi2::Result r;
  ASSERT_TRUE(chi2::TestPoints("noise", chi2::Domain::Square(), points.data(),
                               int64_t(points.size()), noise, options, &r)
                  .ok());
  EXPECT_FALSE(r.passed);
  ASSERT_FALSE(r.failures.empty());
  EXPECT_NE(r.failures.front().find("needed more than 8000000 evaluations"), std::string::npos)
      << r.failures.front();
}

TEST(Chi2ApiBadInput, OptionsDomainsAndEmptyInput) {
  chi2::Subject s = PowerCosine(10, 1.0);
  chi2::Options o;
  o.alpha = 1.5;
  EXPECT_NE(RunWith(s, o).message().find("alpha must be in (0, 1)"), std::string::npos);
  s.uniform_dims = 0;
  EXPECT_NE(RunWith(s).message().find("uniform_dims must be in [1, 8]"), std::string::npos);
  chi2::Domain d;
  EXPECT_FALSE(chi2::ParseDomain("box:1,0,0,1", &d).ok());
  EXPECT_NE(chi2::ParseDomain("cube", &d).message().find("expected square, disk"),
            std::string::npos);
  ASSERT_TRUE(chi2::ParseDomain("box:0,-1,2,1.5", &d).ok());
  EXPECT_EQ(chi2::DomainName(d), "box:0,-1,2,1.5");
  chi2::Result r;
  const chi2::Status st = chi2::TestPoints("none", d, nullptr, 0, s.pdf, {}, &r);
  EXPECT_EQ(st.message(), "no samples given (at least 1 needed)");
}

// Student's t: a sample mean at the reference passes, one 10 standard errors off fails; the
// p-value equals the lab's own OneSampleTTest on the same moments.
TEST(StatChi2Api, TTests) {
  std::vector<double> v(1000), w(1000);
  for (int i = 0; i < 1000; ++i) v[i] = (i % 10) * 0.1, w[i] = v[i] + 0.05;
  chi2::TTestResult t;
  ASSERT_TRUE(chi2::OneSampleTTest(v.data(), 1000, 0.45, 0.01, 1, &t).ok());
  EXPECT_TRUE(t.passed);
  EXPECT_NEAR(t.t, 0.0, 1e-9);
  ASSERT_TRUE(
      chi2::OneSampleTTest(v.data(), 1000, 0.45 + 10 * std::sqrt(t.variance / 1000), 0.01, 1, &t)
          .ok());
  EXPECT_FALSE(t.passed);
  EXPECT_NEAR(t.t, -10.0, 1e-9);
  ASSERT_TRUE(chi2::WelchTTest(v.data(), 1000, w.data(), 1000, 0.01, 1, &t).ok());
  EXPECT_FALSE(t.passed);  // 0.05 apart, standard error ~0.0128: t ~ -3.9
  EXPECT_EQ(chi2::OneSampleTTest(v.data(), 1, 0.0, 0.01, 1, &t).message(),
            "values: a t-test needs at least 2 values, got 1");
}

}  // namespace
}  // namespace ptlab
