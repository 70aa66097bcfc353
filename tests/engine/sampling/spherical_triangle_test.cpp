// Solid-angle sampling of triangles: the solid angle, the points it returns, and hard cases
// (degenerate, grazing, tiny, nearly hemispherical triangles) that must fall back, never NaN.
#include "engine/sampling/spherical_triangle.h"

#include <cmath>

#include <gtest/gtest.h>

#include "engine/core/rng.h"

namespace ptlab {
namespace {

constexpr double kPiD = 3.14159265358979323846;

TEST(SphericalTriangle, OctantIsAnEighthOfTheSphere) {
  EXPECT_NEAR(SphericalTriangleArea({1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}), kPiD / 2, 1e-6);
  // Seen from its other side and from a shifted origin: the same.
  EXPECT_NEAR(SphericalTriangleArea({0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {0, 0, 0}), kPiD / 2, 1e-6);
  EXPECT_NEAR(SphericalTriangleArea({3, 2, 2}, {2, 3, 2}, {2, 2, 3}, {2, 2, 2}), kPiD / 2, 1e-6);
}

TEST(SphericalTriangle, SmallTriangleIsAreaTimesCosineOverDistanceSquared) {
  // A triangle of area 0.5e-4 at distance 10, tilted by 60°: Ω ≈ A cos θ / d².
  const float h = 0.01f;
  const Vec3f c{0, 0, 10};
  const Vec3f u{h * 0.5f, 0, h * 0.8660254f}, v{0, h, 0};
  const float omega = SphericalTriangleArea(c, c + u, c + v, {0, 0, 0});
  EXPECT_NEAR(omega, 0.5 * h * h * 0.5 / 100.0, 1e-3 * 0.5 * h * h * 0.5 / 100.0);
}

TEST(SphericalTriangle, SamplesLieOnTheTriangleWithItsDensity) {
  const Vec3f v0{-0.6f, -0.5f, 1.0f}, v1{0.7f, -0.4f, 1.1f}, v2{0.1f, 0.8f, 0.9f};
  const Vec3f p{0.05f, -0.1f, -0.2f};
  const float omega = SphericalTriangleArea(v0, v1, v2, p);
  Pcg32 rng(1, 2);
  for (int i = 0; i < 100000; ++i) {
    const Vec2f u{rng.NextFloat(), rng.NextFloat()};
    SphericalTriangleSample s;
    ASSERT_TRUE(SampleSphericalTriangle(v0, v1, v2, p, u, &s));
    ASSERT_GE(s.b1, 0.0f);
    ASSERT_GE(s.b2, 0.0f);
    ASSERT_LE(s.b1 + s.b2, 1.0f + 1e-6f);
    const Vec3f q = v0 * (1 - s.b1 - s.b2) + v1 * s.b1 + v2 * s.b2;
    ASSERT_LT(Length(q - s.p), 1e-5f);
    ASSERT_FLOAT_EQ(s.pdf, 1.0f / omega);
  }
}

TEST(SphericalTriangle, CornersOfTheSquareMapToTheTriangle) {
  // u = (0, ·) gives vertex 1 (the arc from b to c_hat collapses when the sub-area is 0) and
  // u = (·, 0) gives vertex 1 too (z = 1: the direction of b).
  const Vec3f v0{1, 0, 1}, v1{0, 1, 1}, v2{-1, -1, 1};
  SphericalTriangleSample s;
  ASSERT_TRUE(SampleSphericalTriangle(v0, v1, v2, {0, 0, 0}, {0.3f, 0.0f}, &s));
  EXPECT_LT(Length(s.p - v1), 1e-5f);
  ASSERT_TRUE(SampleSphericalTriangle(v0, v1, v2, {0, 0, 0}, {0.0f, 0.7f}, &s));
  // Sub-area 0: c_hat = v0's direction, so the point lies on the edge v1-v0.
  EXPECT_NEAR(Length(s.p - v1) + Length(s.p - v0), Length(v1 - v0), 1e-5f) << "on the edge v1-v0";
}

TEST(SphericalTriangle, HardCasesFallBackWithoutNaN) {
  SphericalTriangleSample s;
  const Vec2f corners[] = {{0, 0}, {0, 0.9999999f}, {0.9999999f, 0}, {0.9999999f, 0.9999999f},
                           {0.5f, 0.5f}};
  struct Case {
    Vec3f v0, v1, v2, p;
    const char* what;
  };
  const Case cases[] = {
      {{0, 0, 1}, {1, 0, 1}, {2, 0, 1}, {0, 0, 0}, "collinear vertices"},
      {{0, 0, 1}, {0, 0, 1}, {1, 0, 1}, {0, 0, 0}, "two equal vertices"},
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2f, 0.2f, 0}, "point inside the triangle's plane"},
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, "point at a vertex"},
      {{0, 0, 1}, {1e-4f, 0, 1}, {0, 1e-4f, 1}, {0, 0, 0}, "tiny: 5e-9 sr"},
      {{-1e4f, -1e4f, 1e-3f}, {1e4f, -1e4f, 1e-3f}, {0, 1e4f, 1e-3f}, {0, 0, 0},
       "huge and close: nearly a hemisphere"},
      {{0, 0, 1}, {1, 0, 1.0001f}, {0.5f, 1e-6f, 1}, {0, 0, 0}, "sliver"},
      {{1, 0, 1e-6f}, {0, 1, 1e-6f}, {-1, -1, 1e-6f}, {0, 0, 0}, "grazing, around the point"},
  };
  for (const Case& c : cases) {
    const float omega = SphericalTriangleArea(c.v0, c.v1, c.v2, c.p);
    EXPECT_TRUE(std::isfinite(omega)) << c.what;
    for (const Vec2f& u : corners) {
      const bool ok = SampleSphericalTriangle(c.v0, c.v1, c.v2, c.p, u, &s);
      if (!ok) continue;  // refused: the caller samples by area
      EXPECT_TRUE(UsesSphericalTriangleSampling(omega)) << c.what << ": sampled out of range";
      EXPECT_TRUE(std::isfinite(s.p.x) && std::isfinite(s.p.y) && std::isfinite(s.p.z)) << c.what;
      EXPECT_TRUE(std::isfinite(s.pdf) && s.pdf > 0) << c.what;
    }
  }
  // The tiny and the nearly hemispherical triangles are left to area sampling.
  EXPECT_FALSE(SampleSphericalTriangle({0, 0, 1}, {1e-4f, 0, 1}, {0, 1e-4f, 1}, {0, 0, 0},
                                       {0.5f, 0.5f}, &s));
  EXPECT_FALSE(SampleSphericalTriangle({-1e4f, -1e4f, 1e-3f}, {1e4f, -1e4f, 1e-3f},
                                       {0, 1e4f, 1e-3f}, {0, 0, 0}, {0.5f, 0.5f}, &s));
}

}  // namespace
}  // namespace ptlab
