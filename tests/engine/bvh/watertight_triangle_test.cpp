// Watertight triangle test on its own, and no leaks through closed meshes via the BVH.
#include "engine/bvh/watertight_triangle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "engine/bvh/bvh.h"
#include "engine/bvh/intersect1.h"
#include "engine/core/rng.h"
#include "tests/engine/bvh/test_meshes.h"

namespace ptlab {
namespace {

using bvh_test::IndexedMesh;
using bvh_test::Uniform;
using bvh_test::UniformInBox;
using bvh_test::UniformSphereDirection;

constexpr float kInf = std::numeric_limits<float>::infinity();

bool HitTriangle(const Vec3f& o, const Vec3f& d, const Vec3f& a, const Vec3f& b, const Vec3f& c,
                 float t_min, float t_max, TriangleHit* hit) {
  return IntersectTriangleWatertight(MakeWatertightRay(o, d), a, b, c, t_min, t_max, hit);
}

TEST(WatertightTriangle, HitDistanceAndBarycentricsBothWindings) {
  const Vec3f a{1, 0, 0}, b{3, 0, 0}, c{1, 4, 0};
  TriangleHit h;
  ASSERT_TRUE(HitTriangle({1.5f, 2.0f, 3.0f}, {0, 0, -2}, a, b, c, 0, kInf, &h));
  EXPECT_FLOAT_EQ(h.t, 1.5f);
  EXPECT_FLOAT_EQ(h.b1, 0.25f);
  EXPECT_FLOAT_EQ(h.b2, 0.5f);
  // Swapped winding (no backface culling): b1 and b2 follow the vertices.
  ASSERT_TRUE(HitTriangle({1.5f, 2.0f, 3.0f}, {0, 0, -2}, a, c, b, 0, kInf, &h));
  EXPECT_FLOAT_EQ(h.b1, 0.5f);
  EXPECT_FLOAT_EQ(h.b2, 0.25f);
  // From below, oblique, every major axis and sign of the direction.
  Pcg32 rng(1, 2);
  for (int i = 0; i < 10000; ++i) {
    const float u = rng.NextFloat(), v = rng.NextFloat() * (1.0f - u);
    const Vec3f p = a * (1.0f - u - v) + b * u + c * v;
    const Vec3f d = UniformSphereDirection(rng);
    const Vec3f o = p - d * 2.0f;
    ASSERT_TRUE(HitTriangle(o, d, a, b, c, 0, kInf, &h)) << i;
    EXPECT_NEAR(h.t, 2.0f, 1e-4f);
    EXPECT_NEAR(h.b1, u, 1e-4f);
    EXPECT_NEAR(h.b2, v, 1e-4f);
    EXPECT_FALSE(HitTriangle(o, -d, a, b, c, 0, kInf, &h));
  }
}

TEST(WatertightTriangle, IntervalIsOpenAndScaledWithDirection) {
  const Vec3f a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  const Vec3f o{0.25f, 0.25f, 1.0f}, d{0, 0, -4};  // hits at t = 0.25 exactly
  TriangleHit h;
  EXPECT_TRUE(HitTriangle(o, d, a, b, c, 0, kInf, &h));
  EXPECT_EQ(h.t, 0.25f);
  EXPECT_FALSE(HitTriangle(o, d, a, b, c, 0.25f, kInf, &h));
  EXPECT_FALSE(HitTriangle(o, d, a, b, c, 0, 0.25f, &h));
  EXPECT_TRUE(HitTriangle(o, d, a, b, c, 0.2499f, 0.2501f, &h));
  EXPECT_FALSE(HitTriangle(o, d, a, b, c, 0, 0, &h));
  EXPECT_FALSE(HitTriangle(o, d, a, b, c, 0.3f, 0.2f, &h));
  // Origin on the triangle: t = 0 is outside (0, inf).
  EXPECT_FALSE(HitTriangle({0.25f, 0.25f, 0}, d, a, b, c, 0, kInf, &h));
  // Negative t_min reaches behind the origin.
  EXPECT_TRUE(HitTriangle(o, -d, a, b, c, -1.0f, kInf, &h));
  EXPECT_EQ(h.t, -0.25f);
}

TEST(WatertightTriangle, DegenerateNeverHitsNorNaN) {
  // Zero-area triangles whose edge functions cancel exactly: all vertices equal, a repeated
  // vertex (in each position).
  const Vec3f p{0.3f, -0.7f, 1.1f}, q{1.9f, 0.4f, -0.6f}, r{-0.8f, 1.3f, 0.2f};
  const Vec3f tris[][3] = {{p, p, p}, {p, p, q}, {p, q, p}, {q, p, p}, {r, q, q}, {q, r, r}};
  Pcg32 rng(2, 2);
  int checked = 0;
  for (const auto& t : tris) {
    for (int i = 0; i < 20000; ++i) {
      const Vec3f target =
          (i % 2 == 0) ? t[i % 3] : t[0] + (t[1] + t[2] - t[0] * 2.0f) * (0.5f * rng.NextFloat());
      const Vec3f d = (i % 7 == 0) ? Vec3f{0, 0, 1} : UniformSphereDirection(rng);
      TriangleHit h{-1.0f, -1.0f, -1.0f};
      EXPECT_FALSE(HitTriangle(target - d * 2.0f, d, t[0], t[1], t[2], 0, kInf, &h));
      EXPECT_EQ(h.t, -1.0f);  // untouched on a miss
      ++checked;
    }
  }
  EXPECT_EQ(checked, 6 * 20000);
}

TEST(WatertightTriangle, DoubleFallbackDecidesTheSideOfAnEdge) {
  // Edge BC passes 4e-8 (exactly) from the ray, which runs along +z through the origin, so the
  // sheared coordinates are x and y themselves. In float the edge function rounds to 0; only
  // the double fallback sees which side the ray is on. The two triangles share BC: exactly
  // the one on the ray's side must be hit.
  const Vec3f b{-0x1.49829p+0f, 0x1.2b25c4p-1f, 1.0f};
  const Vec3f c{0x1.402626p+0f, -0x1.22a62cp-1f, 1.0f};
  ASSERT_EQ(c.x * b.y - c.y * b.x, 0.0f);
  ASSERT_LT(static_cast<double>(c.x) * b.y - static_cast<double>(c.y) * b.x, 0.0);
  const Vec3f o{0, 0, 0}, d{0, 0, 1};
  TriangleHit h;
  EXPECT_FALSE(HitTriangle(o, d, {0, -1, 1}, b, c, 0, kInf, &h));
  EXPECT_TRUE(HitTriangle(o, d, {0, 1, 1}, b, c, 0, kInf, &h));
  EXPECT_FLOAT_EQ(h.t, 1.0f);
}

TEST(WatertightTriangle, SharedEdgeAndVertexAlwaysHitOne) {
  // A fan of 6 triangles around a shared centre vertex with awkward coordinates; rays aimed
  // at points on the shared (interior) edges and at the centre must hit at least one.
  Pcg32 rng(3, 3);
  for (int fan = 0; fan < 20; ++fan) {
    const Vec3f centre = UniformInBox(rng, {-10, -10, -10}, {10, 10, 10});
    const Vec3f n = UniformSphereDirection(rng);
    const Vec3f t1 = Normalize(Cross(n, UniformSphereDirection(rng)));
    const Vec3f t2 = Cross(n, t1);
    Vec3f rim[6];
    for (int k = 0; k < 6; ++k) {
      const float ang = static_cast<float>(k) * (2.0f * kPi / 6.0f) + Uniform(rng, -0.3f, 0.3f);
      const float rad = Uniform(rng, 0.1f, 3.0f);
      rim[k] = centre + (t1 * std::cos(ang) + t2 * std::sin(ang)) * rad +
               n * (rad * Uniform(rng, -0.1f, 0.1f));
    }
    for (int i = 0; i < 5000; ++i) {
      const int k = static_cast<int>(rng.NextUint() % 6);
      const float s = (i % 4 == 0) ? 0.0f : rng.NextFloat();
      const Vec3f target = centre + (rim[k] - centre) * s;
      // From either side, steep enough that the fan (a height field over its tangent plane)
      // does not fold over itself in the ray's view, so every shared edge is interior.
      const Vec3f tilt = t1 * Uniform(rng, -0.3f, 0.3f) + t2 * Uniform(rng, -0.3f, 0.3f);
      const float side = (i % 2 == 0) ? 1.0f : -1.0f;
      const Vec3f o = target + (n * side + tilt) * Uniform(rng, 0.5f, 50.0f);
      const WatertightRay wr = MakeWatertightRay(o, target - o);
      int hits = 0;
      for (int j = 0; j < 6; ++j) {
        TriangleHit h;
        hits += IntersectTriangleWatertight(wr, centre, rim[j], rim[(j + 1) % 6], 0, kInf, &h);
      }
      ASSERT_GE(hits, 1) << "fan " << fan << " ray " << i;
    }
  }
}

struct MeshRay {
  Vec3f o, d;
};

// Rays from inside a closed mesh toward its vertices and edge points.
std::vector<MeshRay> RaysTowardVerticesAndEdges(const IndexedMesh& mesh, const Vec3f& centre,
                                                float inner_radius, int count, uint64_t seed) {
  Pcg32 rng(seed, 5);
  std::vector<MeshRay> rays;
  for (int i = 0; i < count; ++i) {
    const Vec3f o = centre + UniformSphereDirection(rng) * (inner_radius * rng.NextFloat());
    const auto& tri = mesh.triangles[rng.NextUint() % mesh.triangles.size()];
    const int k = static_cast<int>(rng.NextUint() % 3);
    const Vec3f a = mesh.vertices[tri[k]], b = mesh.vertices[tri[(k + 1) % 3]];
    const Vec3f target =
        (i % 3 == 0) ? a : ((i % 3 == 1) ? (a + b) * 0.5f : a + (b - a) * rng.NextFloat());
    rays.push_back({o, target - o});
  }
  return rays;
}

#if defined(__x86_64__) && defined(__GNUC__)
// The same inline test compiled for an FMA target, where GCC (-ffp-contract=fast is its C++
// default) and Clang fuse a * b - c * d into one FMA. Returns the rays that hit no triangle.
__attribute__((target("avx2,fma"))) int CountMissesWithFma(const TriangleTable& t,
                                                           const std::vector<MeshRay>& rays) {
  int misses = 0;
  for (const MeshRay& ray : rays) {
    const WatertightRay wr = MakeWatertightRay(ray.o, ray.d);
    bool hit = false;
    for (size_t i = 0; i < t.size() && !hit; ++i) {
      TriangleHit h;
      hit = IntersectTriangleWatertight(wr, t.V0(i), t.V1(i), t.V2(i), 0.0f, kInf, &h);
    }
    misses += hit ? 0 : 1;
  }
  return misses;
}
#endif

TEST(WatertightTriangle, ClosedMeshesHaveNoLeaksWhenCompiledWithFma) {
#if defined(__x86_64__) && defined(__GNUC__)
  if (!__builtin_cpu_supports("fma") || !__builtin_cpu_supports("avx2")) {
    GTEST_SKIP() << "CPU without FMA/AVX2";
  }
  const IndexedMesh cube = bvh_test::MakeCube({-3.1f, 0.7f, 100.3f}, {-1.9f, 1.3f, 101.1f});
  EXPECT_EQ(CountMissesWithFma(cube.ToTable(), RaysTowardVerticesAndEdges(
                                                   cube, {-2.5f, 1.0f, 100.7f}, 0.2f, 200000, 1)),
            0);
  const Vec3f centre{0.3f, -1.7f, 2.1f};
  const IndexedMesh sphere = bvh_test::MakeIcosphere(2, centre, 2.5f);
  EXPECT_EQ(CountMissesWithFma(sphere.ToTable(),
                               RaysTowardVerticesAndEdges(sphere, centre, 1.0f, 20000, 2)),
            0);
#else
  GTEST_SKIP() << "FMA variant only built for x86-64 GCC/Clang";
#endif
}

// Fires rays from the centre region of a closed mesh: toward random directions, toward
// exact vertices and toward points on edges (exact midpoints included). Every one must hit.
void ExpectNoLeaks(const IndexedMesh& mesh, const Vec3f& centre, float inner_radius, int rays,
                   uint64_t seed) {
  const TriangleTable table = mesh.ToTable();
  const Bvh bvh = BuildBvh(table);
  ASSERT_EQ(bvh.prim_id.size(), table.size());
  Pcg32 rng(seed, 4);
  int leaks = 0;
  for (int i = 0; i < rays; ++i) {
    const Vec3f o = (i % 16 == 0)
                        ? centre
                        : centre + UniformSphereDirection(rng) * (inner_radius * rng.NextFloat());
    Vec3f d;
    switch (i % 4) {
      case 0:
        d = UniformSphereDirection(rng);
        break;
      case 1:
        d = mesh.vertices[rng.NextUint() % mesh.vertices.size()] - o;
        break;
      case 2: {
        const auto& tri = mesh.triangles[rng.NextUint() % mesh.triangles.size()];
        const int k = static_cast<int>(rng.NextUint() % 3);
        d = (mesh.vertices[tri[k]] + mesh.vertices[tri[(k + 1) % 3]]) * 0.5f - o;
        break;
      }
      default: {
        const auto& tri = mesh.triangles[rng.NextUint() % mesh.triangles.size()];
        const int k = static_cast<int>(rng.NextUint() % 3);
        const Vec3f a = mesh.vertices[tri[k]], b = mesh.vertices[tri[(k + 1) % 3]];
        d = a + (b - a) * rng.NextFloat() - o;
        break;
      }
    }
    Hit hit;
    const Ray ray{o, d, 0.0f, kInf};
    const bool ok = Intersect1(bvh, ray, &hit) && std::isfinite(hit.t) && hit.t > 0.0f;
    if (!ok && ++leaks <= 5) {
      ADD_FAILURE() << "leak: o=(" << o.x << "," << o.y << "," << o.z << ") d=(" << d.x << ","
                    << d.y << "," << d.z << ")";
    }
    if (i % 8 == 0) {
      EXPECT_TRUE(Occluded1(bvh, ray));
    }
  }
  EXPECT_EQ(leaks, 0);
}

TEST(BvhWatertight, IcosphereHasNoLeaks) {
  const Vec3f centre{0.3f, -1.7f, 2.1f};
  ExpectNoLeaks(bvh_test::MakeIcosphere(3, centre, 2.5f), centre, 1.0f, 400000, 1);
}

TEST(BvhWatertight, AxisAlignedCubeHasNoLeaks) {
  const Vec3f centre{0, 0, 0};
  ExpectNoLeaks(bvh_test::MakeCube({-1, -1, -1}, {1, 1, 1}), centre, 0.5f, 200000, 2);
  // Off-centre with awkward coordinates.
  const Vec3f lo{-3.1f, 0.7f, 100.3f}, hi{-1.9f, 1.3f, 101.1f};
  ExpectNoLeaks(bvh_test::MakeCube(lo, hi), (lo + hi) * 0.5f, 0.2f, 200000, 3);
}

TEST(BvhWatertight, RotatedCubeHasNoLeaks) {
  const IndexedMesh cube =
      bvh_test::Rotated(bvh_test::MakeCube({-1, -1, -1}, {1, 1, 1}), {0.3f, 1.0f, -0.4f}, 0.7f);
  ExpectNoLeaks(cube, {0, 0, 0}, 0.5f, 200000, 4);
}

TEST(BvhWatertight, FlatGridHasNoHolesAtVerticesAndEdges) {
  // Grid lines coincide with leaf box faces: rays aimed at them must still hit.
  const IndexedMesh grid = bvh_test::MakeFlatGrid(64);
  const TriangleTable table = grid.ToTable();
  const Bvh bvh = BuildBvh(table);
  Pcg32 rng(6, 6);
  int leaks = 0;
  for (int i = 0; i < 100000; ++i) {
    // Interior vertices and points on interior grid lines.
    const int gi = 1 + static_cast<int>(rng.NextUint() % 63);
    const int gj = 1 + static_cast<int>(rng.NextUint() % 63);
    Vec3f target = grid.vertices[gj * 65 + gi];
    if (i % 3 == 1) target.x += Uniform(rng, 0.0f, 1.0f / 32.0f);
    if (i % 3 == 2) target.y += Uniform(rng, 0.0f, 1.0f / 32.0f);
    const Vec3f o{Uniform(rng, -3, 3), Uniform(rng, -3, 3), Uniform(rng, 0.001f, 3.0f)};
    Hit hit;
    if (!Intersect1(bvh, {o, target - o}, &hit)) ++leaks;
  }
  EXPECT_EQ(leaks, 0);
}

}  // namespace
}  // namespace ptlab
