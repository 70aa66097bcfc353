// COLLADA <geometry>: <mesh> primitives to MeshData, and the CGL sphere extra.
#pragma once

#include <pugixml.hpp>
#include <string>
#include <vector>

#include "engine/core/status.h"
#include "engine/io/collada_document.h"
#include "engine/io/mesh_builder.h"

namespace ptlab::collada {

/// One primitive element (polylist, triangles, polygons) of a <mesh>, triangulated, in object
/// space, with the material symbol it names ("" when none).
struct MeshPart {
  std::string material_symbol;
  MeshData mesh;
  pugi::xml_node node;
};

/// What a <geometry> holds: mesh parts, or a CGL sphere (radius > 0 about the origin).
struct Geometry {
  std::vector<MeshPart> parts;
  bool is_sphere = false;
  float sphere_radius = 0;
};

/// Reads a <geometry>. Sources are read through their accessor (count, stride, offset; the
/// first 3 params for POSITION and NORMAL, the first 2 for TEXCOORD); a vertex is one distinct
/// index tuple, polygons are fan-triangulated. Errors: accessors reaching past their array,
/// float_array counts that disagree with their text, indices out of range, polygons with fewer
/// than 3 vertices, zero-length normals, and unsupported elements (lines, tristrips, ...).
StatusOr<Geometry> ReadGeometry(const Document& doc, const pugi::xml_node& geometry);

}  // namespace ptlab::collada
