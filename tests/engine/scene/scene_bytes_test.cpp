// Heap bytes of the scene tables and the BVHs: element size × rows of every column.
#include "engine/scene/scene_bytes.h"

#include <string>

#include <gtest/gtest.h>

#include "engine/bvh/bvh.h"
#include "engine/core/memory.h"
#include "simd/bvh8.h"
#include "tests/engine/bvh/test_meshes.h"

namespace ptlab {
namespace {

// Shrinks every column to its rows, so that the expected bytes are sizeof × rows; checks that
// the library did (shrink_to_fit may keep more, which would make the test meaningless).
template <typename Vector>
void ShrinkToRows(Vector& v) {
  v.shrink_to_fit();
  ASSERT_EQ(v.capacity(), v.size());
}
template <typename... Vectors>
void ShrinkAll(Vectors&... v) {
  (ShrinkToRows(v), ...);
}

TEST(SceneBytes, EqualElementSizeTimesRowsOfEveryColumn) {
  constexpr size_t kTriangles = 5, kVertices = 4;
  Scene s;
  for (size_t i = 0; i < kTriangles; ++i)
    s.triangles.Append({0, 0, 0}, {1, 0, 0}, {0, 1, float(i)});
  TriangleTable& t = s.triangles;
  ShrinkAll(t.v0_x, t.v0_y, t.v0_z, t.v1_x, t.v1_y, t.v1_z, t.v2_x, t.v2_y, t.v2_z);
  TriangleShadingTable& sh = s.shading;
  const MaterialRef diffuse = s.materials.AddDiffuse({0.5f, 0.5f, 0.5f});
  ShrinkAll(s.materials.diffuse.albedo_r, s.materials.diffuse.albedo_g,
            s.materials.diffuse.albedo_b);
  sh.mesh.assign(kTriangles, 0), sh.material.assign(kTriangles, diffuse);
  sh.vertex0.assign(kTriangles, 0), sh.vertex1.assign(kTriangles, 1);
  sh.vertex2.assign(kTriangles, 2);
  ShrinkAll(sh.mesh, sh.material, sh.vertex0, sh.vertex1, sh.vertex2);
  s.vertices.n_x.assign(kVertices, 0), s.vertices.n_y.assign(kVertices, 0);
  s.vertices.n_z.assign(kVertices, 1);  // normals, no uvs
  ShrinkAll(s.vertices.n_x, s.vertices.n_y, s.vertices.n_z);
  MeshTable& m = s.meshes;
  m.first_triangle = {0}, m.triangle_count = {uint32_t(kTriangles)}, m.material = {diffuse};
  m.emitter = {EmitterRef::None()}, m.has_normals = {1}, m.has_uvs = {0};
  m.name = {std::string(64, 'm')};  // longer than the short-string buffer
  ShrinkAll(m.first_triangle, m.triangle_count, m.material, m.emitter, m.has_normals, m.has_uvs,
            m.name);
  s.point_lights.position = {{0, 0, 2}}, s.point_lights.power = {{1, 1, 1}};
  s.emitters = {EmitterRef::Make(EmitterTag::kPoint, 0)};
  ShrinkAll(s.point_lights.position, s.point_lights.power, s.emitters);

  const SceneBytes b = SceneTableBytes(s);
  EXPECT_EQ(b.triangles, kTriangles * 9 * sizeof(float));
  EXPECT_EQ(b.spheres, 0u);
  EXPECT_EQ(b.shading,
            kTriangles * (3 * sizeof(uint32_t) + sizeof(uint32_t) + sizeof(MaterialRef)));
  EXPECT_EQ(b.vertices, kVertices * 3 * sizeof(float));
  EXPECT_EQ(b.materials, 3 * sizeof(float));
  EXPECT_EQ(b.meshes, 2 * sizeof(uint32_t) + sizeof(MaterialRef) + sizeof(EmitterRef) + 2 +
                          sizeof(std::string) + m.name[0].capacity() + 1);
  EXPECT_EQ(b.emitters, 2 * sizeof(Vec3f) + sizeof(EmitterRef));
  EXPECT_EQ(b.total(), b.triangles + b.shading + b.vertices + b.materials + b.meshes + b.emitters);
  EXPECT_EQ(TableBytes(s.triangles), b.triangles);
}

// A BVH holds exactly its rows (nodes, the leaf-ordered triangle copy, the prim ids): the builds
// leave no reserved slack; so does the BVH8 (its lines: nodes, packed leaves with their prim ids).
// Both grow with the number of triangles.
TEST(SceneBytes, BvhAndBvh8HoldTheirRowsOnlyAndGrowWithTriangles) {
  size_t last_bvh = 0, last_bvh8 = 0;
  for (int n : {4, 16, 64, 128}) {
    const TriangleTable grid = bvh_test::MakeFlatGrid(n).ToTable();
    const Bvh bvh = BuildBvh(grid);
    const simd::Bvh8 bvh8 = simd::BuildBvh8(bvh);
    const size_t tris = grid.size();
    EXPECT_EQ(BvhBytes(bvh), bvh.nodes.size() * sizeof(BvhNode) + tris * (9 + 1) * 4) << n;
    // The BVH8's lines hold its nodes and every triangle's ten packed columns, and are
    // allocated at their final size.
    EXPECT_GE(bvh8.lines.size() * sizeof(simd::Bvh8Line),
              bvh8.num_nodes * sizeof(simd::Bvh8Node) + simd::kBvh8LeafColumns * 4 * tris)
        << n;
    EXPECT_EQ(simd::Bvh8Bytes(bvh8), bvh8.lines.size() * sizeof(simd::Bvh8Line)) << n;
    EXPECT_GT(BvhBytes(bvh), last_bvh) << n;
    EXPECT_GT(simd::Bvh8Bytes(bvh8), last_bvh8) << n;
    last_bvh = BvhBytes(bvh), last_bvh8 = simd::Bvh8Bytes(bvh8);
  }
}

}  // namespace
}  // namespace ptlab
