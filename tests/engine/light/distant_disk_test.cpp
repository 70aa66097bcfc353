// Tests of the distant disk emitter: cone membership, uniform cone sampling, pdf, edge cases.
#include "engine/light/distant_disk.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/core/rng.h"
#include "engine/core/transform.h"

namespace ptlab {
namespace {

constexpr double kPiD = 3.14159265358979323846;

DistantDiskTable MakeDisk(float theta_a, const Frame& frame = Frame(),
                          const Color3f& radiance = {1, 2, 3}) {
  DistantDiskTable t;
  const StatusOr<uint32_t> row = AddDistantDisk(radiance, theta_a, frame, "disk", &t);
  EXPECT_TRUE(row.ok()) << row.status().message();
  return t;
}

Vec3f AtAngle(double theta_deg, double phi = 0.3) {
  const double t = theta_deg * kPiD / 180;
  return {float(std::sin(t) * std::cos(phi)), float(std::sin(t) * std::sin(phi)),
          float(std::cos(t))};
}

// Nori's sphere_side scene: <rotate axis="1,0,0" angle="45"/> tilts the cone axis (local +z).
Frame RotateX45() {
  const Transform r = Transform::Rotate({1, 0, 0}, 45);
  Frame f;
  f.s = r.ApplyVector({1, 0, 0}), f.t = r.ApplyVector({0, 1, 0}), f.n = r.ApplyVector({0, 0, 1});
  return f;
}

TEST(DistantDisk, RadianceIsConstantInsideTheConeAndZeroOutside) {
  const DistantDiskTable t = MakeDisk(10);
  EXPECT_FLOAT_EQ(DistantDiskRadiance(t, 0, AtAngle(0)).g, 2.0f);
  EXPECT_FLOAT_EQ(DistantDiskRadiance(t, 0, AtAngle(9.99)).b, 3.0f);
  EXPECT_TRUE(IsBlack(DistantDiskRadiance(t, 0, AtAngle(10.01))));
  EXPECT_TRUE(IsBlack(DistantDiskRadiance(t, 0, AtAngle(90))));
  EXPECT_TRUE(IsBlack(DistantDiskRadiance(t, 0, {0, 0, -1})));
}

TEST(DistantDisk, FullSphereIsAConstantEnvironment) {
  const DistantDiskTable t = MakeDisk(180);
  EXPECT_EQ(t.max_chord2[0], INFINITY);
  for (const Vec3f& w : {Vec3f{0, 0, 1}, Vec3f{0, 0, -1}, Vec3f{1, 0, 0}, AtAngle(179.999)}) {
    EXPECT_FLOAT_EQ(DistantDiskRadiance(t, 0, w).r, 1.0f);
    EXPECT_FLOAT_EQ(DistantDiskPdf(t, 0, w), float(1 / (4 * kPiD)));
  }
  // A direction a rounding error longer than 1 is still inside.
  EXPECT_FLOAT_EQ(DistantDiskRadiance(t, 0, {0, 0, -1.0000001f}).r, 1.0f);
}

TEST(DistantDisk, ToWorldRotatesTheAxis) {
  const DistantDiskTable t = MakeDisk(10, RotateX45());
  const float h = std::sqrt(0.5f);
  EXPECT_NEAR(t.to_world[0].n.x, 0.0f, 1e-6f);
  EXPECT_NEAR(t.to_world[0].n.y, -h, 1e-6f);
  EXPECT_NEAR(t.to_world[0].n.z, h, 1e-6f);
  EXPECT_FLOAT_EQ(DistantDiskRadiance(t, 0, {0, -h, h}).r, 1.0f);
  EXPECT_TRUE(IsBlack(DistantDiskRadiance(t, 0, {0, 0, 1})));  // 45° off the axis
}

TEST(DistantDisk, SamplesFillTheConeWithItsUniformPdf) {
  for (const float theta_a : {0.5f, 10.0f, 90.0f, 180.0f}) {
    SCOPED_TRACE(theta_a);
    const DistantDiskTable t = MakeDisk(theta_a, RotateX45());
    const double expected_pdf = 1 / (2 * kPiD * (1 - std::cos(theta_a * kPiD / 180)));
    const double cos_a = std::cos(theta_a * kPiD / 180);
    Pcg32 rng(1, 2);
    double mean_one_minus_cos = 0;
    int outside = 0;
    constexpr int kSamples = 20000;
    for (int k = 0; k < kSamples; ++k) {
      EnvironmentSample s;
      ASSERT_TRUE(SampleDistantDisk(t, 0, {rng.NextFloat(), rng.NextFloat()}, &s));
      ASSERT_NEAR(Length(s.wi), 1.0f, 1e-5f);
      // 1 - cos(angle to the axis) = |wi - axis|² / 2, accurate for narrow cones.
      const Vec3f d = s.wi - t.to_world[0].n;
      const double one_minus_cos = 0.5 * Dot(d, d);
      EXPECT_LE(one_minus_cos, (1 - cos_a) * (1 + 1e-4));
      EXPECT_NEAR(s.pdf, expected_pdf, 1e-5 * expected_pdf);
      EXPECT_EQ(s.radiance.b, 3.0f);
      const float pdf = DistantDiskPdf(t, 0, s.wi);
      if (pdf != s.pdf) ++outside;
      mean_one_minus_cos += one_minus_cos;
    }
    // Only samples within float rounding of the rim may test as outside.
    EXPECT_LE(outside, kSamples / 10000);
    // Uniform in cosθ over [cos thetaA, 1]: the mean of 1 - cosθ is (1 - cos thetaA) / 2.
    EXPECT_NEAR(mean_one_minus_cos / kSamples, 0.5 * (1 - cos_a), 0.01 * (1 - cos_a));
  }
}

TEST(DistantDisk, PdfIntegratesToOne) {
  for (const float theta_a : {5.0f, 10.0f, 90.0f, 180.0f}) {
    const DistantDiskTable t = MakeDisk(theta_a);
    // Midpoint rule in (φ, cosθ) about the axis: exact but for the cell the cone edge cuts.
    const int n = 1000000;
    double sum = 0;
    for (int j = 0; j < n; ++j) {
      const double z = -1 + 2 * (j + 0.5) / n;
      const Vec3f w{float(std::sqrt(1 - z * z)), 0, float(z)};
      sum += DistantDiskPdf(t, 0, w);
    }
    EXPECT_NEAR(sum * 2 * kPiD * (2.0 / n), 1.0, 2e-3) << theta_a;
  }
}

TEST(DistantDisk, BlackDiskNeverSamples) {
  const DistantDiskTable t = MakeDisk(30, Frame(), {0, 0, 0});
  EnvironmentSample s;
  s.pdf = -1;
  EXPECT_FALSE(SampleDistantDisk(t, 0, {0.5f, 0.5f}, &s));
  EXPECT_EQ(s.pdf, -1.0f);
  EXPECT_EQ(DistantDiskPdf(t, 0, {0, 0, 1}), 0.0f);
  EXPECT_TRUE(IsBlack(DistantDiskRadiance(t, 0, {0, 0, 1})));
}

TEST(DistantDisk, RejectsOutOfRangeParameters) {
  DistantDiskTable t;
  // 1e-30 and 1e-5 degrees: cones whose solid angle underflows or is too small to sample
  // (issue 12, finding 9: they gave NaN samples).
  for (const float theta_a : {0.0f, -5.0f, 180.5f, std::nanf(""), 1e-30f, 1e-5f}) {
    const StatusOr<uint32_t> row = AddDistantDisk({1, 1, 1}, theta_a, Frame(), "here", &t);
    ASSERT_FALSE(row.ok());
    EXPECT_NE(row.status().message().find("thetaA"), std::string::npos);
    EXPECT_EQ(row.status().message().rfind("here:", 0), 0u);
  }
  for (const Color3f& radiance :
       {Color3f{-1, 0, 0}, Color3f{0, std::nanf(""), 0}, Color3f{0, 0, INFINITY},
        Color3f{3e38f, 0, 0}}) {
    const StatusOr<uint32_t> row = AddDistantDisk(radiance, 10, Frame(), "here", &t);
    ASSERT_FALSE(row.ok());
    EXPECT_NE(row.status().message().find("radiance"), std::string::npos);
  }
  EXPECT_EQ(t.size(), 0u);
  // The smallest accepted cone still has a finite, positive pdf.
  ASSERT_TRUE(AddDistantDisk({1, 1, 1}, 4e-5f, Frame(), "here", &t).ok());
  EXPECT_GT(t.solid_angle[0], 0.0f);
  EXPECT_TRUE(std::isfinite(1.0f / t.solid_angle[0]));
}

}  // namespace
}  // namespace ptlab
