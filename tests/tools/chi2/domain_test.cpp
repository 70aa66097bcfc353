// Unit tests of the chi-square lab's domains: containment, (φ, cosθ) mapping, disk clipping.
#include "tools/chi2/domain.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ptlab {
namespace {

TEST(Chi2Domain, GridWidthDoublesOnTheSphere) {
  EXPECT_EQ(Chi2GridWidth(Chi2Domain::UnitSquare(), 51), 51);
  EXPECT_EQ(Chi2GridWidth(Chi2Domain::Disk(), 51), 51);
  EXPECT_EQ(Chi2GridWidth(Chi2Domain::Sphere(), 51), 102);
  EXPECT_EQ(Chi2GridWidth(Chi2Domain::Hemisphere(), 51), 102);
}

TEST(Chi2Domain, ContainsUpToRounding) {
  const Chi2Domain box = Chi2Domain::Box(-1, 0, 1, 2);
  EXPECT_TRUE(Chi2Contains(box, {-1, 0, 0}));
  EXPECT_TRUE(Chi2Contains(box, {1, 2, 0}));
  EXPECT_FALSE(Chi2Contains(box, {1.001f, 1, 0}));
  EXPECT_FALSE(Chi2Contains(box, {0, -0.001f, 0}));
  EXPECT_FALSE(Chi2Contains(box, {NAN, 1, 0}));
  EXPECT_FALSE(Chi2Contains(box, {0, 1, INFINITY}));
  const Chi2Domain disk = Chi2Domain::Disk();
  EXPECT_TRUE(Chi2Contains(disk, {std::cos(1.0f), std::sin(1.0f), 0}));
  EXPECT_FALSE(Chi2Contains(disk, {0.71f, 0.71f, 0}));
  const Chi2Domain sphere = Chi2Domain::Sphere(), hemi = Chi2Domain::Hemisphere();
  EXPECT_TRUE(Chi2Contains(sphere, {0, 0.6f, -0.8f}));
  EXPECT_FALSE(Chi2Contains(sphere, {0, 0.6f, -0.9f}));  // not unit length
  EXPECT_FALSE(Chi2Contains(hemi, {0, 0.6f, -0.8f}));
  EXPECT_TRUE(Chi2Contains(hemi, {1, 0, 0}));
}

TEST(Chi2Domain, SphericalParametersRoundTrip) {
  const Chi2Domain sphere = Chi2Domain::Sphere();
  for (double phi : {0.0, 0.5, 3.0, 3.2, 6.0}) {
    for (double z : {-1.0, -0.3, 0.0, 0.7, 1.0}) {
      const Chi2Point w = Chi2FromParam(sphere, {phi, z});
      EXPECT_NEAR(w.x * w.x + w.y * w.y + w.z * w.z, 1.0, 1e-6);
      EXPECT_NEAR(w.z, z, 1e-7);
      if (std::fabs(z) < 1) {
        const Chi2Param q = Chi2ToParam(sphere, w);
        EXPECT_NEAR(q.x, phi, 1e-6) << phi << " " << z;
        EXPECT_NEAR(q.y, z, 1e-7);
      }
    }
  }
  // φ in [0, 2π): -y directions map to φ > π.
  EXPECT_NEAR(Chi2ToParam(sphere, {0, -1, 0}).x, 1.5 * Chi2Domain::kPiD, 1e-6);
  const Chi2Param planar = Chi2ToParam(Chi2Domain::Disk(), {0.25f, -0.5f, 0});
  EXPECT_EQ(planar.x, 0.25);
  EXPECT_EQ(planar.y, -0.5);
}

TEST(Chi2Domain, OnlyTheDiskClipsItsSupport) {
  double lo, hi;
  Chi2SupportY(Chi2Domain::Disk(), 0.6, -1, 1, &lo, &hi);
  EXPECT_NEAR(lo, -0.8, 1e-15);
  EXPECT_NEAR(hi, 0.8, 1e-15);
  Chi2SupportY(Chi2Domain::Disk(), 0.6, 0.5, 0.9, &lo, &hi);
  EXPECT_NEAR(lo, 0.5, 1e-15);
  EXPECT_NEAR(hi, 0.8, 1e-15);
  Chi2SupportY(Chi2Domain::Disk(), 0.99, 0.5, 0.9, &lo, &hi);
  EXPECT_GE(lo, hi);  // the segment misses the disk
  Chi2SupportY(Chi2Domain::UnitSquare(), 0.99, 0.5, 0.9, &lo, &hi);
  EXPECT_EQ(lo, 0.5);
  EXPECT_EQ(hi, 0.9);
}

}  // namespace
}  // namespace ptlab
