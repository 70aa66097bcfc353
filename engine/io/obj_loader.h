// Wavefront OBJ loading (positions, normals, uvs; polygons fan-triangulated) into MeshData.
#pragma once

#include <string>

#include "engine/core/status.h"
#include "engine/io/mesh_builder.h"

namespace ptlab {

/// Loads an OBJ file into object-space MeshData with a deduplicated vertex list: each distinct
/// (position, uv, normal) index triple of the file becomes one vertex, numbered in order of
/// first use. Polygons are triangulated as fans (0, k, k+1), in file order. Unreferenced
/// positions are dropped. `o`, `g`, `s`, `mtllib`, `usemtl` lines and `l`/`p` elements are
/// ignored; materials are not read.
///
/// Accepted: `v x y z [w]` or `v x y z r g b` (w and colours ignored), `vn x y z` (non-zero),
/// `vt u v [w]`, `f` with 3 or more vertices written `p`, `p/t`, `p//n` or `p/t/n`
/// (1-based; negative = relative to the elements defined so far; positive indices may refer
/// forward, as in Nori). Either every face vertex has a normal index or none does; the same for
/// uvs. Numbers must be finite decimal floats ("nan", "inf", "1.2.3", "1x" are errors).
///
/// Errors name the file (as given) and the line and say what was expected:
/// "path:12: expected ...". An unreadable file and a file without faces are errors too.
/// Parsing is done by tinyobjloader after a line-by-line validation pass (which is what gives
/// exact line numbers).
StatusOr<MeshData> LoadObj(const std::string& path);

/// As LoadObj, from OBJ text in memory; `display_name` stands for the file name in messages.
StatusOr<MeshData> LoadObjFromString(const std::string& text, const std::string& display_name);

}  // namespace ptlab
