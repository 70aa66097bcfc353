// Mitsuba `blendbsdf` rows: a mixture (1 − w) f_first + w f_second of two materials (SoA).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/aligned.h"
#include "engine/scene/refs.h"
#include "engine/scene/texture_tables.h"

namespace ptlab {

/// weight ∈ [0, 1] (0: only `first`, 1: only `second`); first / second are MaterialRef bits of
/// rows added before this one (so the children of a row never lead back to it).
struct BlendTable {
  AlignedVector<float> weight;
  AlignedVector<uint32_t> first, second;
  // mask: the textured weight's texture-id column (docs/materials.md "Textured parameters"),
  // empty while no row's weight is a texture.
  AlignedVector<uint32_t> weight_texture;
  size_t size() const { return weight.size(); }
  bool textured() const { return !weight_texture.empty(); }
  uint32_t Add(float w, MaterialRef a, MaterialRef b, uint32_t texture = kNoTexture) {
    weight.push_back(w), first.push_back(a.bits), second.push_back(b.bits);
    if (texture != kNoTexture || textured()) {  // mask: a textured weight
      weight_texture.resize(size() - 1, kNoTexture);
      weight_texture.push_back(texture);
    }
    return uint32_t(size() - 1);
  }
  MaterialRef First(size_t i) const { return MaterialRef{first[i]}; }
  MaterialRef Second(size_t i) const { return MaterialRef{second[i]}; }
};

}  // namespace ptlab
