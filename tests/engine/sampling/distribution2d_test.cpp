// Tests of the piecewise-constant 1-D and 2-D distributions: CDFs, Sample/Pdf agreement, edges.
#include "engine/sampling/distribution2d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/core/rng.h"

namespace ptlab {
namespace {

TEST(Distribution1D, BuildsANormalisedCdf) {
  const float w[4] = {1, 0, 3, 4};
  float cdf[5];
  EXPECT_EQ(BuildPiecewiseConstantCdf(w, 4, cdf), 8.0);
  const float expected[5] = {0, 0.125f, 0.125f, 0.5f, 1};
  for (int i = 0; i < 5; ++i) EXPECT_FLOAT_EQ(cdf[i], expected[i]) << i;
  EXPECT_FLOAT_EQ(PiecewiseConstant1DPdf(cdf, 4, 0.1f), 0.5f);
  EXPECT_EQ(PiecewiseConstant1DPdf(cdf, 4, 0.3f), 0.0f);
  EXPECT_FLOAT_EQ(PiecewiseConstant1DPdf(cdf, 4, 0.6f), 1.5f);
  EXPECT_FLOAT_EQ(PiecewiseConstant1DPdf(cdf, 4, 1.0f), 2.0f);  // x = 1 belongs to the last bin
  EXPECT_EQ(PiecewiseConstant1DPdf(cdf, 4, -0.01f), 0.0f);
  EXPECT_EQ(PiecewiseConstant1DPdf(cdf, 4, 1.01f), 0.0f);
}

TEST(Distribution1D, EmptyDistributionNeverSamples) {
  const std::vector<float> w(5, 0.0f);
  const Distribution1D d(w.data(), 5);
  EXPECT_EQ(d.total, 0.0);
  float x = -7, pdf = -7;
  for (float u : {0.0f, 0.5f, 0.99f}) {
    EXPECT_FALSE(d.Sample(u, &x, &pdf));
    EXPECT_EQ(d.Pdf(u), 0.0f);
  }
  EXPECT_EQ(x, -7.0f);  // untouched
  EXPECT_EQ(pdf, -7.0f);
}

// Every sample lands in the bin its pdf says and never in a zero bin, including u = 0, the
// largest float below 1, the CDF values themselves and NaN; x is monotone in u.
TEST(Distribution1D, SamplePdfMatchesPdfEverywhere) {
  const float w[6] = {0, 2, 0, 0, 1e-3f, 5};
  const Distribution1D d(w, 6);
  std::vector<float> sweep;
  for (int k = 0; k < 10000; ++k) sweep.push_back(float(k) / 10000.0f);
  std::vector<float> us = {0.0f, 0x1.fffffep-1f, std::nanf("")};
  for (float c : d.cdf) us.push_back(c), us.push_back(std::nextafter(c, 0.0f));
  us.insert(us.end(), sweep.begin(), sweep.end());
  for (float u : us) {
    float x, pdf;
    ASSERT_TRUE(d.Sample(u, &x, &pdf)) << u;
    EXPECT_GE(x, 0.0f);
    EXPECT_LT(x, 1.0f);
    EXPECT_GT(pdf, 0.0f) << "u " << u << " x " << x;
    EXPECT_EQ(pdf, d.Pdf(x)) << "u " << u << " x " << x;
    const int bin = PiecewiseConstantBin(x, 6);
    EXPECT_TRUE(bin == 1 || bin == 4 || bin == 5) << bin;
  }
  float last_x = -1;
  for (float u : sweep) {
    float x, pdf;
    ASSERT_TRUE(d.Sample(u, &x, &pdf));
    EXPECT_GE(x, last_x) << u;
    last_x = x;
  }
}

TEST(Distribution1D, InvertsTheCdfLinearlyWithinABin) {
  const float w[2] = {1, 3};
  const Distribution1D d(w, 2);
  float x, pdf;
  ASSERT_TRUE(d.Sample(0.125f, &x, &pdf));  // half of bin 0's mass
  EXPECT_FLOAT_EQ(x, 0.25f);
  EXPECT_FLOAT_EQ(pdf, 0.5f);
  ASSERT_TRUE(d.Sample(0.625f, &x, &pdf));  // half of bin 1's mass
  EXPECT_FLOAT_EQ(x, 0.75f);
  EXPECT_FLOAT_EQ(pdf, 1.5f);
}

TEST(Distribution1D, SingleBinIsUniform) {
  const float w = 2.5f;
  const Distribution1D d(&w, 1);
  float x, pdf;
  ASSERT_TRUE(d.Sample(0.3f, &x, &pdf));
  EXPECT_FLOAT_EQ(x, 0.3f);
  EXPECT_EQ(pdf, 1.0f);
}

Distribution2D RandomDistribution(int nu, int nv, int zero_row) {
  Pcg32 rng(3, 4);
  std::vector<float> w(size_t(nu) * nv);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      w[size_t(j) * nu + i] = (j == zero_row || (i + j) % 4 == 0) ? 0.0f : rng.NextFloat();
  return Distribution2D(w.data(), nu, nv);
}

TEST(Distribution2D, CellProbabilitiesAreTheNormalisedWeights) {
  const int nu = 9, nv = 6;
  Pcg32 rng(3, 4);
  std::vector<float> w(size_t(nu) * nv);
  for (float& x : w) x = rng.NextFloat();
  w[5] = 0;
  double total = 0;
  for (float x : w) total += x;
  const Distribution2D d(w.data(), nu, nv);
  EXPECT_NEAR(d.total, total, 1e-9 * total);
  double sum = 0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double p = Distribution2DCellPdf(d.view(), i, j) / double(nu * nv);
      EXPECT_NEAR(p, w[size_t(j) * nu + i] / total, 1e-6) << i << "," << j;
      sum += p;
    }
  EXPECT_NEAR(sum, 1.0, 1e-6);
}

TEST(Distribution2D, SamplesAvoidEmptyRowsAndCellsAndAgreeWithPdf) {
  const Distribution2D d = RandomDistribution(7, 5, 2);
  Pcg32 rng(1, 2);
  for (int k = 0; k < 20000; ++k) {
    const Vec2f u{rng.NextFloat(), rng.NextFloat()};
    Vec2f p;
    float pdf;
    int column, row;
    ASSERT_TRUE(SampleDistribution2D(d.view(), u, &p, &pdf, &column, &row));
    ASSERT_TRUE(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1);
    EXPECT_EQ(column, PiecewiseConstantBin(p.x, 7));
    EXPECT_EQ(row, PiecewiseConstantBin(p.y, 5));
    EXPECT_NE(row, 2);
    EXPECT_NE((column + row) % 4, 0);
    EXPECT_GT(pdf, 0.0f);
    EXPECT_EQ(pdf, Distribution2DPdf(d.view(), p));
  }
  EXPECT_EQ(Distribution2DPdf(d.view(), {0.5f, 0.5f}), 0.0f);  // row 2
  EXPECT_EQ(Distribution2DPdf(d.view(), {0.5f, 1.5f}), 0.0f);  // outside
  EXPECT_EQ(Distribution2DPdf(d.view(), {std::nanf(""), 0.5f}), 0.0f);
}

TEST(Distribution2D, AllZeroWeightsAreEmpty) {
  const std::vector<float> w(12, 0.0f);
  const Distribution2D d(w.data(), 4, 3);
  EXPECT_FALSE(d.view().NonEmpty());
  Vec2f p{-1, -1};
  float pdf = -1;
  EXPECT_FALSE(SampleDistribution2D(d.view(), {0.3f, 0.7f}, &p, &pdf));
  EXPECT_EQ(p.x, -1.0f);
  EXPECT_EQ(pdf, -1.0f);
  EXPECT_EQ(Distribution2DPdf(d.view(), {0.3f, 0.7f}), 0.0f);
}

TEST(Distribution2D, SingleCellIsUniform) {
  const float w = 0.7f;
  const Distribution2D d(&w, 1, 1);
  Vec2f p;
  float pdf;
  ASSERT_TRUE(SampleDistribution2D(d.view(), {0.25f, 0.75f}, &p, &pdf));
  EXPECT_FLOAT_EQ(p.x, 0.25f);
  EXPECT_FLOAT_EQ(p.y, 0.75f);
  EXPECT_EQ(pdf, 1.0f);
}

// A single non-zero cell among a million: all samples land in it, with pdf = nu·nv.
TEST(Distribution2D, SingleHotCellInALargeGrid) {
  const int nu = 1024, nv = 1024;
  std::vector<float> w(size_t(nu) * nv, 0.0f);
  w[size_t(700) * nu + 33] = 1e-30f;
  const Distribution2D d(w.data(), nu, nv);
  Pcg32 rng(9, 9);
  for (int k = 0; k < 1000; ++k) {
    Vec2f p;
    float pdf;
    int column, row;
    ASSERT_TRUE(SampleDistribution2D(d.view(), {rng.NextFloat(), rng.NextFloat()}, &p, &pdf,
                                     &column, &row));
    EXPECT_EQ(column, 33);
    EXPECT_EQ(row, 700);
    EXPECT_EQ(pdf, float(nu) * float(nv));
  }
}

}  // namespace
}  // namespace ptlab
