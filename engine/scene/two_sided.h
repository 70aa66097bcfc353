// Mitsuba `twosided`: which material rows are shaded on both sides (one flag column per tag).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/aligned.h"
#include "engine/scene/refs.h"

namespace ptlab {

/// A two-sided row is shaded as if the surface faced wo: where wo is below the shading surface
/// (wo.z < 0), the BSDF sees wo and wi with z negated and a sampled wi comes back with z
/// negated (Mitsuba's rule; the same BSDF on both sides). The flag is a wrapper applied in the
/// shading frame by the dispatch (engine/bsdf/bsdf.cpp) and by the batch kernels, not a model
/// of its own: one flag per (tag, row), stored per tag and empty until a row of that tag is
/// two-sided (so scenes without `twosided` pay one empty() test per batch).
struct TwoSidedFlags {
  AlignedVector<uint8_t> by_tag[kMaterialTagCount];

  void Set(MaterialRef ref) {
    AlignedVector<uint8_t>& c = by_tag[static_cast<int>(ref.tag())];
    if (c.size() <= ref.index()) c.resize(ref.index() + 1, uint8_t{0});
    c[ref.index()] = 1;
  }
  /// The flag column of a tag (nullptr when no row of the tag is two-sided); rows past its
  /// end are one-sided.
  const uint8_t* Column(MaterialTag tag, size_t* size) const {
    const AlignedVector<uint8_t>& c = by_tag[static_cast<int>(tag)];
    *size = c.size();
    return c.empty() ? nullptr : c.data();
  }
  bool Of(MaterialRef ref) const {
    const int t = static_cast<int>(ref.tag());
    if (t >= kMaterialTagCount) return false;
    const AlignedVector<uint8_t>& c = by_tag[t];
    return ref.index() < c.size() && c[ref.index()] != 0;
  }
};

}  // namespace ptlab
