// Texture components: one SoA row per texture (bitmap, checkerboard, mesh attribute), every
// row's data (texels, colors, per-triangle attribute values) in one aligned float array.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/aligned.h"

namespace ptlab {

/// "No texture" in a per-row texture-id column (engine/scene/material_tables.h).
inline constexpr uint32_t kNoTexture = 0xffffffffu;

/// What a texture row is (Mitsuba 3's plugins `bitmap`, `checkerboard`, `mesh_attribute`).
enum class TextureKind : uint8_t {
  kBitmap,           // width × height RGB texels, row 0 at the top of the image
  kCheckerboard,     // two colors
  kFaceAttribute,    // mesh_attribute "face_*": one RGB value per triangle
  kVertexAttribute,  // mesh_attribute "vertex_*": per triangle, the plane through its corners
};
enum class TextureFilter : uint8_t { kBilinear, kNearest };
enum class TextureWrap : uint8_t { kRepeat, kMirror, kClamp };

/// Floats per triangle of a kVertexAttribute row: the triangle's v0 (x, y, z), then per channel
/// (value at v0, gradient x, y, z) in world space, so that value(p) = a0 + g · (p − v0).
inline constexpr uint32_t kVertexAttributeFloats = 15;

/// One row per texture. Every row's data lives in `data` from `offset` on:
/// - kBitmap: width × height texels, 3 floats (linear RGB) each, row-major, row 0 at the top;
/// - kCheckerboard: color0 then color1 (3 floats each); width = height = 1;
/// - kFaceAttribute: 3 floats per triangle of scene rows [first, first + count) with
///   first = width, count = height (one mesh per mesh_attribute texture);
/// - kVertexAttribute: kVertexAttributeFloats per triangle of those rows, likewise.
/// `to_uv` (bitmap, checkerboard): uv' = (m00 u + m01 v + m02, m10 u + m11 v + m12).
struct TextureTable {
  AlignedVector<uint8_t> kind, filter, wrap;
  AlignedVector<float> m00, m01, m02, m10, m11, m12;
  AlignedVector<uint32_t> width, height, offset;
  AlignedVector<float> data;

  size_t size() const { return kind.size(); }
  bool empty() const { return kind.empty(); }
  TextureKind Kind(size_t i) const { return TextureKind(kind[i]); }

  /// Appends a row whose data is `count` floats at the end of `data` (zero-filled); returns
  /// its id. The caller fills the data and the kind-specific fields.
  uint32_t AddRow(TextureKind k, uint32_t w, uint32_t h, size_t count) {
    kind.push_back(uint8_t(k));
    filter.push_back(uint8_t(TextureFilter::kBilinear));
    wrap.push_back(uint8_t(TextureWrap::kRepeat));
    m00.push_back(1), m01.push_back(0), m02.push_back(0);
    m10.push_back(0), m11.push_back(1), m12.push_back(0);
    width.push_back(w), height.push_back(h), offset.push_back(uint32_t(data.size()));
    data.resize(data.size() + count, 0.0f);
    return uint32_t(kind.size() - 1);
  }
};

}  // namespace ptlab
