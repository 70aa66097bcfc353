// BVH build invariants and Intersect1 / Occluded1 against a brute-force loop, exactly.
#include "engine/bvh/bvh.h"
#include "engine/bvh/bvh_build.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "engine/bvh/intersect1.h"
#include "engine/core/rng.h"
#include "tests/engine/bvh/test_meshes.h"

namespace ptlab {
namespace {

using bvh_test::BruteForceIntersect;
using bvh_test::IndexedMesh;
using bvh_test::Uniform;
using bvh_test::UniformInBox;
using bvh_test::UniformSphereDirection;

constexpr float kInf = std::numeric_limits<float>::infinity();

bool BoxContains(const BvhNode& n, const Vec3f& p) {
  return n.bounds_min.x <= p.x && p.x <= n.bounds_max.x && n.bounds_min.y <= p.y &&
         p.y <= n.bounds_max.y && n.bounds_min.z <= p.z && p.z <= n.bounds_max.z;
}

// Walks the tree and checks every structural promise of bvh.h. Returns the maximum depth.
int CheckStructure(const Bvh& bvh, const TriangleTable& table) {
  const size_t n = bvh.leaf_triangles.size();
  EXPECT_EQ(bvh.prim_id.size(), n);
  std::vector<int> covered(n, 0);
  int max_depth = 0;
  struct Item {
    uint32_t node;
    int depth;
  };
  std::vector<Item> todo = {{0, 0}};
  size_t visited = 0;
  while (!todo.empty()) {
    const Item it = todo.back();
    todo.pop_back();
    ++visited;
    max_depth = std::max(max_depth, it.depth);
    const BvhNode& node = bvh.nodes[it.node];
    EXPECT_LE(node.bounds_min.x, node.bounds_max.x);
    // Bounds are tight: exactly the union of the leaf's vertices or of the children's boxes
    // (the build takes children's boxes from its bins, so this checks that bookkeeping).
    Vec3f lo{kInf, kInf, kInf}, hi{-kInf, -kInf, -kInf};
    if (node.IsLeaf()) {
      for (uint32_t i = node.offset; i < node.offset + node.count && i < n; ++i) {
        for (const Vec3f& v :
             {bvh.leaf_triangles.V0(i), bvh.leaf_triangles.V1(i), bvh.leaf_triangles.V2(i)}) {
          lo = Min(lo, v);
          hi = Max(hi, v);
        }
      }
    } else if (node.offset > it.node + 1 && node.offset < bvh.nodes.size()) {
      for (uint32_t c : {it.node + 1, node.offset}) {
        lo = Min(lo, bvh.nodes[c].bounds_min);
        hi = Max(hi, bvh.nodes[c].bounds_max);
      }
    }
    EXPECT_EQ(node.bounds_min, lo) << "node " << it.node;
    EXPECT_EQ(node.bounds_max, hi) << "node " << it.node;
    if (node.IsLeaf()) {
      EXPECT_LE(node.count, kBvhMaxLeafSize);
      EXPECT_LE(node.offset + node.count, n);
      for (uint32_t i = node.offset; i < node.offset + node.count && i < n; ++i) {
        ++covered[i];
        EXPECT_TRUE(BoxContains(node, bvh.leaf_triangles.V0(i)));
        EXPECT_TRUE(BoxContains(node, bvh.leaf_triangles.V1(i)));
        EXPECT_TRUE(BoxContains(node, bvh.leaf_triangles.V2(i)));
        const uint32_t row = bvh.prim_id[i];
        EXPECT_LT(row, table.size());
        if (row < table.size()) {
          EXPECT_EQ(bvh.leaf_triangles.V0(i), table.V0(row));
          EXPECT_EQ(bvh.leaf_triangles.V1(i), table.V1(row));
          EXPECT_EQ(bvh.leaf_triangles.V2(i), table.V2(row));
        }
      }
    } else {
      const uint32_t left = it.node + 1, right = node.offset;
      EXPECT_LT(node.axis, 3);
      EXPECT_GT(right, left);
      EXPECT_LT(right, bvh.nodes.size());
      if (right <= left || right >= bvh.nodes.size()) continue;
      for (uint32_t c : {left, right}) {
        EXPECT_TRUE(BoxContains(node, bvh.nodes[c].bounds_min));
        EXPECT_TRUE(BoxContains(node, bvh.nodes[c].bounds_max));
        todo.push_back({c, it.depth + 1});
      }
    }
  }
  EXPECT_EQ(visited, bvh.nodes.size());
  EXPECT_TRUE(std::all_of(covered.begin(), covered.end(), [](int c) { return c == 1; }));
  EXPECT_LT(max_depth, kBvhMaxDepth);
  std::vector<uint32_t> rows(bvh.prim_id.begin(), bvh.prim_id.end());
  std::sort(rows.begin(), rows.end());
  EXPECT_TRUE(std::adjacent_find(rows.begin(), rows.end()) == rows.end());
  return max_depth;
}

// Intersect1 and Occluded1 against the brute-force loop: same hit/no-hit, bit-identical t
// and barycentrics, same row (ties on t resolve to the lowest row on both sides).
void ExpectSameAsBruteForce(const Bvh& bvh, const TriangleTable& table, const Ray& ray,
                            const std::string& what, int* failures) {
  Hit expected, got;
  const bool want = BruteForceIntersect(table, ray, &expected);
  const bool have = Intersect1(bvh, ray, &got);
  const bool occluded = Occluded1(bvh, ray);
  const bool same = want == have && occluded == want &&
                    (!want || (got.t == expected.t && got.prim == expected.prim &&
                               got.b1 == expected.b1 && got.b2 == expected.b2));
  if (!same && ++*failures <= 5) {
    ADD_FAILURE() << what << ": o=(" << ray.o.x << "," << ray.o.y << "," << ray.o.z << ") d=("
                  << ray.d.x << "," << ray.d.y << "," << ray.d.z << ") t=[" << ray.t_min << ","
                  << ray.t_max << "] brute " << want << " t=" << expected.t
                  << " prim=" << expected.prim << " bvh " << have << " t=" << got.t
                  << " prim=" << got.prim << " occluded " << occluded;
  }
}

Vec3f Vertex(const TriangleTable& t, uint32_t row, int k) {
  return k == 0 ? t.V0(row) : (k == 1 ? t.V1(row) : t.V2(row));
}

// Random and adversarial rays against one scene; counts rays that hit to make sure the
// categories are not vacuous.
void CompareWithBruteForce(const TriangleTable& table, uint64_t seed, int rays_per_kind) {
  const Bvh bvh = BuildBvh(table);
  ASSERT_FALSE(bvh.empty());
  CheckStructure(bvh, table);
  const Vec3f lo = bvh.nodes[0].bounds_min, hi = bvh.nodes[0].bounds_max;
  // Pad by half the largest extent on every axis, so flat scenes get origins off-plane too.
  const float half = 0.5f * MaxComponent(hi - lo);
  const Vec3f pad{half, half, half};
  const Vec3f outer_lo = lo - pad, outer_hi = hi + pad;
  Pcg32 rng(seed, 7);
  const uint32_t n = static_cast<uint32_t>(table.size());
  auto random_row = [&] { return rng.NextUint() % n; };
  auto random_vertex = [&] { return Vertex(table, random_row(), rng.NextUint() % 3); };
  int failures = 0;
  int hits = 0, total = 0;
  auto check = [&](const Ray& ray, const char* what) {
    ExpectSameAsBruteForce(bvh, table, ray, what, &failures);
    Hit h;
    hits += Intersect1(bvh, ray, &h) ? 1 : 0;
    ++total;
  };

  for (int i = 0; i < rays_per_kind; ++i) {
    // Random origins around the scene, random directions.
    check({UniformInBox(rng, outer_lo, outer_hi), UniformSphereDirection(rng)}, "random");
    // Aimed at an exact vertex and at the exact midpoint of an edge.
    {
      const uint32_t row = random_row();
      const int k = static_cast<int>(rng.NextUint() % 3);
      const Vec3f a = Vertex(table, row, k), b = Vertex(table, row, (k + 1) % 3);
      const Vec3f o = UniformInBox(rng, outer_lo, outer_hi);
      check({o, a - o}, "vertex");
      check({o, (a + b) * 0.5f - o}, "edge midpoint");
    }
    // Axis-parallel through an exact vertex: the origin shares two coordinates with it, so
    // the ray lies on box faces (0 * inf slab distances) and passes through the vertex.
    {
      const Vec3f v = random_vertex();
      const int axis = static_cast<int>(rng.NextUint() % 3);
      const float sign = (rng.NextUint() & 1) ? 1.0f : -1.0f;
      Vec3f o = v, d;
      o[axis] = v[axis] - sign * Uniform(rng, 0.1f, 2.0f);
      d[axis] = sign;
      // Signed zeros in the other components.
      d[(axis + 1) % 3] = (rng.NextUint() & 1) ? 0.0f : -0.0f;
      d[(axis + 2) % 3] = (rng.NextUint() & 1) ? 0.0f : -0.0f;
      check({o, d}, "axis-parallel through vertex");
      Vec3f o2 = UniformInBox(rng, outer_lo, outer_hi);
      check({o2, d}, "axis-parallel");
    }
    // One zero direction component with the origin on a vertex's plane of that axis.
    {
      const Vec3f v = random_vertex();
      const int axis = static_cast<int>(rng.NextUint() % 3);
      Vec3f d = UniformSphereDirection(rng);
      d[axis] = 0.0f;
      Vec3f o = UniformInBox(rng, outer_lo, outer_hi);
      o[axis] = v[axis];
      check({o, d}, "zero component");
      check({o, v - o}, "zero component to vertex");
    }
    // Grazing: in the plane of a triangle, from a point on its edge line along another edge.
    {
      const uint32_t row = random_row();
      const Vec3f a = table.V0(row), b = table.V1(row), c = table.V2(row);
      const float s = Uniform(rng, -1.0f, 2.0f);
      const Vec3f o = a + (b - a) * s;
      check({o, c - a}, "grazing");
      check({a - (c - a), c - a}, "grazing along edge");
    }
    // Origin inside a random node's box.
    {
      const BvhNode& node = bvh.nodes[rng.NextUint() % bvh.nodes.size()];
      check({UniformInBox(rng, node.bounds_min, node.bounds_max), UniformSphereDirection(rng)},
            "origin in node box");
    }
    // Clipped intervals: t_max = 0, t_min > t_max, and an interval ending near a hit.
    {
      const Vec3f o = UniformInBox(rng, outer_lo, outer_hi);
      const Vec3f d = random_vertex() - o;
      Ray r{o, d, 0.0f, 0.0f};
      check(r, "t_max = 0");
      Hit h;
      EXPECT_FALSE(Intersect1(bvh, r, &h));
      r.t_min = 0.5f;
      r.t_max = 0.25f;
      check(r, "t_min > t_max");
      EXPECT_FALSE(Intersect1(bvh, r, &h));
      EXPECT_FALSE(Occluded1(bvh, r));
      r.t_min = Uniform(rng, 0.0f, 0.9f);
      r.t_max = r.t_min + Uniform(rng, 0.0f, 0.2f);
      check(r, "short interval");
    }
  }
  EXPECT_EQ(failures, 0);
  // Every category mixes hits and misses; make sure the comparison was not vacuous.
  EXPECT_GT(hits, total / 10);
  EXPECT_LT(hits, total);
}

TEST(BvhBuild, EmptyTableHasNoNodesAndNeverHits) {
  const Bvh bvh = BuildBvh(TriangleTable{});
  EXPECT_TRUE(bvh.empty());
  EXPECT_EQ(bvh.leaf_triangles.size(), 0u);
  Hit hit;
  const Ray ray{{0, 0, -1}, {0, 0, 1}};
  EXPECT_FALSE(Intersect1(bvh, ray, &hit));
  EXPECT_EQ(hit.prim, kNoHit);
  EXPECT_FALSE(Occluded1(bvh, ray));
}

TEST(BvhBuild, SingleTriangleIsOneLeaf) {
  TriangleTable t;
  t.Append({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const Bvh bvh = BuildBvh(t);
  ASSERT_EQ(bvh.nodes.size(), 1u);
  EXPECT_TRUE(bvh.nodes[0].IsLeaf());
  EXPECT_EQ(bvh.nodes[0].count, 1);
  Hit hit;
  ASSERT_TRUE(Intersect1(bvh, {{0.25f, 0.5f, 2.0f}, {0, 0, -1}}, &hit));
  EXPECT_EQ(hit.prim, 0u);
  EXPECT_EQ(hit.t, 2.0f);
  EXPECT_FLOAT_EQ(hit.b1, 0.25f);
  EXPECT_FLOAT_EQ(hit.b2, 0.5f);
  EXPECT_FALSE(Intersect1(bvh, {{0.75f, 0.5f, 2.0f}, {0, 0, -1}}, &hit));
}

TEST(BvhBuild, NodesAreThirtyTwoBytes) {
  EXPECT_EQ(sizeof(BvhNode), 32u);
  EXPECT_EQ(alignof(BvhNode), 32u);
}

TEST(BvhBuild, StructureOfRandomSoupAndSphere) {
  Pcg32 rng(1, 1);
  const TriangleTable soup = bvh_test::MakeRandomSoup(5000, rng);
  const Bvh a = BuildBvh(soup);
  EXPECT_EQ(a.leaf_triangles.size(), soup.size());
  CheckStructure(a, soup);
  const TriangleTable sphere = bvh_test::MakeIcosphere(4, {0.1f, 0.2f, 0.3f}, 1.5f).ToTable();
  const Bvh b = BuildBvh(sphere);
  EXPECT_EQ(b.leaf_triangles.size(), sphere.size());
  const int depth = CheckStructure(b, sphere);
  // 5120 well-spread triangles: SAH gives a roughly balanced tree.
  EXPECT_LE(depth, 20);
}

TEST(BvhBuild, AllCentroidsEqualStillSplitsAndTiesPickLowestRow) {
  // 100 copies of one triangle plus 100 triangles rotated about the same centroid.
  TriangleTable t;
  for (int i = 0; i < 100; ++i) t.Append({-1, -1, 0}, {2, -1, 0}, {-1, 2, 0});
  for (int i = 0; i < 100; ++i) {
    const float a = 0.06f * static_cast<float>(i);
    const Vec3f u{std::cos(a), std::sin(a), 0.5f}, v{-std::sin(a), std::cos(a), -0.5f};
    t.Append(u, v, -(u + v));
  }
  const Bvh bvh = BuildBvh(t);
  EXPECT_EQ(bvh.leaf_triangles.size(), t.size());
  CheckStructure(bvh, t);
  Hit hit;
  // Straight down at a point only the 100 copies cover (all at the same t): row 0 wins.
  ASSERT_TRUE(Intersect1(bvh, {{1.5f, -0.9f, 5.0f}, {0, 0, -1}}, &hit));
  EXPECT_EQ(hit.prim, 0u);
  EXPECT_EQ(hit.t, 5.0f);
  Hit brute;
  ASSERT_TRUE(BruteForceIntersect(t, {{1.5f, -0.9f, 5.0f}, {0, 0, -1}}, &brute));
  EXPECT_EQ(brute.prim, 0u);
}

TEST(BvhBuild, ExponentialSpacingStaysUnderMaxDepth) {
  // Each triangle twice as far as the previous one: SAH peels one triangle per level, so
  // the depth limit has to take over.
  TriangleTable t;
  float x = 1.0f;
  for (int i = 0; i < 120; ++i, x *= 1.7f) t.Append({x, 0, 0}, {x, 1, 0}, {x, 0, 1});
  for (int i = 0; i < 2000; ++i) {
    const float s = 1.0f + 1e-3f * static_cast<float>(i);
    t.Append({s, 0, 0}, {s, 1, 0}, {s, 0, 1});
  }
  const Bvh bvh = BuildBvh(t);
  EXPECT_LT(CheckStructure(bvh, t), kBvhMaxDepth);
  int failures = 0;
  Pcg32 rng(3, 3);
  for (int i = 0; i < 2000; ++i) {
    const Ray ray{{-1.0f, Uniform(rng, 0, 0.5f), Uniform(rng, 0, 0.5f)},
                  {1.0f, Uniform(rng, -1e-3f, 1e-3f), Uniform(rng, -1e-3f, 1e-3f)}};
    ExpectSameAsBruteForce(bvh, t, ray, "exponential", &failures);
    Ray back = ray;
    back.o.x = 1e30f;
    back.d.x = -1.0f;
    ExpectSameAsBruteForce(bvh, t, back, "exponential backwards", &failures);
  }
  EXPECT_EQ(failures, 0);
}

// Issue 12, finding 2: bounds near FLT_MAX overflow the doubled centroids and the extent to
// Inf; binning used to turn that into bin INT_MIN and write outside its array. Finite
// triangles whose sums overflow still build a valid tree and keep every triangle.
TEST(BvhBuild, BoundsNearFloatMaxBinSafely) {
  TriangleTable t;
  const float big = 3e38f;
  for (int i = 0; i < 64; ++i) {
    const float s = (i % 2 == 0 ? 1.0f : -1.0f) * big * (0.5f + 0.0078125f * float(i));
    t.Append({s, 0, 0}, {s, s, 0}, {0, s, s});
  }
  for (int i = 0; i < 64; ++i) {
    const float x = float(i);
    t.Append({x, 0, 5}, {x + 1, 0, 5}, {x, 1, 5});
  }
  const Bvh bvh = BuildBvh(t);
  EXPECT_EQ(bvh.prim_id.size(), t.size());
  CheckStructure(bvh, t);
}

TEST(BvhBuild, DegenerateTrianglesAreDroppedAndNeverHit) {
  TriangleTable t;
  t.Append({0, 0, 0}, {1, 0, 0}, {0, 1, 0});                // 0: regular
  t.Append({2, 2, 0}, {2, 2, 0}, {2, 2, 0});                // 1: a point
  t.Append({0, 0, 1}, {1, 1, 1}, {2, 2, 1});                // 2: collinear
  t.Append({0, 0, 2}, {1, 0, 2}, {1, 0, 2});                // 3: repeated vertex
  t.Append({0.5f, 0.5f, 3}, {3, 3, 3}, {1.75f, 1.75f, 3});  // 4: collinear, mid vertex last
  const float nan = std::numeric_limits<float>::quiet_NaN();
  t.Append({0, 0, 4}, {nan, 0, 4}, {0, 1, 4});   // 5: non-finite
  t.Append({0, 0, 5}, {kInf, 0, 5}, {0, 1, 5});  // 6: non-finite
  const Bvh bvh = BuildBvh(t);
  ASSERT_EQ(bvh.prim_id.size(), 1u);
  EXPECT_EQ(bvh.prim_id[0], 0u);
  // Rays through the degenerate ones' vertices and interiors, from many directions.
  Pcg32 rng(5, 5);
  for (int i = 0; i < 20000; ++i) {
    const uint32_t row = 1 + rng.NextUint() % 4;
    const Vec3f a = t.V0(row), b = t.V1(row), c = t.V2(row);
    const float s = rng.NextFloat();
    const Vec3f target = (i % 3 == 0) ? a : ((i % 3 == 1) ? a + (c - a) * s : (b + c) * 0.5f);
    const Vec3f dir = UniformSphereDirection(rng);
    const Ray ray{target - dir * 3.0f, dir, 0.0f, kInf};
    Hit hit;
    if (Intersect1(bvh, ray, &hit)) {
      EXPECT_EQ(hit.prim, 0u);
      EXPECT_TRUE(std::isfinite(hit.t) && std::isfinite(hit.b1) && std::isfinite(hit.b2));
    }
  }
}

// The parallel build defers subtrees to threads and splices their nodes back: the tree must
// be the same bit for bit for any thread count (so renders do not depend on it). The table
// is large enough to be built in parallel (16,384 triangles or more) and mixes a random soup,
// 300 copies of one triangle (the object-median fallback) and exponentially spaced ones (the
// depth limit), all inside subtrees that the threads build.
TEST(BvhBuild, SameTreeForAnyThreadCount) {
  Pcg32 rng(9, 4);
  TriangleTable t = bvh_test::MakeRandomSoup(40000, rng);
  for (int i = 0; i < 300; ++i) t.Append({0.1f, 0.1f, 0.1f}, {0.2f, 0.1f, 0.1f}, {0.1f, 0.2f, 0.1f});
  float x = 1.0f;
  for (int i = 0; i < 60; ++i, x *= 1.7f) t.Append({x, 0, 0}, {x, 1, 0}, {x, 0, 1});
  const Bvh one = BuildBvh(t, SphereTable{}, 1);
  CheckStructure(one, t);
  for (const int threads : {2, 3, 8}) {
    SCOPED_TRACE(threads);
    const Bvh many = BuildBvh(t, SphereTable{}, threads);
    ASSERT_EQ(many.nodes.size(), one.nodes.size());
    EXPECT_EQ(std::memcmp(many.nodes.data(), one.nodes.data(), one.nodes.size() * sizeof(BvhNode)),
              0);
    EXPECT_TRUE(std::equal(one.prim_id.begin(), one.prim_id.end(), many.prim_id.begin(),
                           many.prim_id.end()));
    EXPECT_TRUE(std::equal(one.leaf_triangles.v2_z.begin(), one.leaf_triangles.v2_z.end(),
                           many.leaf_triangles.v2_z.begin(), many.leaf_triangles.v2_z.end()));
  }
}

TEST(BvhTraversal, MatchesBruteForceOnRandomSoup) {
  Pcg32 rng(11, 1);
  CompareWithBruteForce(bvh_test::MakeRandomSoup(800, rng), 21, 2500);
}

TEST(BvhTraversal, MatchesBruteForceOnSphere) {
  const IndexedMesh sphere = bvh_test::MakeIcosphere(3, {0.3f, -0.2f, 0.1f}, 1.0f);
  CompareWithBruteForce(sphere.ToTable(), 22, 2500);
}

TEST(BvhTraversal, MatchesBruteForceOnFlatGrid) {
  CompareWithBruteForce(bvh_test::MakeFlatGrid(32).ToTable(), 23, 2500);
}

TEST(BvhTraversal, MatchesBruteForceOnRotatedCubes) {
  TriangleTable t;
  Pcg32 rng(9, 9);
  for (int i = 0; i < 40; ++i) {
    const Vec3f c = UniformInBox(rng, {-2, -2, -2}, {2, 2, 2});
    const float s = Uniform(rng, 0.05f, 0.5f);
    const IndexedMesh cube =
        bvh_test::Rotated(bvh_test::MakeCube(c - Vec3f{s, s, s}, c + Vec3f{s, s, s}),
                          UniformSphereDirection(rng), (i % 2 == 0) ? 0.0f : Uniform(rng, 0, 3));
    for (const auto& tri : cube.triangles) {
      t.Append(cube.vertices[tri[0]], cube.vertices[tri[1]], cube.vertices[tri[2]]);
    }
  }
  CompareWithBruteForce(t, 24, 1500);
}

}  // namespace
}  // namespace ptlab
