// The triangles as the SIMD hit kernels read them: one cache line per triangle.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/aligned.h"
#include "engine/scene/scene.h"

namespace ptlab::simd {

/// Floats in a triangle's row: v0, v1, v2 (x, y, z each), then the bits of its MaterialRef,
/// its mesh's EmitterRef and its three VertexTable rows, then two zeros. 64 bytes.
inline constexpr size_t kTriangleRowFloats = 16;
/// Column offsets inside a row.
inline constexpr size_t kRowV0 = 0, kRowMaterial = 9, kRowEmitter = 10, kRowVertex0 = 11;

/// A copy of the scene's triangles for the kernels that look up eight hits at once (simd/
/// interaction8): eight hits read eight rows and transpose them, instead of gathering fourteen
/// columns of TriangleTable, TriangleShadingTable and MeshTable (a gather is one load per
/// lane). Vertex normals likewise, one 16-byte row per VertexTable row. The oracle keeps
/// reading the columns; the SIMD kernel table needs these (simd/wavefront/kernels8.h).
struct TriangleRows {
  AlignedVector<float> triangles;  // kTriangleRowFloats per scene triangle, 64-byte aligned
  AlignedVector<float> normals;    // (n_x, n_y, n_z, 0) per vertex; empty without normals

  size_t size() const { return triangles.size() / kTriangleRowFloats; }
};

/// The rows of `scene`'s triangles and vertex normals (the columns' values bit for bit).
TriangleRows BuildTriangleRows(const Scene& scene);

/// Heap bytes of the rows (for the render's memory statistics).
size_t TriangleRowsBytes(const TriangleRows& rows);

}  // namespace ptlab::simd
