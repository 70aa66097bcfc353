// Tests of EnvironmentRows::kAtPoles (Mitsuba 3's envmap rows: row 0 on the north pole, row
// H − 1 on the south pole): the lookup, the cell grid, and that sampling stays normalised and
// unbiased. kCentred is tested in environment_map_test.cpp.
#include <cmath>

#include <gtest/gtest.h>

#include "engine/core/rng.h"
#include "engine/light/environment_map.h"

namespace ptlab {
namespace {

constexpr double kPiD = 3.14159265358979323846;

EnvironmentMapTable AtPoles(const Image& image) {
  EnvironmentMapTable table;
  EnvironmentMapDesc desc;
  desc.rows = EnvironmentRows::kAtPoles;
  const StatusOr<uint32_t> row = AddEnvironmentMap(image, desc, "test.exr", &table);
  EXPECT_TRUE(row.ok()) << row.status().message();
  return table;
}

Image RandomMap(int w, int h, uint64_t seed) {
  Pcg32 rng(seed, 1);
  Image image(w, h);
  for (float& v : image.rgb) v = 4.0f * rng.NextFloat() * rng.NextFloat();
  return image;
}

Vec3f Dir(double u, double v) { return EnvironmentUvToDirection({float(u), float(v)}); }

void ExpectColorNear(const Color3f& a, const Color3f& b, float rel) {
  EXPECT_NEAR(a.r, b.r, rel * std::max(1.0f, std::fabs(b.r)));
  EXPECT_NEAR(a.g, b.g, rel * std::max(1.0f, std::fabs(b.g)));
  EXPECT_NEAR(a.b, b.b, rel * std::max(1.0f, std::fabs(b.b)));
}

TEST(EnvironmentRowsAtPoles, PixelRowsSitOnThePolesAndEvenlyBetween) {
  const Image image = RandomMap(8, 5, 1);
  const EnvironmentMapTable t = AtPoles(image);
  EXPECT_EQ(EnvironmentCellRows(t, 0), 4);
  // Rows 0 and 4 a hair (v ± 1e-6) off the poles, where φ (so u) still means something.
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 8; ++i) {
      const double v = j == 0 ? 1e-6 : (j == 4 ? 1 - 1e-6 : j / 4.0);
      ExpectColorNear(EnvironmentRadiance(t, 0, Dir((i + 0.5) / 8, v)), image.At(i, j), 1e-4f);
    }
  // Halfway between rows 1 and 2 (v = 1.5/4), at column 3's centre; and the u seam halfway
  // between the last and the first column, on row 3.
  ExpectColorNear(EnvironmentRadiance(t, 0, Dir(3.5 / 8, 1.5 / 4)),
                  0.5f * (image.At(3, 1) + image.At(3, 2)), 1e-4f);
  ExpectColorNear(EnvironmentRadiance(t, 0, Dir(0.0, 3.0 / 4)),
                  0.5f * (image.At(7, 3) + image.At(0, 3)), 1e-4f);
  // The exact poles: atan2(0, -0) = π, so u = ½, halfway between columns 3 and 4 of row 0 / 4.
  ExpectColorNear(EnvironmentRadiance(t, 0, {0, 1, 0}), 0.5f * (image.At(3, 0) + image.At(4, 0)),
                  1e-4f);
  ExpectColorNear(EnvironmentRadiance(t, 0, {0, -1, 0}),
                  0.5f * (image.At(3, 4) + image.At(4, 4)), 1e-4f);
}

TEST(EnvironmentRowsAtPoles, OneRowIsConstantInTheta) {
  const Image image = RandomMap(4, 1, 2);
  const EnvironmentMapTable t = AtPoles(image);
  EXPECT_EQ(EnvironmentCellRows(t, 0), 1);
  for (double v : {1e-6, 0.3, 0.5, 1 - 1e-6})
    ExpectColorNear(EnvironmentRadiance(t, 0, Dir(2.5 / 4, v)), image.At(2, 0), 1e-4f);
}

// pdf · sinθ is constant on each cell (W × (H − 1)), so the midpoint rule on a refinement of
// the cell grid integrates the pdf exactly.
double IntegratePdf(const EnvironmentMapTable& t, int refine) {
  const int nu = t.width[0] * refine, nv = EnvironmentCellRows(t, 0) * refine;
  double sum = 0;
  for (int j = 0; j < nv; ++j) {
    const double theta = kPiD * (j + 0.5) / nv;
    for (int i = 0; i < nu; ++i)
      sum += double(EnvironmentPdf(t, 0, Dir((i + 0.5) / nu, (j + 0.5) / nv))) * std::sin(theta);
  }
  return sum * (kPiD / nv) * (2 * kPiD / nu);
}

TEST(EnvironmentRowsAtPoles, PdfIntegratesToOne) {
  EXPECT_NEAR(IntegratePdf(AtPoles(RandomMap(16, 9, 4)), 3), 1.0, 1e-5);
  EXPECT_NEAR(IntegratePdf(AtPoles(RandomMap(5, 2, 5)), 8), 1.0, 1e-5);
  EXPECT_NEAR(IntegratePdf(AtPoles(RandomMap(3, 1, 6)), 16), 1.0, 1e-5);
}

// One hot pixel on the pole row (row 0) or inside: wherever the radiance is > 0 the pdf is > 0,
// and light sampling alone estimates ∫ L dω (4 standard errors, seed fixed: fails with
// probability ~6e-5 if unbiased).
void ExpectUnbiasedForHotPixel(int hx, int hy) {
  Image image(16, 9);
  image.Set(hx, hy, {10, 20, 30});
  const EnvironmentMapTable t = AtPoles(image);
  const int nu = 16 * 32, nv = 8 * 32;
  double reference = 0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double u = (i + 0.5) / nu, v = (j + 0.5) / nv;
      const Vec3f w = Dir(u, v);
      const float l = EnvironmentRadiance(t, 0, w).g;
      if (l > 0) {
        EXPECT_GT(EnvironmentPdf(t, 0, w), 0.0f) << u << "," << v;
      }
      reference += l * std::sin(kPiD * v);
    }
  reference *= (kPiD / nv) * (2 * kPiD / nu);
  Pcg32 rng(8, 8);
  constexpr int kSamples = 200000;
  double sum = 0, sum2 = 0;
  for (int k = 0; k < kSamples; ++k) {
    EnvironmentSample s;
    ASSERT_TRUE(SampleEnvironment(t, 0, {rng.NextFloat(), rng.NextFloat()}, &s));
    ASSERT_TRUE(std::isfinite(s.pdf) && s.pdf > 0);
    const double f = s.radiance.g / s.pdf;
    sum += f, sum2 += f * f;
  }
  const double mean = sum / kSamples;
  const double stderr_ = std::sqrt((sum2 / kSamples - mean * mean) / kSamples);
  EXPECT_NEAR(mean, reference, 4 * stderr_ + 1e-3 * reference);
  EXPECT_LT(stderr_, 0.02 * reference);
}

TEST(EnvironmentRowsAtPoles, LightSamplingAloneIsUnbiasedForAHotPixel) {
  ExpectUnbiasedForHotPixel(5, 3);
  ExpectUnbiasedForHotPixel(0, 0);   // on the north pole row, at the u seam
  ExpectUnbiasedForHotPixel(15, 8);  // on the south pole row, at the u seam
}

}  // namespace
}  // namespace ptlab
