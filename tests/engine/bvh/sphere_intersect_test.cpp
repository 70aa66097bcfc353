// Ray-sphere intersection (the scalar oracle): rays from outside and inside, grazing rays,
// tiny and huge spheres far from the origin, the open (t_min, t_max) interval, and the
// sphere ids beside the triangle rows.
#include "engine/bvh/sphere_intersect.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/bvh/intersect1.h"
#include "engine/bvh/ray_offset.h"
#include "engine/core/rng.h"
#include "tests/engine/bvh/test_meshes.h"

namespace ptlab {
namespace {

bool Hit1(const Vec3f& c, float r, const Ray& ray, float* t) {
  return IntersectSphere1(c.x, c.y, c.z, r, ray, ray.t_max, t);
}

// |p - c| - r in double for the float hit point p = o + t d.
double SurfaceDistance(const Vec3f& c, float r, const Ray& ray, float t) {
  const double px = double(ray.o.x) + double(t) * ray.d.x - c.x;
  const double py = double(ray.o.y) + double(t) * ray.d.y - c.y;
  const double pz = double(ray.o.z) + double(t) * ray.d.z - c.z;
  return std::sqrt(px * px + py * py + pz * pz) - double(r);
}

// The entry root in double precision of the (float) inputs.
double EntryInDouble(const Vec3f& c, float r, const Ray& ray) {
  const double fx = double(ray.o.x) - c.x, fy = double(ray.o.y) - c.y, fz = double(ray.o.z) - c.z;
  const double a =
      double(ray.d.x) * ray.d.x + double(ray.d.y) * ray.d.y + double(ray.d.z) * ray.d.z;
  const double b = fx * ray.d.x + fy * ray.d.y + fz * ray.d.z;
  const double cc = fx * fx + fy * fy + fz * fz - double(r) * r;
  return (-b - std::sqrt(b * b - a * cc)) / a;
}

TEST(SphereIntersect, OutsideInsideAndTheOpenInterval) {
  float t = -1;
  const Ray ray{{0, 0, -5}, {0, 0, 1}, 0.0f, 1e30f};
  ASSERT_TRUE(Hit1({0, 0, 0}, 1, ray, &t));
  EXPECT_EQ(t, 4.0f);
  // Non-unit directions scale t.
  ASSERT_TRUE(Hit1({0, 0, 0}, 1, Ray{{0, 0, -5}, {0, 0, 2}, 0.0f, 1e30f}, &t));
  EXPECT_EQ(t, 2.0f);
  // From inside (a glass sphere's refracted rays): the exit.
  ASSERT_TRUE(Hit1({0, 0, 0}, 1, Ray{{0, 0.5f, 0}, {0, 1, 0}, 0.0f, 1e30f}, &t));
  EXPECT_EQ(t, 0.5f);
  ASSERT_TRUE(Hit1({1, 2, 3}, 2, Ray{{1, 2, 3}, {0, 0, -4}, 0.0f, 1e30f}, &t));
  EXPECT_EQ(t, 0.5f);
  // t_max and t_min bound the open interval: t_max = 4 excludes the entry and the exit (6).
  EXPECT_FALSE(Hit1({0, 0, 0}, 1, Ray{ray.o, ray.d, 0.0f, 4.0f}, &t));
  ASSERT_TRUE(Hit1({0, 0, 0}, 1, Ray{ray.o, ray.d, 0.0f, std::nextafter(4.0f, 5.0f)}, &t));
  EXPECT_EQ(t, 4.0f);
  ASSERT_TRUE(Hit1({0, 0, 0}, 1, Ray{ray.o, ray.d, 4.0f, 1e30f}, &t));  // past the entry
  EXPECT_EQ(t, 6.0f);
  EXPECT_FALSE(Hit1({0, 0, 0}, 1, Ray{ray.o, ray.d, 6.0f, 1e30f}, &t));
  EXPECT_FALSE(Hit1({0, 0, 0}, 1, Ray{ray.o, ray.d, 0.0f, 0.0f}, &t));
  // Behind the origin, and pointing away.
  EXPECT_FALSE(Hit1({0, 0, 0}, 1, Ray{{0, 0, -5}, {0, 0, -1}, 0.0f, 1e30f}, &t));
  EXPECT_FALSE(Hit1({0, 0, -10}, 1, ray, &t));
}

TEST(SphereIntersect, GrazingRaysHitInsideAndMissOutside) {
  float t = 0;
  for (int k = 4; k <= 22; ++k) {
    SCOPED_TRACE(k);
    const float eps = std::ldexp(1.0f, -k);
    // A ray along x at height y = 1 -/+ eps past the unit sphere.
    const Ray inside{{-3, 1 - eps, 0}, {1, 0, 0}, 0.0f, 1e30f};
    ASSERT_TRUE(Hit1({0, 0, 0}, 1, inside, &t));
    const double y = 1.0 - double(eps);
    const double t_exact = 3.0 - std::sqrt(1.0 - y * y);
    // The entry moves as sqrt(eps) with y: the error stays within float resolution of 3
    // times the conditioning 1/sqrt(2 eps).
    EXPECT_NEAR(t, t_exact, 4 * 2.4e-7 * 3 / std::sqrt(2 * double(eps)));
    EXPECT_FALSE(Hit1({0, 0, 0}, 1, Ray{{-3, 1 + eps, 0}, {1, 0, 0}, 0.0f, 1e30f}, &t));
  }
}

TEST(SphereIntersect, TinyAndHugeSpheresFarFromTheOrigin) {
  float t = 0;
  // A sphere of radius 1e-3 at distance ~1.7e3: b² and a c agree to 12 digits, so the
  // textbook discriminant b² - a c is all rounding error in float; r² - |f - (b/a) d|² is not.
  const Vec3f c{1000, 1000, 1000};
  const float r = 1e-3f;
  for (const float off : {0.0f, 5e-4f, 9e-4f}) {
    SCOPED_TRACE(off);
    const Vec3f target{c.x, c.y + off, c.z};
    const Vec3f d = Normalize(target - Vec3f{0, 0, 0});
    const Ray ray{{0, 0, 0}, d, 0.0f, 1e30f};
    ASSERT_TRUE(Hit1(c, r, ray, &t));
    const double exact = EntryInDouble(c, r, ray);
    const double ulp = std::nextafter(float(exact), 1e30f) - float(exact);
    EXPECT_NEAR(t, exact, 4 * ulp);
  }
  EXPECT_FALSE(Hit1(c, r, Ray{{0, 0, 0}, Normalize(Vec3f{1000, 1000.002f, 1000}), 0, 1e30f}, &t));
  // A ground sphere of radius 1e4 one unit below a point, seen straight down and obliquely,
  // and from just inside: the hit point lies on the surface to the float precision of 1e4.
  const Vec3f g{0, -1e4f, 0};
  for (const Ray& ray : {Ray{{0, 1, 0}, {0, -1, 0}, 0.0f, 1e30f},
                         Ray{{0, 1, 0}, Normalize(Vec3f{1, -1, 0.5f}), 0.0f, 1e30f},
                         Ray{{0, -0.5f, 0}, {0, 1, 0}, 0.0f, 1e30f}}) {
    ASSERT_TRUE(Hit1(g, 1e4f, ray, &t));
    EXPECT_LT(std::fabs(SurfaceDistance(g, 1e4f, ray, t)), 2e-3);  // ulp(1e4) = 9.8e-4
  }
}

// Secondary rays leave a sphere from its surface point pushed off by OffsetRayOrigin (as the
// integrators spawn them): outward they never meet the sphere again, inward (glass) they meet
// its far side (a point on the sphere at least half the chord 2 r |cos θ| away), never the
// surface they start on. Spheres far from the origin included, down to radii 30 times the
// offset (256 ulps of the coordinates, which also moves the origin sideways).
TEST(SphereIntersect, SpawnedRaysLeaveOrCrossTheSphere) {
  Pcg32 rng(77, 3);
  const struct {
    Vec3f c;
    float r;
  } spheres[] = {{{0, 0, 0}, 1},
                 {{1000, -500, 200}, 0.5f},
                 {{0, 0, 0}, 1e-3f},
                 {{0, -1e4f, 0}, 1e4f},
                 {{3, 4, 5}, 100}};
  for (const auto& sp : spheres) {
    SCOPED_TRACE(sp.r);
    int crossed = 0;
    for (int i = 0; i < 20000; ++i) {
      Vec3f n = bvh_test::UniformSphereDirection(rng);
      // As MakeInteraction places a sphere hit.
      const Vec3f p = ProjectOntoSphere(sp.c + n * sp.r, sp.c, sp.r, &n);
      Vec3f d = bvh_test::UniformSphereDirection(rng);
      const float cos_theta = Dot(d, n);
      if (std::fabs(cos_theta) < 0.1f) continue;
      const bool inward = cos_theta < 0;
      const Ray ray{OffsetRayOrigin(p, inward ? -n : n), d, 0.0f, 1e30f};
      float t = 0;
      const bool hit = Hit1(sp.c, sp.r, ray, &t);
      ASSERT_EQ(hit, inward) << "cos " << cos_theta;
      if (!hit) continue;
      ++crossed;
      const double chord = 2.0 * double(sp.r) * std::fabs(double(cos_theta));
      const Vec3f q = ray.At(t);
      ASSERT_NEAR(Length(q - sp.c), sp.r, 1e-6 * (Length(sp.c) + sp.r));
      ASSERT_GT(Length(q - p), 0.5 * chord);
    }
    EXPECT_GT(crossed, 8000);
  }
}

TEST(SphereIntersect, SpheresBesideTheBvhAndTheirHitIds) {
  TriangleTable tris;
  tris.Append({-5, -5, 2}, {5, -5, 2}, {0, 5, 2});  // a wall at z = 2
  SphereTable spheres;
  spheres.Append({0, 0, 0}, 1, MaterialRef::Make(MaterialTag::kDiffuse, 3));
  spheres.Append({0, 0, 0.5f}, 1, MaterialRef::Make(MaterialTag::kMirror, 0));
  const Bvh bvh = BuildBvh(tris, spheres);
  ASSERT_EQ(bvh.spheres.size(), 2u);
  Hit hit;
  // From z = -5: the first sphere's entry at z = -1.
  ASSERT_TRUE(Intersect1(bvh, Ray{{0, 0, -5}, {0, 0, 1}, 0.0f, 1e30f}, &hit));
  EXPECT_TRUE(IsSphereHit(hit.prim));
  EXPECT_EQ(SphereHitRow(hit.prim), 0u);
  EXPECT_EQ(hit.t, 4.0f);
  EXPECT_EQ(hit.b1, 0.0f);
  // From inside both: the second sphere's exit (z = 1.5) comes before the first's (z = 1).
  ASSERT_TRUE(Intersect1(bvh, Ray{{0, 0, 1.2f}, {0, 0, 1}, 0.0f, 1e30f}, &hit));
  EXPECT_EQ(SphereHitRow(hit.prim), 1u);
  // The wall before any sphere.
  ASSERT_TRUE(Intersect1(bvh, Ray{{0, 0, 1.8f}, {0, 0, 1}, 0.0f, 1e30f}, &hit));
  EXPECT_FALSE(IsSphereHit(hit.prim));
  EXPECT_EQ(hit.prim, 0u);
  EXPECT_TRUE(Occluded1(bvh, Ray{{0, 0, -5}, {0, 0, 1}, 0.0f, 0.5f}) == false);
  EXPECT_TRUE(Occluded1(bvh, Ray{{0, 0, -5}, {0, 0, 1}, 0.0f, 4.5f}));
  EXPECT_TRUE(Occluded1(bvh, Ray{{1, -2, -5}, {0, 0, 1}, 0.0f, 1e30f}));  // the wall only
  EXPECT_FALSE(Occluded1(bvh, Ray{{9, 9, -5}, {0, 0, 1}, 0.0f, 1e30f}));
  // Spheres without any triangle.
  const Bvh only = BuildBvh(TriangleTable{}, spheres);
  ASSERT_TRUE(Intersect1(only, Ray{{0, 0, -5}, {0, 0, 1}, 0.0f, 1e30f}, &hit));
  EXPECT_EQ(SphereHitRow(hit.prim), 0u);
  EXPECT_TRUE(Occluded1(only, Ray{{0, 0, -5}, {0, 0, 1}, 0.0f, 1e30f}));
}

}  // namespace
}  // namespace ptlab
