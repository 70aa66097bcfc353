// Writers of binary PLY and Mitsuba .serialized bytes from MeshData, for tests, seeds and
// benchmarks.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "engine/io/mesh_builder.h"

namespace ptlab::test_util {

template <class T>
void AppendValue(std::string* out, T v, bool big_endian = false) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big_endian)
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  out->append(b, sizeof(T));
}

/// A binary PLY of `m` (float positions, normals and uvs when present; faces as uchar-counted
/// int lists), in either byte order.
inline std::string PlyBinaryBytes(const MeshData& m, bool big_endian) {
  std::string out = "ply\nformat ";
  out += big_endian ? "binary_big_endian" : "binary_little_endian";
  out += " 1.0\ncomment written by ptlab's tests\nelement vertex " +
         std::to_string(m.positions.size()) +
         "\nproperty float x\nproperty float y\nproperty float z\n";
  if (!m.normals.empty()) out += "property float nx\nproperty float ny\nproperty float nz\n";
  if (!m.uvs.empty()) out += "property float u\nproperty float v\n";
  out += "element face " + std::to_string(m.indices.size() / 3) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
  for (size_t i = 0; i < m.positions.size(); ++i) {
    for (float v : {m.positions[i].x, m.positions[i].y, m.positions[i].z})
      AppendValue(&out, v, big_endian);
    if (!m.normals.empty())
      for (float v : {m.normals[i].x, m.normals[i].y, m.normals[i].z})
        AppendValue(&out, v, big_endian);
    if (!m.uvs.empty())
      for (float v : {m.uvs[i].x, m.uvs[i].y}) AppendValue(&out, v, big_endian);
  }
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    out.push_back(char(3));
    for (size_t k = 0; k < 3; ++k) AppendValue(&out, int32_t(m.indices[t + k]), big_endian);
  }
  return out;
}

/// A Mitsuba .serialized file (version 3 or 4) of `shapes`, with the end-of-file dictionary.
/// uvs are written in Mitsuba's convention (v flipped), as LoadSerialized expects them.
/// `extra_flags` are OR-ed into the flag word (e.g. 0x0008 colours, written as zeros).
inline std::string SerializedBytes(const std::vector<MeshData>& shapes, int version, bool doubles,
                                   uint32_t extra_flags = 0) {
  std::string file;
  std::vector<uint64_t> offsets;
  for (const MeshData& m : shapes) {
    offsets.push_back(file.size());
    AppendValue(&file, uint16_t(0x041C));
    AppendValue(&file, uint16_t(version));
    std::string raw;
    const uint32_t flags = (m.normals.empty() ? 0u : 0x0001u) | (m.uvs.empty() ? 0u : 0x0002u) |
                           (doubles ? 0x2000u : 0u) | extra_flags;
    AppendValue(&raw, flags);
    if (version == 4) raw += std::string("mesh") + '\0';
    AppendValue(&raw, uint64_t(m.positions.size()));
    AppendValue(&raw, uint64_t(m.indices.size() / 3));
    const auto real = [&](float v) {
      if (doubles)
        AppendValue(&raw, double(v));
      else
        AppendValue(&raw, v);
    };
    for (const Vec3f& p : m.positions) real(p.x), real(p.y), real(p.z);
    for (const Vec3f& n : m.normals) real(n.x), real(n.y), real(n.z);
    for (const Vec2f& t : m.uvs) real(t.x), real(1.0f - t.y);  // Mitsuba's v convention
    if (extra_flags & 0x0008)
      for (size_t i = 0; i < 3 * m.positions.size(); ++i) real(0.5f);
    for (uint32_t i : m.indices) AppendValue(&raw, i);
    uLongf size = compressBound(uLong(raw.size()));
    std::string packed(size, '\0');
    compress2(reinterpret_cast<Bytef*>(packed.data()), &size,
              reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()), 6);
    packed.resize(size);
    file += packed;
  }
  for (uint64_t o : offsets) {
    if (version == 4)
      AppendValue(&file, o);
    else
      AppendValue(&file, uint32_t(o));
  }
  AppendValue(&file, uint32_t(shapes.size()));
  return file;
}

/// A grid of n x n quads (2 n² triangles) with normals and uvs.
inline MeshData GridMesh(int n) {
  MeshData m;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const float u = float(i) / float(n), v = float(j) / float(n);
      m.positions.push_back({u, v, 0.1f * u * v});
      m.normals.push_back({0.0f, 0.0f, 1.0f});
      m.uvs.push_back({u, v});
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n) + 1, d = c + 1;
      m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
    }
  }
  return m;
}

}  // namespace ptlab::test_util
