// MeshAttribute: a named per-vertex or per-triangle float column of a mesh file (PLY properties).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ptlab {

/// A mesh attribute as Mitsuba names them for its mesh_attribute texture: "vertex_<prefix>" or
/// "face_<prefix>" ("vertex_color", "face_weight"), `dim` (1 to 4) floats per row. Vertex
/// attributes have one row per MeshData vertex; face attributes one row per MeshData triangle
/// (a polygon's row repeated for each triangle of its fan), so that a hit's vertex indices or
/// triangle index within the mesh selects the row. Integer-typed properties are stored as
/// Mitsuba does: divided by the type's maximum, then decoded from sRGB to linear.
struct MeshAttribute {
  std::string name;
  uint32_t dim = 1;
  std::vector<float> values;  ///< rows × dim, row-major

  bool is_face() const { return name.starts_with("face_"); }
  size_t rows() const { return dim > 0 ? values.size() / dim : 0; }
};

}  // namespace ptlab
