// The two-level BVH (instancing): Intersect1 / Occluded1 on BuildSceneBvh against a brute-force
// loop over every top-level triangle, sphere and instanced triangle (in group space).
#include <gtest/gtest.h>

#include <cstring>

#include "engine/bvh/instance_level.h"
#include "engine/bvh/intersect1.h"
#include "engine/bvh/scene_bvh.h"
#include "tests/engine/bvh/instance_scene.h"

namespace ptlab {
namespace {

uint32_t Bits(float f) {
  uint32_t b;
  std::memcpy(&b, &f, sizeof(b));
  return b;
}

TEST(InstanceBvh, MatchesBruteForce) {
  const Scene s = bvh_test::MakeInstancedScene();
  const Bvh bvh = BuildSceneBvh(s);
  ASSERT_EQ(bvh.groups.size(), 2u);
  ASSERT_FALSE(bvh.instances.empty());
  const uint32_t rows = uint32_t(s.triangles.size());
  int hits = 0, instanced = 0, on_first_identity = 0, failures = 0;
  for (const Ray& ray : bvh_test::InstancedSceneRays(s, 5, 8000)) {
    Hit want, got;
    const bool w = bvh_test::BruteForceInstanced(s, bvh.instances, ray, &want);
    const bool g = Intersect1(bvh, ray, &got);
    const bool occluded = Occluded1(bvh, ray);
    EXPECT_EQ(w, g);
    EXPECT_EQ(w, occluded);
    if (w && g) {
      const bool same = Bits(want.t) == Bits(got.t) && Bits(want.b1) == Bits(got.b1) &&
                        Bits(want.b2) == Bits(got.b2) && want.prim == got.prim;
      if (!same && ++failures <= 5)
        ADD_FAILURE() << "ray o=(" << ray.o.x << "," << ray.o.y << "," << ray.o.z << ") d=("
                      << ray.d.x << "," << ray.d.y << "," << ray.d.z << "): want t=" << want.t
                      << " prim " << want.prim << ", got t=" << got.t << " prim " << got.prim;
    }
    if (w) {
      ++hits;
      if (!IsSphereHit(want.prim) && want.prim >= rows) {
        ++instanced;
        const InstancedRow at = FindInstancedRow(s.instances, rows, want.prim);
        if (at.instance == 0) ++on_first_identity;
      }
    }
  }
  EXPECT_EQ(failures, 0);
  // The rays meet the instances (not a vacuous comparison), and the identity instance 0 wins
  // its exact ties with instance 4.
  EXPECT_GT(hits, 4000);
  EXPECT_GT(instanced, 2000);
  EXPECT_GT(on_first_identity, 40);
  for (const Ray& ray : bvh_test::InstancedSceneRays(s, 6, 5000)) {
    Hit h;
    if (!Intersect1(bvh, ray, &h) || IsSphereHit(h.prim) || h.prim < rows) continue;
    EXPECT_NE(FindInstancedRow(s.instances, rows, h.prim).instance, 4u);
  }
}

// A scene without shape groups gets BuildBvh's tree, bit for bit.
TEST(InstanceBvh, WithoutGroupsIsTheOneLevelTree) {
  Scene s = bvh_test::MakeInstancedScene();
  s.instances = InstanceTable{};
  const Bvh a = BuildSceneBvh(s), b = BuildBvh(s.triangles, s.spheres);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  EXPECT_EQ(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(BvhNode)), 0);
  EXPECT_TRUE(a.instances.empty());
  EXPECT_TRUE(a.groups.empty());
}

// Hit ids: instance i's triangle j is rows + first_prim[i] + j, and back.
TEST(InstanceBvh, HitIdsRoundTrip) {
  const Scene s = bvh_test::MakeInstancedScene();
  const InstanceTable& in = s.instances;
  const uint32_t rows = uint32_t(s.triangles.size());
  for (uint32_t i = 0; i < in.size(); ++i)
    for (uint32_t j = 0; j < in.group_row_count[in.group[i]]; ++j) {
      const InstancedRow at = FindInstancedRow(in, rows, rows + in.first_prim[i] + j);
      ASSERT_EQ(at.instance, i);
      ASSERT_EQ(at.row, in.group_first_row[in.group[i]] + j);
    }
}

}  // namespace
}  // namespace ptlab
