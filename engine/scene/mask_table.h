// Mitsuba `mask` rows: a nested material seen with probability `opacity`, else passed through.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/aligned.h"
#include "engine/scene/refs.h"
#include "engine/scene/texture_tables.h"

namespace ptlab {

/// opacity ∈ [0, 1] (1: only the nested material, 0: fully transparent); `nested` is the
/// MaterialRef bits of a row added before this one. opacity_texture is the textured-parameter
/// column (docs/materials.md "Textured parameters"): empty while no row is textured.
struct MaskTable {
  AlignedVector<float> opacity;
  AlignedVector<uint32_t> opacity_texture;
  AlignedVector<uint32_t> nested;
  size_t size() const { return opacity.size(); }
  bool textured() const { return !opacity_texture.empty(); }
  MaterialRef Nested(size_t i) const { return MaterialRef{nested[i]}; }
  /// A row with a constant opacity, or (texture != kNoTexture) one driven by that texture.
  uint32_t Add(float o, MaterialRef child, uint32_t texture = kNoTexture) {
    opacity.push_back(o), nested.push_back(child.bits);
    if (texture != kNoTexture || textured()) {
      opacity_texture.resize(size() - 1, kNoTexture);
      opacity_texture.push_back(texture);
    }
    return uint32_t(size() - 1);
  }
};

}  // namespace ptlab
