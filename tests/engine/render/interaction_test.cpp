// MakeInteraction's surface uv: a mesh's texture coordinates interpolated at the hit, the
// barycentrics on meshes without them (Nori), (φ/2π, θ/π) on spheres. The batch into the
// wavefront's rows.
#include "engine/wavefront/interaction.h"

#include <gtest/gtest.h>

#include <tuple>
#include <vector>

#include "engine/bvh/sphere_intersect.h"
#include "engine/io/mesh_builder.h"

namespace ptlab {
namespace {

// Two quads in the z = 1 plane: mesh 0 with uvs (triangle 0: uv (0.5,0), (1,0), (1,0.25)),
// mesh 1 with normals only, so its zero-filled uv rows exist but are not its uvs.
Scene QuadScene() {
  Scene scene;
  MeshData m;
  m.positions = {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.uvs = {{0.5f, 0}, {1, 0}, {1, 0.25f}, {0.5f, 0.25f}};
  AddMesh(&scene, m, Transform(), MaterialRef{}, "with uvs");
  m.uvs.clear();
  m.normals.assign(4, Vec3f{0, 0, 1});
  AddMesh(&scene, m, Transform(), MaterialRef{}, "without uvs");
  return scene;
}

const Ray kDown{{0.5f, 0.5f, 3}, {0, 0, -1}};

TEST(Interaction, UvInterpolatesMeshTexCoords) {
  const Scene scene = QuadScene();
  const float b1 = 0.25f, b2 = 0.5f, b0 = 1 - b1 - b2;
  const SurfaceInteraction its = MakeInteraction(scene, kDown, Hit{2, b1, b2, 0});
  EXPECT_EQ(its.uv.x, b0 * 0.5f + b1 * 1.0f + b2 * 1.0f);
  EXPECT_EQ(its.uv.y, b0 * 0.0f + b1 * 0.0f + b2 * 0.25f);
  EXPECT_EQ(MakeInteraction(scene, kDown, Hit{2, 0, 0, 0}).uv.x, 0.5f);
  EXPECT_EQ(MakeInteraction(scene, kDown, Hit{2, 0, 1, 0}).uv.y, 0.25f);
}

TEST(Interaction, UvIsBarycentricsWithoutTexCoords) {
  const Scene scene = QuadScene();
  ASSERT_FALSE(scene.vertices.u.empty());  // mesh 1 has zero-filled uv rows
  for (const uint32_t tri : {2u, 3u}) {
    const SurfaceInteraction its = MakeInteraction(scene, kDown, Hit{2, 0.125f, 0.75f, tri});
    EXPECT_EQ(its.uv.x, 0.125f);
    EXPECT_EQ(its.uv.y, 0.75f);
  }
  Scene bare;  // no VertexTable columns at all
  MeshData m;
  m.positions = {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}};
  m.indices = {0, 1, 2};
  AddMesh(&bare, m, Transform(), MaterialRef{}, "bare");
  EXPECT_EQ(MakeInteraction(bare, kDown, Hit{2, 0.3f, 0.6f, 0}).uv.y, 0.6f);
}

TEST(Interaction, SphereUvIsPhiAndTheta) {
  Scene scene;
  scene.spheres.Append({1, 2, 3}, 2.0f, MaterialRef{});
  const uint32_t prim = kSphereHitBit | 0;
  // Rays from outside along -axis towards the centre hit at t = 8 - 2.
  const auto uv_at = [&](const Vec3f& axis) {
    const Ray ray{Vec3f{1, 2, 3} + axis * 8.0f, -axis};
    return MakeInteraction(scene, ray, Hit{6, 0, 0, prim}).uv;
  };
  EXPECT_EQ(uv_at({1, 0, 0}).x, 0.0f);
  EXPECT_FLOAT_EQ(uv_at({1, 0, 0}).y, 0.5f);
  EXPECT_FLOAT_EQ(uv_at({0, 1, 0}).x, 0.25f);
  EXPECT_FLOAT_EQ(uv_at({-1, 0, 0}).x, 0.5f);
  EXPECT_FLOAT_EQ(uv_at({0, -1, 0}).x, 0.75f);
  EXPECT_EQ(uv_at({0, 0, 1}).y, 0.0f);
  EXPECT_FLOAT_EQ(uv_at({0, 0, -1}).y, 1.0f);
  // Just below the seam φ = 2π: u stays below 1.
  EXPECT_LT(SphereUv({1, -1e-30f, 0}).x, 1.0f);
  EXPECT_GE(SphereUv({1, -1e-30f, 0}).x, 0.0f);
}

// The wavefront's rows: MakeInteraction without uv, and wo = -d / |d| in its frame, for the hit
// lanes (a triangle and a sphere); the other rows left as they were.
TEST(Interaction, BatchIntoRows) {
  Scene scene = QuadScene();
  scene.spheres.Append({0.5f, 0.5f, -2}, 1.0f, MaterialRef::Make(MaterialTag::kMirror, 3));
  const Ray slanted{{0.25f, 0.5f, 3}, {0.5f, -1.0f, -4}};
  RayPacket8 rays{};
  HitPacket8 hits{};
  SetLaneRay(&rays, 0, slanted);
  SetLaneHit(&hits, 0, 0.5f, 0.2f, 0.3f, 1);
  SetLaneRay(&rays, 2, kDown);
  SetLaneHit(&hits, 2, 4, 0, 0, kSphereHitBit | 0);
  const Mask8 hit = LaneBit(0) | LaneBit(2);
  SurfaceInteraction fill;
  fill.prim = 77;
  std::vector<SurfaceInteraction> its(kPacketWidth, fill);
  std::vector<Vec3f> wo(kPacketWidth, Vec3f{-1, -1, -1});
  std::vector<uint32_t> entries(kPacketWidth, 99), area(kPacketWidth, 99);
  HitLists lists{entries.data(), area.data()};
  MakeInteractionBatch(scene, &rays, &hits, &hit, 1, InteractionRows{its.data(), wo.data()},
                       &lists);
  const SurfaceInteraction tri = MakeInteraction(scene, slanted, Hit{0.5f, 0.2f, 0.3f, 1});
  const SurfaceInteraction sphere = MakeInteraction(scene, kDown, Hit{4, 0, 0, kSphereHitBit});
  for (const auto& [q, want, ray] : {std::tuple{0, tri, slanted}, std::tuple{2, sphere, kDown}}) {
    SCOPED_TRACE(q);
    EXPECT_EQ(its[q].p, want.p);
    EXPECT_EQ(its[q].ng, want.ng);
    EXPECT_EQ(its[q].frame.s, want.frame.s);
    EXPECT_EQ(its[q].frame.t, want.frame.t);
    EXPECT_EQ(its[q].frame.n, want.frame.n);
    EXPECT_EQ(its[q].uv.x, 0.0f);
    EXPECT_EQ(its[q].uv.y, 0.0f);
    EXPECT_EQ(its[q].prim, want.prim);
    EXPECT_EQ(its[q].material, want.material);
    EXPECT_EQ(its[q].emitter, want.emitter);
    EXPECT_EQ(wo[q], want.frame.ToLocal(-ray.d / Length(ray.d)));
  }
  EXPECT_EQ(its[2].material, MaterialRef::Make(MaterialTag::kMirror, 3));
  EXPECT_FALSE(its[2].emitter.valid());
  EXPECT_NEAR(Length(wo[0]), 1.0f, 1e-6f);
  EXPECT_EQ(its[1].prim, 77u);  // lanes without a hit: rows left as they were
  EXPECT_EQ(wo[1], (Vec3f{-1, -1, -1}));
  // The lists: both hits in lane order, counted by material group.
  ASSERT_EQ(lists.hits, 2u);
  EXPECT_EQ(entries[0], 0u);
  EXPECT_EQ(entries[1], 2u);
  EXPECT_EQ(entries[2], 99u);
  EXPECT_EQ(lists.area_hits, 0u);  // the quads do not emit, spheres never do
  uint32_t groups[kMaterialGroups] = {};
  ++groups[kMaterialTagCount], ++groups[int(MaterialTag::kMirror)];  // no material; mirror
  for (int g = 0; g < kMaterialGroups; ++g) EXPECT_EQ(lists.group_hits[g], groups[g]) << g;
}

}  // namespace
}  // namespace ptlab
