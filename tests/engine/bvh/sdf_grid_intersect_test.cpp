// Ray-sdfgrid intersection (the scalar oracle) and the sdfgrid normals: exact roots of a linear
// field, hits on the zero set with no earlier sign change along the ray (checked by a dense
// march of the interpolant, SdfGridValueAt, independent of the per-cell cubic), misses that
// cross no zero, rays along grid planes, rays leaving the surface, empty cells, grazing rays,
// a rotated and scaled grid, and the hit ids beside the spheres'.
#include "engine/bvh/sdf_grid_intersect.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/bvh/intersect1.h"
#include "engine/bvh/ray_offset.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/core/rng.h"
#include "engine/render/sdf_grid_normal.h"
#include "tests/engine/bvh/test_meshes.h"

namespace ptlab {
namespace {

using bvh_test::UniformInBox;
using bvh_test::UniformSphereDirection;

const MaterialRef kMat = MaterialRef::Make(MaterialTag::kDiffuse, 0);

// An n³ grid of f(object point).
template <class F>
SdfGridTable Grid(uint32_t n, F f, const Transform& to_world = Transform(),
                  SdfNormals how = SdfNormals::kSmooth) {
  std::vector<float> v;
  for (uint32_t k = 0; k < n; ++k)
    for (uint32_t j = 0; j < n; ++j)
      for (uint32_t i = 0; i < n; ++i)
        v.push_back(f(double(i) / (n - 1), double(j) / (n - 1), double(k) / (n - 1)));
  SdfGridTable g;
  g.Append(n, n, n, v, to_world, kMat, how);
  return g;
}

SdfGridTable BallGrid(uint32_t n, const Transform& to_world = Transform()) {
  return Grid(
      n,
      [](double x, double y, double z) {
        return float(std::sqrt((x - 0.5) * (x - 0.5) + (y - 0.45) * (y - 0.45) +
                               (z - 0.55) * (z - 0.55)) -
                     0.3);
      },
      to_world);
}

double ObjectValue(const SdfGridTable& g, const Vec3f& world) {
  const Matrix4& m = g.to_world[0].inverse_matrix();
  double p[3];
  for (int r = 0; r < 3; ++r)
    p[r] = double(m.m[r][0]) * world.x + double(m.m[r][1]) * world.y +
           double(m.m[r][2]) * world.z + double(m.m[r][3]);
  return SdfGridValueAt(g, 0, p);
}

// The interpolant along the ray, in double, at t.
double ValueAlong(const SdfGridTable& g, const Ray& ray, double t) {
  const Matrix4& m = g.to_world[0].inverse_matrix();
  double p[3];
  for (int r = 0; r < 3; ++r)
    p[r] = double(m.m[r][0]) * (ray.o.x + t * ray.d.x) + double(m.m[r][1]) * (ray.o.y + t * ray.d.y) +
           double(m.m[r][2]) * (ray.o.z + t * ray.d.z) + double(m.m[r][3]);
  for (double c : p)
    if (c < 0.0 || c > 1.0) return NAN;  // outside the box: no surface
  return SdfGridValueAt(g, 0, p);
}

// Whether the interpolant changes sign (strictly) between samples of [a, b] (n samples).
bool SignChangeIn(const SdfGridTable& g, const Ray& ray, double a, double b, int n) {
  int last = 0;
  for (int s = 0; s <= n; ++s) {
    const double f = ValueAlong(g, ray, a + (b - a) * s / n);
    if (std::isnan(f)) continue;
    const int sign = f > 0 ? 1 : (f < 0 ? -1 : 0);
    if (sign != 0 && last != 0 && sign != last) return true;
    if (sign != 0) last = sign;
  }
  return false;
}

TEST(SdfGridIntersect, LinearFieldRootIsExactToFloat) {
  // f = x − 0.37 on any grid: the trilinear interpolant is exact, the zero set the plane.
  const SdfGridTable g = Grid(7, [](double x, double, double) { return float(x - 0.37); });
  Pcg32 rng(7, 1);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    Ray ray;
    ray.o = UniformInBox(rng, {-1.0f, -0.2f, -0.2f}, {-0.1f, 1.2f, 1.2f});
    ray.d = UniformInBox(rng, {0.1f, -1, -1}, {1, 1, 1});
    float t = 0;
    const double exact = (0.37 - double(ray.o.x)) / double(ray.d.x);
    const double y = ray.o.y + exact * ray.d.y, z = ray.o.z + exact * ray.d.z;
    const bool inside = y > 1e-6 && y < 1 - 1e-6 && z > 1e-6 && z < 1 - 1e-6;
    const bool got = IntersectSdfGrid1(g, 0, ray, ray.t_max, &t);
    if (std::fabs(y) < 1e-6 || std::fabs(y - 1) < 1e-6 || std::fabs(z) < 1e-6 ||
        std::fabs(z - 1) < 1e-6)
      continue;  // on the box's edge: either answer
    ASSERT_EQ(got, inside) << i;
    if (!got) continue;
    ++hits;
    // The float rounding of the root: within one ulp of the exact t (the values are floats of
    // x − 0.37, so the root itself moves by their rounding: a few 1e-8 in x).
    EXPECT_NEAR(t, exact, 4e-7 * std::fabs(exact) + 1e-7 / std::fabs(ray.d.x)) << i;
  }
  EXPECT_GT(hits, 1500);
}

// Random rays at a ball-shaped field: every hit on the zero set with no sign change before it;
// every miss with no sign change in (t_min, t_max) at all.
void CheckAgainstMarch(const SdfGridTable& g, const std::vector<Ray>& rays, int* hits_out) {
  int hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Ray& ray = rays[i];
    float t = 0;
    const bool got = IntersectSdfGrid1(g, 0, ray, ray.t_max, &t);
    const double t_end = std::min(double(ray.t_max), 100.0);
    if (got) {
      ++hits;
      ASSERT_GT(t, ray.t_min);
      ASSERT_LT(t, ray.t_max);
      // On the surface: the interpolant at o + t d (in double) within the float rounding of t.
      const double f = ValueAlong(g, ray, t);
      const double df = std::fabs(ValueAlong(g, ray, t * (1 + 1e-6) + 1e-9) - f) + 1e-12;
      EXPECT_LT(std::fabs(f), 4 * df + 1e-9) << "ray " << i << " t " << t;
      // Nothing nearer: no strict sign change over [t_min, t (1 − 1e-5)].
      EXPECT_FALSE(SignChangeIn(g, ray, ray.t_min, double(t) * (1 - 1e-5), 4000)) << "ray " << i;
    } else {
      EXPECT_FALSE(SignChangeIn(g, ray, ray.t_min, t_end, 4000)) << "ray " << i;
    }
  }
  *hits_out = hits;
}

TEST(SdfGridIntersect, RandomRaysHitTheZeroSetFirst) {
  const SdfGridTable g = BallGrid(9);
  Pcg32 rng(2026, 3);
  std::vector<Ray> rays;
  for (int i = 0; i < 4000; ++i) {
    Ray ray;
    if (i % 3 == 0) {  // from outside at the box
      ray.o = UniformInBox(rng, {-1, -1, -1}, {2, 2, 2});
      ray.d = UniformInBox(rng, {0, 0, 0}, {1, 1, 1}) - ray.o;
    } else if (i % 3 == 1) {  // from inside the box, any direction (some inside the ball)
      ray.o = UniformInBox(rng, {0, 0, 0}, {1, 1, 1});
      ray.d = UniformSphereDirection(rng);
    } else {  // cut short by t_max
      ray.o = UniformInBox(rng, {-1, -1, -1}, {2, 2, 2});
      ray.d = UniformInBox(rng, {0.3f, 0.3f, 0.3f}, {0.7f, 0.7f, 0.7f}) - ray.o;
      ray.t_max = rng.NextFloat();
    }
    rays.push_back(ray);
  }
  int hits = 0;
  CheckAgainstMarch(g, rays, &hits);
  EXPECT_GT(hits, 1000);
}

TEST(SdfGridIntersect, RaysAlongGridPlanesAndThroughGridPoints) {
  const SdfGridTable g = BallGrid(9);
  std::vector<Ray> rays;
  for (int a = 0; a <= 8; ++a)
    for (int b = 0; b <= 8; ++b) {
      const float u = a / 8.0f, v = b / 8.0f;
      rays.push_back({{-0.5f, u, v}, {1, 0, 0}});           // along grid lines
      rays.push_back({{u, -0.5f, v}, {0, 1, 0}});
      rays.push_back({{u, v, 1.5f}, {0, 0, -1}});
      rays.push_back({{-0.5f, u, 0.3f}, {1, 0, 0.37f}});  // in the plane y = u
      rays.push_back({{-0.5f, -0.5f, -0.5f}, {1, u + 0.01f, v + 0.01f}});
    }
  int hits = 0;
  CheckAgainstMarch(g, rays, &hits);
  EXPECT_GT(hits, 60);
}

TEST(SdfGridIntersect, GrazingRaysAndRotatedScaledGrid) {
  const Transform place = Transform::Translate({3, -2, 1}) *
                          Transform::Rotate({0.3f, 1.0f, -0.2f}, 50.0f) *
                          Transform::Scale({2.0f, 0.5f, 1.5f});
  const SdfGridTable g = BallGrid(12, place);
  Pcg32 rng(99, 5);
  std::vector<Ray> rays;
  for (int i = 0; i < 3000; ++i) {
    // In object space: past the ball's centre at 0.3 (1 ± 2^-e), then placed.
    const Vec3f w = UniformSphereDirection(rng);
    const Vec3f side = Normalize(Cross(w, UniformSphereDirection(rng)));
    const float e = std::ldexp(1.0f, -int(rng.NextUint() % 20));
    const float dist = 0.3f * (rng.NextFloat() < 0.5f ? 1.0f - e : 1.0f + e);
    const Vec3f c{0.5f, 0.45f, 0.55f};
    const Vec3f o = c + side * dist - w * 2.0f;
    const Vec3f d = w;
    rays.push_back({place.ApplyPoint(o), place.ApplyVector(d)});
  }
  int hits = 0;
  CheckAgainstMarch(g, rays, &hits);
  EXPECT_GT(hits, 300);  // half of them pass outside the surface
}

TEST(SdfGridIntersect, RaysLeavingTheSurfaceDoNotHitItAgain) {
  const SdfGridTable g = BallGrid(10);
  Pcg32 rng(5, 8);
  int checked = 0;
  for (int i = 0; i < 3000; ++i) {
    Ray ray{UniformInBox(rng, {-1, -1, -1}, {2, 2, 2}), {}};
    ray.d = Vec3f{0.5f, 0.45f, 0.55f} + UniformSphereDirection(rng) * 0.1f - ray.o;
    float t = 0;
    if (!IntersectSdfGrid1(g, 0, ray, ray.t_max, &t)) continue;
    const Vec3f p = ray.At(t);
    Vec3f ng, ns;
    SdfGridNormals(g, 0, p, &ng, &ns);
    // The offset origins lie on their side of the surface: outside along ng, inside against it.
    const Vec3f o_out = OffsetRayOrigin(p, ng), o_in = OffsetRayOrigin(p, -ng);
    EXPECT_GT(ObjectValue(g, o_out), 0.0) << i;
    EXPECT_LT(ObjectValue(g, o_in), 0.0) << i;
    // Leaving outward (a convex ball): nothing to hit.
    Vec3f w = UniformSphereDirection(rng);
    if (Dot(w, ng) < 0) w = -w;
    const Ray out{o_out, w};
    EXPECT_FALSE(IntersectSdfGrid1(g, 0, out, out.t_max, &t)) << i;
    // Leaving inward: a hit there is the far side (inside all the way to it).
    const Ray in{o_in, -w};
    float t_in = 0;
    EXPECT_TRUE(IntersectSdfGrid1(g, 0, in, in.t_max, &t_in)) << i;
    EXPECT_LT(ValueAlong(g, in, 0.5 * t_in), 0.0) << i;
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

TEST(SdfGridIntersect, EmptyCellsAndFieldsWithoutSurface) {
  // Positive everywhere but one corner cell with a negative value: only that cell can hold the
  // surface; rays through the rest miss.
  SdfGridTable g = Grid(5, [](double x, double y, double z) {
    return float(x + y + z < 0.2 ? -1.0 : 1.0);
  });
  float t = 0;
  EXPECT_FALSE(IntersectSdfGrid1(g, 0, {{-1, 0.6f, 0.6f}, {1, 0, 0}}, 1e30f, &t));
  // At y = z = 0.02 the corner's weight is 0.92² = 0.8464: f = 1 − 2 · 0.8464 (1 − x / 0.25)
  // is negative where the ray enters the box and crosses zero at x = 0.25 (1 − 0.5 / 0.8464).
  EXPECT_TRUE(IntersectSdfGrid1(g, 0, {{-1, 0.02f, 0.02f}, {1, 0, 0}}, 1e30f, &t));
  EXPECT_NEAR(t, 1.0 + 0.25 * (1.0 - 0.5 / (0.92 * 0.92)), 1e-5);
  const SdfGridTable none = Grid(4, [](double, double, double) { return 1.0f; });
  EXPECT_FALSE(IntersectSdfGrid1(none, 0, {{-1, 0.5f, 0.5f}, {1, 0, 0}}, 1e30f, &t));
  // Degenerate rays: zero direction components outside the box, t_max before the box.
  EXPECT_FALSE(IntersectSdfGrid1(g, 0, {{-1, 2, 0.05f}, {1, 0, 0}}, 1e30f, &t));
  EXPECT_FALSE(IntersectSdfGrid1(g, 0, {{-1, 0.1f, 0.05f}, {1, 0, 0}}, 0.5f, &t));
}

TEST(SdfGridIntersect, HitIdsBesideSpheresAndClosestAmongGrids) {
  EXPECT_TRUE(IsSdfGridHit(0x80000000u | kSdfGridHitBit | 3));
  EXPECT_FALSE(IsSphereHit(0x80000000u | kSdfGridHitBit | 3));
  EXPECT_TRUE(IsSphereHit(kSphereHitBit | 3));
  EXPECT_FALSE(IsSdfGridHit(kSphereHitBit | 3));
  EXPECT_FALSE(IsSdfGridHit(kNoHit));
  EXPECT_FALSE(IsSphereHit(kNoHit));
  EXPECT_EQ(SdfGridHitRow(0x80000000u | kSdfGridHitBit | 7), 7u);
  // Two grids along x; the nearer wins whatever its row.
  SdfGridTable g = BallGrid(8, Transform::Translate({5, 0, 0}));
  const SdfGridTable near = BallGrid(8);
  g.AppendPlaced(near, 0, Transform(), kMat);
  const Ray ray{{-2, 0.45f, 0.55f}, {1, 0, 0}};
  float t_max = 1e30f;
  uint32_t prim = kNoHit;
  ASSERT_TRUE(IntersectSdfGrids1(g, ray, &t_max, &prim));
  EXPECT_EQ(prim, 0x80000000u | kSdfGridHitBit | 1);
  EXPECT_NEAR(t_max, 2.2f, 0.01f);
  EXPECT_TRUE(OccludedSdfGrids1(g, ray));
  // Through Intersect1 with a Bvh holding the grids and no triangle.
  Bvh bvh = BuildBvh(TriangleTable{});
  bvh.sdf_grids = g;
  Hit hit;
  ASSERT_TRUE(Intersect1(bvh, ray, &hit));
  EXPECT_EQ(hit.prim, prim);
  EXPECT_EQ(hit.t, t_max);
}

TEST(SdfGridNormal, PlaneAndBallNormals) {
  // f = x − 0.37 placed by a rotation: both normals are the rotated +x.
  const Transform rot = Transform::Rotate({0, 0, 1}, 90.0f);
  for (SdfNormals how : {SdfNormals::kAnalytic, SdfNormals::kSmooth}) {
    const SdfGridTable g = Grid(6, [](double x, double, double) { return float(x - 0.37); }, rot,
                                how);
    Vec3f ng, ns;
    SdfGridNormals(g, 0, rot.ApplyPoint({0.37f, 0.5f, 0.6f}), &ng, &ns);
    EXPECT_NEAR(ng.x, 0.0f, 1e-6f);
    EXPECT_NEAR(ng.y, 1.0f, 1e-6f);
    EXPECT_NEAR(ns.y, 1.0f, 1e-6f);
  }
  // A ball: the smooth normal is within a few degrees of the radial direction, the geometric
  // one (a cell's gradient) coarser; both unit and outward.
  const SdfGridTable g = BallGrid(24);
  Pcg32 rng(3, 3);
  for (int i = 0; i < 500; ++i) {
    const Vec3f w = UniformSphereDirection(rng);
    const Ray ray{Vec3f{0.5f, 0.45f, 0.55f} + w * 2.0f, -w};
    float t = 0;
    ASSERT_TRUE(IntersectSdfGrid1(g, 0, ray, ray.t_max, &t));
    Vec3f ng, ns;
    SdfGridNormals(g, 0, ray.At(t), &ng, &ns);
    EXPECT_NEAR(Length(ng), 1.0f, 1e-5f);
    EXPECT_NEAR(Length(ns), 1.0f, 1e-5f);
    const Vec3f radial = Normalize(ray.At(t) - Vec3f{0.5f, 0.45f, 0.55f});
    EXPECT_GT(Dot(ns, radial), 0.995f) << i;
    EXPECT_GT(Dot(ng, radial), 0.98f) << i;
    EXPECT_NEAR(ObjectValue(g, ray.At(t)), 0.0, 1e-5);
  }
  // A flat grid (no gradient) gives +z, never NaN.
  const SdfGridTable flat = Grid(3, [](double, double, double) { return 0.0f; });
  Vec3f ng, ns;
  SdfGridNormals(flat, 0, {0.5f, 0.5f, 0.5f}, &ng, &ns);
  EXPECT_EQ(ng.z, 1.0f);
  EXPECT_EQ(ns.z, 1.0f);
}

}  // namespace
}  // namespace ptlab
