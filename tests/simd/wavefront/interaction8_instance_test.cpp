// The interaction stage on instanced hits: the oracle's world-space point and normals (the
// group's through the instance's to_world and its inverse transpose), and simd/'s
// MakeInteractionBatch bit-identical to the oracle's on every target, lists included.
// clang-format off
#include "simd/targets.h"  // first: the same target policy as simd/
// clang-format on
#include "simd/dispatched_target.h"
#include "simd/wavefront/interaction8.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "engine/bvh/intersect1.h"
#include "engine/bvh/scene_bvh.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/core/rng.h"
#include "engine/io/mitsuba_loader.h"
#include "engine/wavefront/interaction.h"
#include "tests/simd/for_each_target.h"

namespace ptlab {
namespace {

// Group g (rectangle, cube, sphere) under a rotation with scale and under a mirror; group h (a
// rectangle) under a non-uniform scale with shear; a top-level floor with its own material.
constexpr const char* kScene = R"(<scene version="3.0.0">
<sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/>
<integer name="height" value="8"/></film></sensor>
<shape type="shapegroup" id="g">
  <shape type="rectangle"><bsdf type="diffuse"><rgb name="reflectance" value="0.1 0.2 0.3"/></bsdf></shape>
  <shape type="cube"><transform name="to_world"><scale value="0.3"/><translate z="0.5"/></transform></shape>
  <shape type="sphere"><float name="radius" value="0.2"/><point name="center" x="0.5" y="0.5" z="0.5"/></shape>
</shape>
<shape type="shapegroup" id="h"><shape type="rectangle"/></shape>
<shape type="instance"><ref id="g"/><transform name="to_world">
  <rotate x="1" y="1" angle="35"/><scale value="1.5"/><translate x="-2"/></transform></shape>
<shape type="instance"><ref id="g"/><transform name="to_world">
  <scale x="-1" y="1" z="1"/><rotate z="1" angle="20"/><translate x="2"/></transform></shape>
<shape type="instance"><ref id="h"/><transform name="to_world">
  <matrix value="1 0.5 0 0  0 0.4 0.2 2  -0.3 0 1 0.5  0 0 0 1"/></transform></shape>
<shape type="rectangle"><transform name="to_world"><scale value="6"/><translate z="-1"/></transform></shape>
</scene>)";

TEST(Interaction8Instances, WorldSpaceAndBitIdenticalOnEveryTarget) {
  StatusOr<Scene> loaded = LoadMitsubaSceneFromString(kScene, ".", "inst.xml");
  ASSERT_TRUE(loaded.ok()) << loaded.status().message();
  const Scene& scene = *loaded;
  ASSERT_EQ(scene.instances.size(), 3u);
  const Bvh bvh = BuildSceneBvh(scene);
  const uint32_t rows = uint32_t(scene.triangles.size());
  // Packets of hits from random rays towards the instances.
  Pcg32 rng(12, 1);
  std::vector<RayPacket8> rays;
  std::vector<HitPacket8> hits;
  std::vector<Mask8> masks;
  int instanced = 0, checked = 0;
  for (int k = 0; k < 600; ++k) {
    RayPacket8 p;
    HitPacket8 h{};
    Mask8 m = 0;
    for (int j = 0; j < 8; ++j) {
      Ray r;
      r.o = {rng.NextFloat() * 8 - 4, rng.NextFloat() * 8 - 4, 2 + rng.NextFloat() * 2};
      const Vec3f target{rng.NextFloat() * 6 - 3, rng.NextFloat() * 4 - 1,
                         rng.NextFloat() * 1.5f - 0.5f};
      r.d = target - r.o;
      SetLaneRay(&p, j, r);
      Hit hit;
      if (!Intersect1(bvh, r, &hit)) continue;
      SetLaneHit(&h, j, hit.t, hit.b1, hit.b2, hit.prim);
      m |= LaneBit(j);
      if (IsSphereHit(hit.prim) || hit.prim < rows) continue;
      ++instanced;
      // The oracle's world-space interaction: on the ray, and the normal of the world triangle
      // (its transformed vertices' cross product, times the sign of the determinant).
      const SurfaceInteraction its = MakeInteraction(scene, r, hit);
      const Vec3f on_ray = r.At(hit.t);
      EXPECT_LE(Length(its.p - on_ray), 1e-4f * (1.0f + Length(on_ray)));
      const InstancedRow at = FindInstancedRow(scene.instances, rows, hit.prim);
      const Transform& w = scene.instances.to_world[at.instance];
      const Vec3f v0 = w.ApplyPoint(scene.triangles.V0(at.row));
      const Vec3f v1 = w.ApplyPoint(scene.triangles.V1(at.row));
      const Vec3f v2 = w.ApplyPoint(scene.triangles.V2(at.row));
      const Vec3f n = Normalize(Cross(v1 - v0, v2 - v0)) * (w.FlipsHandedness() ? -1.0f : 1.0f);
      EXPECT_NEAR(Dot(n, its.ng), 1.0f, 1e-4f);
      EXPECT_NEAR(Length(its.frame.n), 1.0f, 1e-5f);
      EXPECT_EQ(its.material.bits, scene.shading.material[at.row].bits);
      EXPECT_EQ(its.emitter.bits, EmitterRef::None().bits);
      ++checked;
    }
    rays.push_back(p), hits.push_back(h), masks.push_back(m);
  }
  ASSERT_GT(instanced, 500);
  const size_t n = rays.size() * kPacketWidth;
  std::vector<SurfaceInteraction> want(n), got(n);
  std::vector<Vec3f> want_wo(n), got_wo(n);
  std::vector<uint32_t> we(n), wa(n), ge(n), ga(n);
  HitLists want_lists{we.data(), wa.data()};
  MakeInteractionBatch(scene, rays.data(), hits.data(), masks.data(), rays.size(),
                       {want.data(), want_wo.data()}, &want_lists);
  const simd::TriangleRows tri_rows = simd::BuildTriangleRows(scene);
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    HitLists got_lists{ge.data(), ga.data()};
    simd::MakeInteractionBatch(scene, tri_rows, rays.data(), hits.data(), masks.data(),
                               rays.size(), {got.data(), got_wo.data()}, &got_lists);
    ASSERT_EQ(got_lists.hits, want_lists.hits);
    ASSERT_EQ(got_lists.area_hits, want_lists.area_hits);
    for (int g = 0; g < kMaterialGroups; ++g)
      EXPECT_EQ(got_lists.group_hits[g], want_lists.group_hits[g]);
    EXPECT_EQ(std::memcmp(ge.data(), we.data(), want_lists.hits * sizeof(uint32_t)), 0);
    size_t differ = 0;
    for (size_t q = 0; q < n; ++q) {
      if (!LaneActive(masks[q / 8], int(q % 8))) continue;
      differ += std::memcmp(&got[q], &want[q], sizeof(SurfaceInteraction)) != 0 ||
                std::memcmp(&got_wo[q], &want_wo[q], sizeof(Vec3f)) != 0;
    }
    EXPECT_EQ(differ, 0u);
  });
}

}  // namespace
}  // namespace ptlab
