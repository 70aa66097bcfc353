// Mitsuba's .serialized meshes (zlib-compressed, format versions 3 and 4) into MeshData.
#pragma once

#include <cstdint>
#include <string>

#include "engine/core/status.h"
#include "engine/io/mesh_builder.h"

namespace ptlab {

/// Loads shape `shape_index` of a Mitsuba .serialized file into object-space MeshData.
///
/// The format (little endian), as Mitsuba 0.5-0.6 write it and Mitsuba 3 reads it: each shape is
/// a header — uint16 0x041C, uint16 version (3 or 4) — then a zlib stream holding: uint32 flags
/// (0x0001 vertex normals, 0x0002 uvs, 0x0008 vertex colours, 0x0010 use face normals, 0x2000
/// double precision), the shape's name as a NUL-terminated string (version 4 only), uint64 vertex
/// count V, uint64 triangle count F, then V positions (3 floats or doubles each), V normals, V uvs
/// (2 each), V colours (3 each; read and dropped), each only when its flag is set, and 3 F uint32
/// vertex indices. Shapes are concatenated; the file ends with the offset of every shape (uint64
/// in version 4, uint32 in version 3) and a uint32 shape count, which locate shape_index > 0.
/// uvs are returned in the OBJ convention of LoadObj, v = 1 - stored: Mitsuba stores its
/// internal convention, into which its obj plugin flips an OBJ file's v.
/// With flag 0x0010 the normals are dropped (the mesh is shaded with face normals, as Mitsuba
/// does). Version 5 (Mitsuba 3's newer packed records) is refused with a clear error.
///
/// Errors name the file, the shape, the byte offset (in the file, and in the shape's
/// decompressed stream) and what was expected. Counts are checked before allocation: V and F
/// must be below 2^32, and the bytes they need may not exceed what the compressed bytes left
/// can hold (deflate expands at most 1032:1), so a small file cannot ask for gigabytes.
StatusOr<MeshData> LoadSerialized(const std::string& path, uint32_t shape_index);

/// As LoadSerialized, from the file's bytes in memory; `display_name` names it in messages.
StatusOr<MeshData> LoadSerializedFromBytes(const std::string& bytes, uint32_t shape_index,
                                           const std::string& display_name);

}  // namespace ptlab
