// Tests of the environment map emitter: convention, bilinear lookup, sampling/pdf, edge cases.
#include "engine/light/environment_map.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/core/rng.h"
#include "engine/image/image_io.h"
#include "engine/image/srgb.h"
#include "tests/test_data.h"

namespace ptlab {
namespace {

constexpr double kPiD = 3.14159265358979323846;

EnvironmentMapTable MakeTable(const Image& image,
                              EnvironmentSampling sampling = EnvironmentSampling::kImportance,
                              const Frame& to_world = Frame(), float scale = 1.0f) {
  EnvironmentMapTable table;
  EnvironmentMapDesc desc;
  desc.sampling = sampling;
  desc.to_world = to_world;
  desc.scale = scale;
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

// World direction at (u, v) under the identity frame.
Vec3f Dir(double u, double v) { return EnvironmentUvToDirection({float(u), float(v)}); }

void ExpectColorNear(const Color3f& a, const Color3f& b, float rel) {
  EXPECT_NEAR(a.r, b.r, rel * std::max(1.0f, std::fabs(b.r)));
  EXPECT_NEAR(a.g, b.g, rel * std::max(1.0f, std::fabs(b.g)));
  EXPECT_NEAR(a.b, b.b, rel * std::max(1.0f, std::fabs(b.b)));
}

void ExpectVecNear(const Vec3f& a, const Vec3f& b, float tol = 1e-6f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// Mitsuba: d = (sinθ sinφ, cosθ, -sinθ cosφ), u = φ/2π, v = θ/π.
TEST(EnvironmentMapConvention, MatchesMitsubasLatLong) {
  ExpectVecNear(Dir(0.0, 0.5), {0, 0, -1});
  ExpectVecNear(Dir(0.25, 0.5), {1, 0, 0});
  ExpectVecNear(Dir(0.5, 0.5), {0, 0, 1});
  ExpectVecNear(Dir(0.75, 0.5), {-1, 0, 0});
  ExpectVecNear(Dir(0.3, 0.0), {0, 1, 0});
  ExpectVecNear(Dir(0.3, 1.0), {0, -1, 0});
  Pcg32 rng(5, 5);
  for (int k = 0; k < 1000; ++k) {
    const Vec2f uv{0.001f + 0.998f * rng.NextFloat(), 0.001f + 0.998f * rng.NextFloat()};
    const Vec2f back = EnvironmentDirectionToUv(EnvironmentUvToDirection(uv));
    EXPECT_NEAR(back.x, uv.x, 2e-6f);
    EXPECT_NEAR(back.y, uv.y, 2e-6f);
  }
  // Length does not matter; the result stays in [0, 1]².
  const Vec2f uv = EnvironmentDirectionToUv({0, 0, -3});
  EXPECT_EQ(uv.x, 0.0f);
  EXPECT_FLOAT_EQ(uv.y, 0.5f);
}

TEST(EnvironmentMapRadiance, PixelCentresReturnThePixels) {
  const Image image = RandomMap(8, 4, 1);
  const EnvironmentMapTable t = MakeTable(image);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 8; ++i)
      ExpectColorNear(EnvironmentRadiance(t, 0, Dir((i + 0.5) / 8, (j + 0.5) / 4)), image.At(i, j),
                      1e-4f);
}

TEST(EnvironmentMapRadiance, InterpolatesBilinearlyAndWrapsInU) {
  const Image image = RandomMap(8, 4, 2);
  const EnvironmentMapTable t = MakeTable(image);
  // Halfway between columns 2 and 3 of row 1.
  ExpectColorNear(EnvironmentRadiance(t, 0, Dir(3.0 / 8, 1.5 / 4)),
                  0.5f * (image.At(2, 1) + image.At(3, 1)), 1e-4f);
  // The seam u = 0 lies halfway between the last and the first column.
  ExpectColorNear(EnvironmentRadiance(t, 0, Dir(0.0, 2.5 / 4)),
                  0.5f * (image.At(7, 2) + image.At(0, 2)), 1e-4f);
  // A quarter of the way from row 1's centre to row 2's, at column 5's centre.
  ExpectColorNear(EnvironmentRadiance(t, 0, Dir(5.5 / 8, 1.75 / 4)),
                  0.75f * image.At(5, 1) + 0.25f * image.At(5, 2), 1e-4f);
  // Above row 0's centre the value is clamped to row 0 (no wrap over the pole).
  ExpectColorNear(EnvironmentRadiance(t, 0, Dir(4.5 / 8, 0.1 / 4)), image.At(4, 0), 1e-4f);
  ExpectColorNear(EnvironmentRadiance(t, 0, Dir(6.5 / 8, 3.9 / 4)), image.At(6, 3), 1e-4f);
}

TEST(EnvironmentMapRadiance, AppliesScaleAndToWorld) {
  const Image image = RandomMap(8, 4, 3);
  // Local +y (up) -> world +z; local x -> world x.
  Frame y_to_z;
  y_to_z.s = {1, 0, 0}, y_to_z.t = {0, 0, 1}, y_to_z.n = {0, -1, 0};
  const EnvironmentMapTable t = MakeTable(image, EnvironmentSampling::kImportance, y_to_z, 2.5f);
  for (int k = 0; k < 20; ++k) {
    const Vec3f local = Dir((k + 0.5) / 20, (k % 7 + 0.5) / 7);
    const Vec3f world = y_to_z.ToWorld(local);
    const EnvironmentMapTable plain = MakeTable(image);
    ExpectColorNear(EnvironmentRadiance(t, 0, world), 2.5f * EnvironmentRadiance(plain, 0, local),
                    1e-4f);
  }
}

TEST(EnvironmentMapRadiance, OneByOneMapIsConstant) {
  Image image(1, 1);
  image.Set(0, 0, {0.25f, 0.5f, 2.0f});
  const EnvironmentMapTable t = MakeTable(image);
  Pcg32 rng(1, 1);
  for (int k = 0; k < 100; ++k) {
    const float u = rng.NextFloat(), v = rng.NextFloat();  // not in Dir's arguments: unsequenced
    const Vec3f w = Dir(u, v);
    const Color3f c = EnvironmentRadiance(t, 0, w);
    EXPECT_FLOAT_EQ(c.r, 0.25f);
    EXPECT_FLOAT_EQ(c.g, 0.5f);
    EXPECT_FLOAT_EQ(c.b, 2.0f);
  }
  for (const Vec3f& pole : {Vec3f{0, 1, 0}, Vec3f{0, -1, 0}})
    EXPECT_FLOAT_EQ(EnvironmentRadiance(t, 0, pole).g, 0.5f);
}

// pdf · sinθ is constant on each pixel cell, so the midpoint rule on a refinement of the pixel
// grid integrates the pdf exactly.
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

TEST(EnvironmentMapSampling, PdfIntegratesToOne) {
  EXPECT_NEAR(IntegratePdf(MakeTable(RandomMap(16, 8, 4)), 3), 1.0, 1e-5);
  Image one(1, 1);
  one.Set(0, 0, {1, 1, 1});
  EXPECT_NEAR(IntegratePdf(MakeTable(one), 64), 1.0, 1e-5);
  // Constant pdf: the midpoint rule's error on ∫ sinθ dθ, (π/n)²/24, needs n = 256 rows.
  EXPECT_NEAR(IntegratePdf(MakeTable(RandomMap(16, 8, 4), EnvironmentSampling::kUniform), 32), 1.0,
              1e-5);
}

// The density on pixel (i, j) is P(i, j) · W·H / (2π² sinθ), where P is the cell's mean bilinear
// luminance × sinθ(row centre), normalised: recomputed here independently.
TEST(EnvironmentMapSampling, PdfIsLuminanceTimesSinThetaOverTheJacobian) {
  const int w = 16, h = 8;
  const Image image = RandomMap(w, h, 5);
  const EnvironmentMapTable t = MakeTable(image);
  std::vector<double> p(size_t(w) * h);
  double total = 0;
  const double k[3] = {0.125, 0.75, 0.125};
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      double mean = 0;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const Color3f c = image.At((i + di + w) % w, std::clamp(j + dj, 0, h - 1));
          mean += k[dj + 1] * k[di + 1] * (0.212671 * c.r + 0.715160 * c.g + 0.072169 * c.b);
        }
      total += (p[size_t(j) * w + i] = mean * std::sin(kPiD * (j + 0.5) / h));
    }
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      // Off the cell centre, to see the 1/sinθ of the exact pdf (not the row centre's).
      const double u = (i + 0.3) / w, v = (j + 0.8) / h;
      const double expected =
          p[size_t(j) * w + i] / total * w * h / (2 * kPiD * kPiD * std::sin(kPiD * v));
      EXPECT_NEAR(EnvironmentPdf(t, 0, Dir(u, v)), expected, 1e-5 * expected) << i << "," << j;
    }
}

TEST(EnvironmentMapSampling, SamplesAgreeWithPdfAndRadiance) {
  for (const EnvironmentSampling sampling :
       {EnvironmentSampling::kImportance, EnvironmentSampling::kUniform}) {
    Frame rotated(Normalize(Vec3f{0.3f, -0.5f, 0.8f}));
    const EnvironmentMapTable t = MakeTable(RandomMap(16, 8, 6), sampling, rotated);
    Pcg32 rng(7, 7);
    int pdf_mismatch = 0, radiance_mismatch = 0;
    constexpr int kSamples = 100000;
    for (int k = 0; k < kSamples; ++k) {
      EnvironmentSample s;
      ASSERT_TRUE(SampleEnvironment(t, 0, {rng.NextFloat(), rng.NextFloat()}, &s));
      ASSERT_TRUE(std::isfinite(s.pdf) && s.pdf > 0);
      ASSERT_NEAR(Length(s.wi), 1.0f, 1e-5f);
      const float pdf = EnvironmentPdf(t, 0, s.wi);
      if (!(std::fabs(pdf - s.pdf) <= 1e-4f * s.pdf)) ++pdf_mismatch;
      const Color3f l = EnvironmentRadiance(t, 0, s.wi);
      if (!(std::fabs(l.g - s.radiance.g) <= 1e-4f * std::max(1.0f, l.g))) ++radiance_mismatch;
    }
    // Pdf(wi) and Radiance(wi) recompute (u, v) from wi: only samples within float rounding of a
    // pixel edge may differ.
    EXPECT_LE(pdf_mismatch, kSamples / 2000);
    EXPECT_LE(radiance_mismatch, kSamples / 2000);
  }
}

// Importance sampling alone (no MIS) is unbiased: the distribution covers every cell where
// the bilinear radiance is non-zero, including the neighbours of a single hot pixel.
TEST(EnvironmentMapSampling, LightSamplingAloneIsUnbiasedForAHotPixel) {
  Image image(16, 8);
  image.Set(5, 3, {10, 20, 30});
  const EnvironmentMapTable t = MakeTable(image);
  // Reference ∫ L dω by the midpoint rule on a fine grid.
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
    const double f = s.radiance.g / s.pdf;
    sum += f, sum2 += f * f;
  }
  const double mean = sum / kSamples;
  const double stderr_ = std::sqrt((sum2 / kSamples - mean * mean) / kSamples);
  EXPECT_NEAR(mean, reference, 4 * stderr_ + 1e-3 * reference);
  EXPECT_LT(stderr_, 0.01 * reference);  // and the estimator is good, not just unbiased
}

TEST(EnvironmentMapSampling, HotPixelSamplesStayInItsNeighbourhood) {
  Image image(32, 16);
  image.Set(0, 15, {100, 0, 0});  // at the u seam, in the bottom (pole) row
  const EnvironmentMapTable t = MakeTable(image);
  Pcg32 rng(9, 9);
  for (int k = 0; k < 10000; ++k) {
    EnvironmentSample s;
    ASSERT_TRUE(SampleEnvironment(t, 0, {rng.NextFloat(), rng.NextFloat()}, &s));
    ASSERT_TRUE(std::isfinite(s.pdf) && s.pdf > 0);
    const Vec2f uv = EnvironmentDirectionToUv(s.wi);
    const int i = std::min(int(uv.x * 32), 31), j = std::min(int(uv.y * 16), 15);
    EXPECT_TRUE(i == 31 || i == 0 || i == 1) << i;
    EXPECT_TRUE(j == 14 || j == 15) << j;
  }
}

TEST(EnvironmentMapSampling, OneByOneMapSamplesUniformlyInUv) {
  Image image(1, 1);
  image.Set(0, 0, {1, 2, 3});
  const EnvironmentMapTable t = MakeTable(image);
  Pcg32 rng(10, 10);
  for (int k = 0; k < 1000; ++k) {
    const Vec2f u{rng.NextFloat(), rng.NextFloat()};
    EnvironmentSample s;
    ASSERT_TRUE(SampleEnvironment(t, 0, u, &s));
    const Vec2f uv = EnvironmentDirectionToUv(s.wi);
    EXPECT_NEAR(uv.x, u.x, 1e-5f);
    EXPECT_NEAR(uv.y, u.y, 1e-5f);
    // sinθ of the direction itself (exact near both poles, unlike sin(π v)).
    const double sin_theta = std::hypot(double(s.wi.x), double(s.wi.z));
    EXPECT_NEAR(s.pdf, 1.0 / (2 * kPiD * kPiD * sin_theta), 1e-5 * s.pdf);
    EXPECT_FLOAT_EQ(s.radiance.b, 3.0f);
  }
}

TEST(EnvironmentMapSampling, PolesGiveFiniteSamplesAndZeroPdfExactlyOnThem) {
  const EnvironmentMapTable t = MakeTable(RandomMap(16, 8, 11));
  for (const float uy : {0.0f, 1e-7f, 0x1.fffffep-1f}) {
    for (const float ux : {0.0f, 0.5f, 0x1.fffffep-1f}) {
      EnvironmentSample s;
      ASSERT_TRUE(SampleEnvironment(t, 0, {ux, uy}, &s));
      EXPECT_TRUE(std::isfinite(s.pdf) && s.pdf > 0) << ux << "," << uy;
      EXPECT_TRUE(IsFinite(s.radiance));
      if (uy < 0.5f) {
        EXPECT_GT(s.wi.y, 0.9999f);
      } else {
        EXPECT_LT(s.wi.y, -0.9999f);
      }
      EXPECT_GT(EnvironmentPdf(t, 0, s.wi), 0.0f);
    }
  }
  EXPECT_EQ(EnvironmentPdf(t, 0, {0, 1, 0}), 0.0f);
  EXPECT_EQ(EnvironmentPdf(t, 0, {0, -1, 0}), 0.0f);
  const float near_pole = EnvironmentPdf(t, 0, Normalize(Vec3f{1e-6f, 1, 0}));
  EXPECT_TRUE(std::isfinite(near_pole) && near_pole > 0);
  EXPECT_TRUE(IsFinite(EnvironmentRadiance(t, 0, {0, 1, 0})));
}

TEST(EnvironmentMapEdgeCases, BlackMapNeverSamplesAndHasZeroPdf) {
  for (const EnvironmentSampling sampling :
       {EnvironmentSampling::kImportance, EnvironmentSampling::kUniform}) {
    for (const float scale : {1.0f, 0.0f}) {
      const Image image = scale == 0.0f ? RandomMap(8, 4, 12) : Image(8, 4);
      const EnvironmentMapTable t = MakeTable(image, sampling, Frame(), scale);
      EXPECT_EQ(t.luminance_integral[0], 0.0f);
      Pcg32 rng(13, 13);
      for (int k = 0; k < 1000; ++k) {
        EnvironmentSample s;
        s.pdf = -1;
        const Vec2f u{rng.NextFloat(), rng.NextFloat()};
        EXPECT_FALSE(SampleEnvironment(t, 0, u, &s));
        EXPECT_EQ(s.pdf, -1.0f);  // untouched
        const Vec3f w = Dir(u.x, u.y);
        EXPECT_EQ(EnvironmentPdf(t, 0, w), 0.0f);
        EXPECT_TRUE(IsBlack(EnvironmentRadiance(t, 0, w)));
      }
    }
  }
}

TEST(EnvironmentMapEdgeCases, UniformSamplingHasTheSpherePdf) {
  const EnvironmentMapTable t = MakeTable(RandomMap(8, 4, 14), EnvironmentSampling::kUniform);
  EnvironmentSample s;
  ASSERT_TRUE(SampleEnvironment(t, 0, {0.3f, 0.6f}, &s));
  EXPECT_FLOAT_EQ(s.pdf, float(1 / (4 * kPiD)));
  EXPECT_FLOAT_EQ(EnvironmentPdf(t, 0, {0, 1, 0}), float(1 / (4 * kPiD)));
  EXPECT_TRUE(t.marginal_cdf.empty() && t.conditional_cdf.empty());  // pays for no distribution
}

TEST(EnvironmentMapEdgeCases, SeveralMapsShareTheTable) {
  EnvironmentMapTable t;
  ASSERT_TRUE(AddEnvironmentMap(RandomMap(8, 4, 15), {}, "a", &t).ok());
  EnvironmentMapDesc uniform;
  uniform.sampling = EnvironmentSampling::kUniform;
  ASSERT_TRUE(AddEnvironmentMap(RandomMap(3, 2, 16), uniform, "b", &t).ok());
  const StatusOr<uint32_t> third = AddEnvironmentMap(RandomMap(5, 7, 17), {}, "c", &t);
  ASSERT_TRUE(third.ok());
  EXPECT_EQ(*third, 2u);
  EXPECT_EQ(t.size(), 3u);
  const EnvironmentMapTable alone = MakeTable(RandomMap(5, 7, 17));
  for (int k = 0; k < 50; ++k) {
    const Vec3f w = Dir((k + 0.5) / 50, (k % 9 + 0.5) / 9);
    EXPECT_EQ(EnvironmentPdf(t, 2, w), EnvironmentPdf(alone, 0, w));
    EXPECT_EQ(EnvironmentRadiance(t, 2, w).r, EnvironmentRadiance(alone, 0, w).r);
  }
}

// EnvironmentRadianceAndPdf is EnvironmentRadiance and EnvironmentPdf bit for bit: importance,
// uniform and black maps, a rotated frame, random directions, the poles, the u seam and axes.
TEST(EnvironmentMapRadiance, RadianceAndPdfTogetherAreBothBitForBit) {
  const auto bits = [](float v) { return std::bit_cast<uint32_t>(v); };
  Image black(4, 2);
  const EnvironmentMapTable tables[] = {
      MakeTable(RandomMap(16, 8, 21)),
      MakeTable(RandomMap(9, 5, 22), EnvironmentSampling::kUniform),
      MakeTable(RandomMap(7, 3, 23), EnvironmentSampling::kImportance,
                Frame(Normalize(Vec3f{0.3f, 1, -0.2f}))),
      MakeTable(black)};
  std::vector<Vec3f> dirs = {{0, 1, 0},  {0, -1, 0}, {1, 0, 0},         {-1, 0, 0},
                             {0, 0, 1},  {0, 0, -1}, {1e-30f, 1, 0},   {0, 1, -1e-30f},
                             {-1e-7f, 0, -1}, {1e-7f, 0, -1}};
  Pcg32 rng(24, 2);
  for (int k = 0; k < 2000; ++k) {
    const float u = rng.NextFloat(), v = rng.NextFloat();  // not in Dir's arguments: unsequenced
    dirs.push_back(Dir(u, v));
  }
  for (const EnvironmentMapTable& t : tables) {
    for (const Vec3f& w : dirs) {
      Color3f L;
      const float pdf = EnvironmentRadianceAndPdf(t, 0, w, &L);
      const Color3f L1 = EnvironmentRadiance(t, 0, w);
      ASSERT_EQ(bits(pdf), bits(EnvironmentPdf(t, 0, w)));
      ASSERT_EQ(bits(L.r), bits(L1.r));
      ASSERT_EQ(bits(L.g), bits(L1.g));
      ASSERT_EQ(bits(L.b), bits(L1.b));
    }
  }
}

// Pixel policy: NaN, ±Inf and negative values are rejected with a message; -0 is fine.
TEST(EnvironmentMapPolicy, RejectsNonFiniteAndNegativePixels) {
  struct Case {
    float value;
    const char* word;
  };
  for (const Case& c : {Case{std::nanf(""), "NaN"}, Case{INFINITY, "infinite"},
                        Case{-INFINITY, "infinite"}, Case{-0.5f, "negative"}}) {
    Image image = RandomMap(6, 3, 18);
    image.rgb[(size_t(2) * 6 + 4) * 3 + 1] = c.value;  // pixel (4, 2), G
    image.rgb[(size_t(0) * 6 + 5) * 3 + 0] = c.value;  // pixel (5, 0), R: the first one
    EnvironmentMapTable t;
    const StatusOr<uint32_t> row = AddEnvironmentMap(image, {}, "sky.exr", &t);
    ASSERT_FALSE(row.ok()) << c.word;
    const std::string& m = row.status().message();
    for (const std::string& w : {std::string("sky.exr"), std::string(c.word), std::string("(5, 0)"),
                                 std::string(" R "), std::string("2 of 18 pixels")})
      EXPECT_NE(m.find(w), std::string::npos) << "'" << w << "' missing from: " << m;
    EXPECT_EQ(t.size(), 0u);
    EXPECT_TRUE(t.texels.empty());
  }
  Image image = RandomMap(6, 3, 18);
  image.rgb[7] = -0.0f;
  EnvironmentMapTable t;
  EXPECT_TRUE(AddEnvironmentMap(image, {}, "sky.exr", &t).ok());
}

TEST(EnvironmentMapPolicy, RejectsBadScaleAndEmptyImages) {
  EnvironmentMapTable t;
  EnvironmentMapDesc desc;
  for (const float scale : {-1.0f, std::nanf(""), INFINITY}) {
    desc.scale = scale;
    const StatusOr<uint32_t> row = AddEnvironmentMap(RandomMap(2, 2, 19), desc, "s.hdr", &t);
    ASSERT_FALSE(row.ok());
    EXPECT_NE(row.status().message().find("scale"), std::string::npos);
  }
  Image huge(2, 1);
  huge.Set(1, 0, {3e38f, 0, 0});
  desc.scale = 10.0f;
  StatusOr<uint32_t> row = AddEnvironmentMap(huge, desc, "s.hdr", &t);
  ASSERT_FALSE(row.ok());
  EXPECT_NE(row.status().message().find("exceeds the largest radiance"), std::string::npos);
  // Issue 12, finding 9: finite values near FLT_MAX at scale 1 overflowed the sampling sums.
  desc.scale = 1.0f;
  row = AddEnvironmentMap(huge, desc, "s.hdr", &t);
  ASSERT_FALSE(row.ok());
  EXPECT_NE(row.status().message().find("exceeds the largest radiance"), std::string::npos);
  row = AddEnvironmentMap(Image(), {}, "s.hdr", &t);
  ASSERT_FALSE(row.ok());
  EXPECT_NE(row.status().message().find("empty"), std::string::npos);
  EXPECT_EQ(t.size(), 0u);
}

TEST(EnvironmentMapDebugImage, ChannelsAreTheCdfsAndTheNormalisedPixelProbability) {
  const EnvironmentMapTable t = MakeTable(RandomMap(8, 4, 20));
  const Image image = EnvironmentPdfDebugImage(t, 0);
  ASSERT_EQ(image.width, 8);
  ASSERT_EQ(image.height, 4);
  const Distribution2DView d = EnvironmentDistribution(t, 0);
  float max_b = 0;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 8; ++i) {
      const Color3f c = image.At(i, j);
      EXPECT_EQ(c.r, d.marginal_cdf[j + 1]);
      EXPECT_EQ(c.g, d.Row(j)[i + 1]);
      EXPECT_NEAR(c.b / Distribution2DCellPdf(d, i, j),
                  image.At(0, 0).b / Distribution2DCellPdf(d, 0, 0), 1e-5f);
      max_b = std::max(max_b, c.b);
    }
  EXPECT_EQ(max_b, 1.0f);
  EXPECT_EQ(image.At(7, 3).r, 1.0f);
  EXPECT_EQ(image.At(7, 3).g, 1.0f);
  const Image black = EnvironmentPdfDebugImage(MakeTable(Image(4, 2)), 0);
  for (float v : black.rgb) EXPECT_EQ(v, 0.0f);
}

std::string TempDir() {
  const std::string dir = PTLAB_BINARY_DIR "/light_test_tmp";
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(EnvironmentMapDebugImage, WritesThePngOfAMapFile) {
  const std::string map = TempDir() + "/debug_map.exr", png = TempDir() + "/debug_pdf.png";
  const Image source = RandomMap(16, 8, 21);
  ASSERT_TRUE(WriteExr(map, source).ok());
  std::filesystem::remove(png);
  const StatusOr<Image> pdf = EnvironmentPdfImage(map, LowercaseExtension(png) == ".png");
  ASSERT_TRUE(pdf.ok()) << pdf.status().message();
  const Status written = WriteImage(png, *pdf);
  ASSERT_TRUE(written.ok()) << written.message();
  const StatusOr<Image> read = ReadImage(png);
  ASSERT_TRUE(read.ok()) << read.status().message();
  const Image expected = EnvironmentPdfDebugImage(MakeTable(source), 0);
  ASSERT_EQ(read->width, 16);
  ASSERT_EQ(read->height, 8);
  // Bytes = round(255 · value): no sRGB curve on the stored CDFs.
  for (size_t k = 0; k < expected.rgb.size(); ++k)
    EXPECT_NEAR(LinearToSrgb(read->rgb[k]) * 255.0f, expected.rgb[k] * 255.0f, 0.51f) << k;
}

TEST(EnvironmentMapDebugImage, FailsClearlyOnBadInput) {
  const std::string png = TempDir() + "/never_written.png";
  std::filesystem::remove(png);
  StatusOr<Image> pdf = EnvironmentPdfImage(TempDir() + "/no_such_map.exr", true);
  ASSERT_FALSE(pdf.ok());
  Status s = pdf.status();
  EXPECT_NE(s.message().find("no_such_map.exr"), std::string::npos) << s.message();
  Image bad = RandomMap(4, 2, 22);
  bad.rgb[4] = std::nanf("");
  const std::string map = TempDir() + "/nan_map.exr";
  ASSERT_TRUE(WriteExr(map, bad).ok());
  pdf = EnvironmentPdfImage(map, true);
  ASSERT_FALSE(pdf.ok());
  s = pdf.status();
  EXPECT_NE(s.message().find("NaN"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("nan_map.exr"), std::string::npos) << s.message();
}

TEST(EnvironmentMapRealData, VeniceSunsetLoadsAndSamplesFinitely) {
  const std::string path = test_data::Path("envmaps/venice_sunset_1k.hdr");
  PTLAB_REQUIRE_DATA(path);
  const StatusOr<Image> image = ReadImage(path);
  ASSERT_TRUE(image.ok()) << image.status().message();
  const EnvironmentMapTable t = MakeTable(*image);
  EXPECT_EQ(t.width[0], 1024);
  EXPECT_EQ(t.height[0], 512);
  EXPECT_GT(t.luminance_integral[0], 0.0f);
  Pcg32 rng(23, 23);
  for (int k = 0; k < 10000; ++k) {
    EnvironmentSample s;
    ASSERT_TRUE(SampleEnvironment(t, 0, {rng.NextFloat(), rng.NextFloat()}, &s));
    ASSERT_TRUE(std::isfinite(s.pdf) && s.pdf > 0 && IsFinite(s.radiance));
  }
}

}  // namespace
}  // namespace ptlab
