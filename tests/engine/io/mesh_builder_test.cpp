// Tests of AddMesh: world-space transform of positions and normals, winding, vertex rows.
#include "engine/io/mesh_builder.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ptlab {
namespace {

MeshData Triangle(bool normals, bool uvs) {
  MeshData mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  if (normals) mesh.normals.assign(3, Vec3f{0, 0, 1});
  if (uvs) mesh.uvs = {{0, 0}, {1, 0}, {0, 1}};
  mesh.indices = {0, 1, 2};
  return mesh;
}

Vec3f ShadingNormal(const Scene& scene, uint32_t vertex_row) {
  return {scene.vertices.n_x[vertex_row], scene.vertices.n_y[vertex_row],
          scene.vertices.n_z[vertex_row]};
}

TEST(SceneLoaderMeshBuilder, TransformsPositionsAndNormals) {
  Scene scene;
  MeshData mesh = Triangle(true, false);
  mesh.normals[1] = Normalize(Vec3f{1, 1, 0});
  const Transform to_world = Transform::Translate({0, 0, 5}) * Transform::Scale({2, 1, 1});
  const MaterialRef material = scene.materials.AddDiffuse({0.5f, 0.5f, 0.5f});
  const uint32_t row = AddMesh(&scene, mesh, to_world, material, "tri");
  EXPECT_EQ(row, 0u);
  ASSERT_EQ(scene.triangles.size(), 1u);
  EXPECT_EQ(scene.triangles.V1(0), (Vec3f{2, 0, 5}));
  EXPECT_EQ(scene.triangles.V2(0), (Vec3f{0, 1, 5}));
  EXPECT_EQ(scene.shading.vertex1[0], 1u);
  // Inverse transpose of scale(2,1,1) maps (1,1,0) to (0.5,1,0), then renormalised.
  const Vec3f n = ShadingNormal(scene, 1);
  const Vec3f expected = Normalize(Vec3f{0.5f, 1, 0});
  EXPECT_NEAR(n.x, expected.x, 1e-6f);
  EXPECT_NEAR(n.y, expected.y, 1e-6f);
  EXPECT_EQ(n.z, 0.0f);
  EXPECT_EQ(scene.shading.material[0], material);
  EXPECT_EQ(scene.shading.mesh[0], 0u);
  EXPECT_EQ(scene.meshes.name[0], "tri");
  EXPECT_EQ(scene.meshes.has_normals[0], 1);
  EXPECT_EQ(scene.meshes.has_uvs[0], 0);
  EXPECT_FALSE(scene.meshes.emitter[0].valid());
  EXPECT_TRUE(scene.vertices.u.empty());
}

TEST(SceneLoaderMeshBuilder, MirroringKeepsWindingSoGeometricNormalFlips) {
  Scene scene;
  AddMesh(&scene, Triangle(true, false), Transform::Scale({-1, 1, 1}),
          MaterialRef::Make(MaterialTag::kDiffuse, 0), "m");
  const Vec3f v0 = scene.triangles.V0(0), v1 = scene.triangles.V1(0), v2 = scene.triangles.V2(0);
  EXPECT_EQ(v1, (Vec3f{-1, 0, 0}));  // same vertex order as the input
  const Vec3f geometric = Cross(v1 - v0, v2 - v0);
  EXPECT_LT(geometric.z, 0.0f);                          // was +z in object space
  EXPECT_EQ(ShadingNormal(scene, 0), (Vec3f{0, 0, 1}));  // shading normal stays +z
}

TEST(SceneLoaderMeshBuilder, VertexColumnsStayAligned) {
  Scene scene;
  const MaterialRef m = MaterialRef::Make(MaterialTag::kDiffuse, 0);
  AddMesh(&scene, Triangle(false, false), Transform(), m, "none");    // no vertex rows
  AddMesh(&scene, Triangle(true, false), Transform(), m, "normals");  // rows 0..2
  AddMesh(&scene, Triangle(false, true), Transform(), m, "uvs");      // rows 3..5
  AddMesh(&scene, Triangle(true, true), Transform(), m, "both");      // rows 6..8
  const VertexTable& v = scene.vertices;
  EXPECT_EQ(v.n_x.size(), 9u);
  EXPECT_EQ(v.n_z.size(), 9u);
  EXPECT_EQ(v.u.size(), 9u);
  EXPECT_EQ(v.v.size(), 9u);
  EXPECT_EQ(scene.shading.vertex0[0], kNoVertex);
  EXPECT_EQ(scene.shading.vertex2[0], kNoVertex);
  EXPECT_EQ(scene.shading.vertex0[1], 0u);
  EXPECT_EQ(scene.shading.vertex1[2], 4u);
  EXPECT_EQ(scene.shading.vertex2[3], 8u);
  EXPECT_EQ(v.n_z[0], 1.0f);
  EXPECT_EQ(v.u[0], 0.0f);    // zero-filled: mesh "normals" has no uvs
  EXPECT_EQ(v.u[4], 1.0f);    // mesh "uvs", vertex 1
  EXPECT_EQ(v.n_z[4], 0.0f);  // zero-filled: mesh "uvs" has no normals
  EXPECT_EQ(v.n_z[7], 1.0f);
  EXPECT_EQ(v.v[8], 1.0f);
  EXPECT_EQ(scene.meshes.first_triangle[3], 3u);
  EXPECT_EQ(scene.meshes.triangle_count[3], 1u);
  EXPECT_EQ(scene.meshes.has_uvs[2], 1);
  EXPECT_EQ(scene.meshes.has_normals[2], 0);
}

}  // namespace
}  // namespace ptlab
