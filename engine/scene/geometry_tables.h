// Geometry components: hot triangle positions (traversal), cold shading data, and meshes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/aligned.h"
#include "engine/core/vec.h"
#include "engine/scene/refs.h"

namespace ptlab {

inline constexpr uint32_t kNoVertex = 0xffffffffu;

/// Hot component: world-space vertex positions, one row per triangle. Vertices are stored
/// (not edges) so that two triangles sharing an edge see bit-identical endpoints, which the
/// watertight intersection test needs.
struct TriangleTable {
  AlignedVector<float> v0_x, v0_y, v0_z, v1_x, v1_y, v1_z, v2_x, v2_y, v2_z;

  size_t size() const { return v0_x.size(); }
  void Append(const Vec3f& a, const Vec3f& b, const Vec3f& c) {
    v0_x.push_back(a.x), v0_y.push_back(a.y), v0_z.push_back(a.z);
    v1_x.push_back(b.x), v1_y.push_back(b.y), v1_z.push_back(b.z);
    v2_x.push_back(c.x), v2_y.push_back(c.y), v2_z.push_back(c.z);
  }
  Vec3f V0(size_t i) const { return {v0_x[i], v0_y[i], v0_z[i]}; }
  Vec3f V1(size_t i) const { return {v1_x[i], v1_y[i], v1_z[i]}; }
  Vec3f V2(size_t i) const { return {v2_x[i], v2_y[i], v2_z[i]}; }
};

/// Per-vertex shading attributes (world space), referenced by TriangleShadingTable.
/// A column is empty when no mesh in the scene has that attribute.
struct VertexTable {
  AlignedVector<float> n_x, n_y, n_z;  // unit shading normals
  AlignedVector<float> u, v;           // texture coordinates
};

/// Cold component: what shading reads after a hit, one row per triangle (same row ids as
/// TriangleTable).
struct TriangleShadingTable {
  AlignedVector<uint32_t> mesh;  // row in MeshTable
  AlignedVector<MaterialRef> material;
  /// Rows in VertexTable for normals/uvs; kNoVertex when the mesh has none.
  AlignedVector<uint32_t> vertex0, vertex1, vertex2;

  size_t size() const { return mesh.size(); }
};

/// One row per loaded shape: its triangle range, material and (optional) emitter.
struct MeshTable {
  std::vector<uint32_t> first_triangle, triangle_count;
  std::vector<MaterialRef> material;
  std::vector<EmitterRef> emitter;  // EmitterRef::None() if the mesh does not emit
  std::vector<uint8_t> has_normals, has_uvs;
  std::vector<std::string> name;  // source file or shape type, for messages

  size_t size() const { return first_triangle.size(); }
};

}  // namespace ptlab
