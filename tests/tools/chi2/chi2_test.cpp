// The chi-square test's checks: each kind of wrong sampler or pdf is rejected for its reason.
#include "tools/chi2/chi2.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/sampling/warp.h"
#include "tools/chi2/subjects.h"

namespace ptlab {
namespace {

bool FailedFor(const Chi2Result& r, const std::string& text) {
  return std::any_of(r.failures.begin(), r.failures.end(),
                     [&](const std::string& f) { return f.find(text) != std::string::npos; });
}

std::string Describe(const Chi2Subject& s, const Chi2Result& r) { return FormatChi2Result(s, r); }

Chi2Subject UniformSquare(float (*pdf)(const Vec2f&)) {
  return PlanarWarpSubject("test/square", Chi2Domain::UnitSquare(), SampleUniformSquare, pdf);
}

TEST(StatChi2Checks, PdfIntegratingToPointNineIsRejected) {
  const Chi2Subject s = UniformSquare([](const Vec2f&) { return 0.9f; });
  const Chi2Result r = RunChi2Test(s, {});
  EXPECT_FALSE(r.pass);
  EXPECT_NEAR(r.pdf_integral, 0.9, 1e-6);
  EXPECT_TRUE(FailedFor(r, "integrates to 0.900000")) << Describe(s, r);
}

TEST(StatChi2Checks, PdfOffByLessThanTheToleranceIsNotFlagged) {
  // 1.0005 is within the 1e-3 integral tolerance; with 10^5 samples χ² cannot see 0.05 %.
  const Chi2Subject s = UniformSquare([](const Vec2f&) { return 1.0005f; });
  Chi2Options options;
  options.samples = 100000;
  const Chi2Result r = RunChi2Test(s, options);
  EXPECT_TRUE(r.pass) << Describe(s, r);
}

TEST(StatChi2Checks, SampleOutsideTheDomainIsRejected) {
  // One sample in 10^4 lands at x = 1.5, the rest is exactly uniform.
  Chi2Subject s = PlanarWarpSubject(
      "test/leaky_square", Chi2Domain::UnitSquare(),
      [](const Vec2f& u) {
        return u.x < 1e-4f ? Vec2f{1.5f, u.y} : u;
      },
      UniformSquarePdf);
  const Chi2Result r = RunChi2Test(s, {});
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(FailedFor(r, "samples outside the domain (first (1.5,")) << Describe(s, r);
}

TEST(StatChi2Checks, NonFiniteSampleIsRejected) {
  Chi2Subject s = PlanarWarpSubject(
      "test/nan_square", Chi2Domain::UnitSquare(),
      [](const Vec2f& u) {
        return u.x < 1e-4f ? Vec2f{NAN, u.y} : u;
      },
      UniformSquarePdf);
  Chi2Options options;
  options.samples = 200000;
  const Chi2Result r = RunChi2Test(s, options);
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(FailedFor(r, "non-finite samples")) << Describe(s, r);
}

TEST(StatChi2Checks, NegativeOrNonFinitePdfIsRejected) {
  Chi2Options options;
  options.samples = 100000;
  // Negative on a corner region, compensated elsewhere so the integral stays about 1.
  const Chi2Subject negative =
      UniformSquare([](const Vec2f& p) { return (p.x < 0.1f && p.y < 0.1f) ? -0.01f : 1.0001f; });
  Chi2Result r = RunChi2Test(negative, options);
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(FailedFor(r, "non-finite or negative")) << Describe(negative, r);
  const Chi2Subject nan =
      UniformSquare([](const Vec2f& p) { return (p.x > 0.99f && p.y > 0.99f) ? NAN : 1.0f; });
  r = RunChi2Test(nan, options);
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(FailedFor(r, "non-finite or negative")) << Describe(nan, r);
}

TEST(StatChi2Checks, SamplesInCellsOfZeroExpectedMassAreRejected) {
  // Uniform disk samples, but a pdf that puts all the mass on the right half (integral 1).
  const Chi2Subject s =
      PlanarWarpSubject("test/half_disk_pdf", Chi2Domain::Disk(), SampleUniformDisk,
                        [](const Vec2f& p) { return p.x >= 0 ? 2.0f * UniformDiskPdf(p) : 0.0f; });
  Chi2Options options;
  options.samples = 200000;
  const Chi2Result r = RunChi2Test(s, options);
  EXPECT_FALSE(r.pass);
  EXPECT_NEAR(r.pdf_integral, 1.0, 1e-4);
  EXPECT_TRUE(FailedFor(r, "cells of zero expected mass")) << Describe(s, r);
}

TEST(StatChi2Checks, SliverOfSupportMissedByTheCoarseRuleIsFound) {
  // Uniform on [0.252, 0.26] x [0.2, 0.26]: on a 4x4 grid the support lies in two cells but
  // between the 9 points per axis of their first integration (x = 0.25, 0.28125, ...).
  const Chi2Subject s = PlanarWarpSubject(
      "test/sliver", Chi2Domain::UnitSquare(),
      [](const Vec2f& u) {
        return Vec2f{0.252f + 0.008f * u.x, 0.2f + 0.06f * u.y};
      },
      [](const Vec2f& p) {
        const bool in = p.x >= 0.252f && p.x <= 0.26f && p.y >= 0.2f && p.y <= 0.26f;
        return in ? float(1.0 / (0.008 * 0.06)) : 0.0f;
      });
  Chi2Options options;
  options.samples = 100000;
  options.res = 4;
  const Chi2Result r = RunChi2Test(s, options);
  EXPECT_TRUE(r.pass) << Describe(s, r);
  EXPECT_NEAR(r.pdf_integral, 1.0, 1e-3);
}

TEST(StatChi2Checks, ChiSquareAloneRejectsANormalisedWrongPdf) {
  const Chi2Registry registry = DefaultChi2Registry();
  const Chi2Subject* s = registry.Find("broken/cosine_sampler_uniform_pdf");
  ASSERT_NE(s, nullptr);
  const Chi2Result r = RunChi2Test(*s, {});
  EXPECT_FALSE(r.pass);
  EXPECT_NEAR(r.pdf_integral, 1.0, 1e-6);
  // Only the χ² statistics reject it: on the fine grid and on the coarse one.
  ASSERT_EQ(r.failures.size(), 2u) << Describe(*s, r);
  for (const std::string& f : r.failures) EXPECT_EQ(f.rfind("chi-square rejects", 0), 0u) << f;
  EXPECT_LT(r.p_value, r.alpha_each);
  EXPECT_LT(r.coarse_p_value, r.alpha_each);
}

// A uniform-hemisphere "BSDF" that absorbs when u1 < absorb, claiming mass `albedo`.
Chi2Subject AbsorbingHemisphere(float absorb, double albedo) {
  Chi2Subject s;
  s.name = "test/absorbing_hemisphere";
  s.domain = Chi2Domain::Hemisphere();
  s.uniform_dims = 3;
  s.sample = [absorb](float u1, const Vec2f& u2, Chi2Point* p) {
    if (u1 < absorb) return false;
    *p = SampleUniformHemisphere(u2);
    return true;
  };
  const double mass = std::isnan(albedo) ? 0.75 : albedo;
  s.pdf = [mass](const Chi2Point& w) { return mass * UniformHemispherePdf(w); };
  s.albedo = albedo;
  return s;
}

TEST(StatChi2Checks, DefectiveSubjectWithMatchingAbsorptionPasses) {
  const Chi2Subject s = AbsorbingHemisphere(0.25f, 0.75);
  const Chi2Result r = RunChi2Test(s, {});
  EXPECT_TRUE(r.pass) << Describe(s, r);
  EXPECT_NEAR(double(r.absorbed), 0.25e6, 5 * std::sqrt(0.25 * 0.75 * 1e6));
  EXPECT_NEAR(r.pdf_integral, 0.75, 1e-6);
  // With an unknown albedo only ∫pdf <= 1 is required.
  const Chi2Subject unknown = AbsorbingHemisphere(0.25f, kChi2UnknownAlbedo);
  EXPECT_TRUE(RunChi2Test(unknown, {}).pass);
}

TEST(StatChi2Checks, DefectiveSubjectWithWrongAbsorptionIsRejected) {
  // Absorbs 30 % but the pdf (and the stated albedo) say 25 %: every cell is 7 % short and the
  // absorbed outcome 20 % over, which only χ² sees (∫pdf equals the stated albedo).
  const Chi2Subject s = AbsorbingHemisphere(0.30f, 0.75);
  const Chi2Result r = RunChi2Test(s, {});
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(FailedFor(r, "chi-square rejects")) << Describe(s, r);
}

TEST(StatChi2Checks, AbsorbedSamplesOfANonDefectiveSubjectAreRejected) {
  Chi2Subject s = AbsorbingHemisphere(0.001f, 1.0);
  s.pdf = [](const Chi2Point& w) { return double(UniformHemispherePdf(w)); };
  Chi2Options options;
  options.samples = 100000;
  const Chi2Result r = RunChi2Test(s, options);
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(FailedFor(r, "absorbed")) << Describe(s, r);
}

TEST(StatChi2Checks, IntegralAboveOneIsRejectedForUnknownAlbedo) {
  Chi2Subject s = AbsorbingHemisphere(0.0f, kChi2UnknownAlbedo);
  s.pdf = [](const Chi2Point& w) { return 1.01 * UniformHemispherePdf(w); };
  Chi2Options options;
  options.samples = 100000;
  const Chi2Result r = RunChi2Test(s, options);
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(FailedFor(r, "more than 1")) << Describe(s, r);
}

TEST(StatChi2Checks, BatchSamplerSeesTheSameUniformsAsTheScalarOne) {
  Chi2Subject scalar =
      PlanarWarpSubject("test/disk", Chi2Domain::Disk(), SampleConcentricDisk, ConcentricDiskPdf);
  Chi2Subject batch = scalar;
  batch.sample = nullptr;
  batch.sample_batch = [](const float*, const Vec2f* u, int n, Chi2Point* p, uint8_t* ok) {
    for (int i = 0; i < n; ++i) {
      const Vec2f q = SampleConcentricDisk(u[i]);
      p[i] = {q.x, q.y, 0.0f};
      ok[i] = 1;
    }
  };
  Chi2Options options;
  options.samples = 100003;  // not a multiple of the chunk size
  const Chi2Result a = RunChi2Test(scalar, options), b = RunChi2Test(batch, options);
  EXPECT_TRUE(a.pass) << Describe(scalar, a);
  EXPECT_EQ(a.observed, b.observed);
  EXPECT_EQ(a.chi2, b.chi2);
}

TEST(StatChi2Checks, RunsAreDeterministicAndSeedsMatter) {
  const Chi2Subject s =
      PlanarWarpSubject("warp/tent", Chi2Domain::Box(-1, -1, 1, 1), SampleTent, TentPdf);
  Chi2Options options;
  options.samples = 100000;
  const Chi2Result a = RunChi2Test(s, options), b = RunChi2Test(s, options);
  EXPECT_EQ(a.observed, b.observed);
  EXPECT_EQ(a.chi2, b.chi2);
  options.seed += 1;
  EXPECT_NE(RunChi2Test(s, options).chi2, a.chi2);
}

TEST(StatChi2Checks, ResolutionAndSidakAreApplied) {
  const Chi2Subject s = PlanarWarpSubject("test/square", Chi2Domain::UnitSquare(),
                                          SampleUniformSquare, UniformSquarePdf);
  Chi2Options options;
  options.samples = 100000;
  options.res = 20;
  options.test_count = 10;
  const Chi2Result r = RunChi2Test(s, options);
  EXPECT_EQ(r.xres, 20);
  EXPECT_EQ(r.yres, 20);
  EXPECT_EQ(r.dof, 399);
  EXPECT_DOUBLE_EQ(r.alpha, SidakAlpha(0.01, 10));
  double total = 0;
  for (double e : r.expected) total += e;
  EXPECT_NEAR(total, 100000.0, 1e-6);
}

}  // namespace
}  // namespace ptlab
