// simd::BuildTriangleRows: each triangle's row holds its columns' values bit for bit, in the
// order simd/triangle_rows.h states; the normal rows hold VertexTable's normals.
#include "simd/triangle_rows.h"

#include <gtest/gtest.h>

#include <cstring>

#include "engine/scene/scene.h"

namespace ptlab::simd {
namespace {

uint32_t Bits(float f) {
  uint32_t b;
  std::memcpy(&b, &f, 4);
  return b;
}

TEST(TriangleRows, RowsHoldTheColumnsInOrder) {
  Scene scene;
  scene.meshes.emitter = {EmitterRef::None(), EmitterRef::Make(EmitterTag::kArea, 3)};
  for (uint32_t i = 0; i < 5; ++i) {
    const float f = float(i);
    scene.triangles.Append({f, f + 0.1f, f + 0.2f}, {-f, 1e-30f, 3.5f}, {f * 7, -0.0f, 1e30f});
    scene.shading.mesh.push_back(i % 2);
    scene.shading.material.push_back(MaterialRef::Make(MaterialTag(i % 3), i));
    scene.shading.vertex0.push_back(i == 3 ? kNoVertex : 3 * i);
    scene.shading.vertex1.push_back(3 * i + 1);
    scene.shading.vertex2.push_back(3 * i + 2);
  }
  for (int v = 0; v < 15; ++v) {
    scene.vertices.n_x.push_back(float(v)), scene.vertices.n_y.push_back(-float(v));
    scene.vertices.n_z.push_back(0.5f * float(v));
  }
  const TriangleRows rows = BuildTriangleRows(scene);
  ASSERT_EQ(rows.size(), 5u);
  ASSERT_EQ(rows.triangles.size(), 5 * kTriangleRowFloats);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(rows.triangles.data()) % 64, 0u);
  const TriangleTable& t = scene.triangles;
  for (size_t i = 0; i < 5; ++i) {
    const float* row = rows.triangles.data() + i * kTriangleRowFloats;
    const float want[9] = {t.v0_x[i], t.v0_y[i], t.v0_z[i], t.v1_x[i], t.v1_y[i],
                           t.v1_z[i], t.v2_x[i], t.v2_y[i], t.v2_z[i]};
    for (size_t c = 0; c < 9; ++c) EXPECT_EQ(Bits(row[kRowV0 + c]), Bits(want[c])) << i << c;
    EXPECT_EQ(Bits(row[kRowMaterial]), scene.shading.material[i].bits) << i;
    EXPECT_EQ(Bits(row[kRowEmitter]), scene.meshes.emitter[i % 2].bits) << i;
    EXPECT_EQ(Bits(row[kRowVertex0]), scene.shading.vertex0[i]) << i;
    EXPECT_EQ(Bits(row[kRowVertex0 + 1]), scene.shading.vertex1[i]) << i;
    EXPECT_EQ(Bits(row[kRowVertex0 + 2]), scene.shading.vertex2[i]) << i;
    EXPECT_EQ(Bits(row[14]), 0u);
    EXPECT_EQ(Bits(row[15]), 0u);
  }
  ASSERT_EQ(rows.normals.size(), 15u * 4);
  for (size_t v = 0; v < 15; ++v) {
    EXPECT_EQ(rows.normals[4 * v], scene.vertices.n_x[v]);
    EXPECT_EQ(rows.normals[4 * v + 1], scene.vertices.n_y[v]);
    EXPECT_EQ(rows.normals[4 * v + 2], scene.vertices.n_z[v]);
    EXPECT_EQ(rows.normals[4 * v + 3], 0.0f);
  }
  EXPECT_EQ(TriangleRowsBytes(rows), (5 * 16 + 15 * 4) * sizeof(float));
}

TEST(TriangleRows, NoNormalRowsWithoutVertexNormals) {
  Scene scene;
  scene.meshes.emitter = {EmitterRef::None()};
  scene.triangles.Append({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  scene.shading.mesh.push_back(0);
  scene.shading.material.push_back(MaterialRef::Make(MaterialTag(0), 0));
  scene.shading.vertex0.push_back(kNoVertex);
  scene.shading.vertex1.push_back(kNoVertex);
  scene.shading.vertex2.push_back(kNoVertex);
  const TriangleRows rows = BuildTriangleRows(scene);
  EXPECT_EQ(rows.size(), 1u);
  EXPECT_TRUE(rows.normals.empty());
}

}  // namespace
}  // namespace ptlab::simd
