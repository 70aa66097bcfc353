// Stanford PLY loading (ASCII and binary; positions, normals, uvs, other properties) into MeshData.
#pragma once

#include <string>

#include "engine/core/status.h"
#include "engine/io/mesh_builder.h"

namespace ptlab {

/// Loads a PLY file (format ascii, binary_little_endian or binary_big_endian 1.0) into
/// object-space MeshData, one vertex per vertex row of the file, in file order.
///
/// Element "vertex": properties x, y, z (required, finite); nx, ny, nz (all three or none;
/// finite and non-zero); uvs from u/v, s/t, texture_u/texture_v or texture_s/texture_t.
/// Element "face": a list property vertex_indices (or vertex_index) of 3 or more indices in
/// [0, vertex count), fan-triangulated as (0, k, k + 1). Every other scalar property of the two
/// elements becomes a MeshAttribute ("vertex_..." / "face_...", see mesh_attribute.h) grouped as
/// Mitsuba groups them: consecutive `P_x P_y [P_z [P_w]]`, `P_r P_g ...`, `P_0 P_1 ...` or
/// `P_1 P_2 ...` form one attribute "vertex_P" of that many channels; `r g b [a]` and
/// `red green blue [alpha]` form "vertex_color"; any other property `N` is "vertex_N" with one
/// channel. Other list properties and other elements are read and skipped.
/// uvs are returned as the file has them. Note for scene loaders: Mitsuba's ply plugin takes a
/// PLY's v as is into its internal convention (flip_tex_coords defaults to false) while its obj
/// plugin flips an OBJ's v (flip_tex_coords defaults to true), so the same numbers in a PLY and
/// an OBJ map a texture upside down relative to each other in Mitsuba.
/// Scalar types: char/int8, uchar/uint8, short/int16, ushort/uint16, int/int32, uint/uint32,
/// float/float32, double/float64.
///
/// Errors name the file and where: "path:LINE: ..." in the header and ASCII data,
/// "path: byte N: ..." in binary data, and say what was expected. Every element's row count is
/// checked against the bytes left before anything is allocated for it.
StatusOr<MeshData> LoadPly(const std::string& path);

/// As LoadPly, from the file's bytes in memory; `display_name` names it in messages.
StatusOr<MeshData> LoadPlyFromBytes(const std::string& bytes, const std::string& display_name);

}  // namespace ptlab
