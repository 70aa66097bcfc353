// Mitsuba `blendbsdf` rows: a mixture (1 − w) f_first + w f_second of two materials (SoA).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/aligned.h"
#include "engine/scene/refs.h"

namespace ptlab {

/// weight ∈ [0, 1] (0: only `first`, 1: only `second`); first / second are MaterialRef bits of
/// rows added before this one (so the children of a row never lead back to it).
struct BlendTable {
  AlignedVector<float> weight;
  AlignedVector<uint32_t> first, second;
  size_t size() const { return weight.size(); }
  uint32_t Add(float w, MaterialRef a, MaterialRef b) {
    weight.push_back(w), first.push_back(a.bits), second.push_back(b.bits);
    return uint32_t(size() - 1);
  }
  MaterialRef First(size_t i) const { return MaterialRef{first[i]}; }
  MaterialRef Second(size_t i) const { return MaterialRef{second[i]}; }
};

}  // namespace ptlab
