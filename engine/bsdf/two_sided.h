// Mitsuba `twosided` in the shading frame: the row's BSDF on both sides of the surface.
#pragma once

#include "engine/core/vec.h"
#include "engine/scene/material_tables.h"

namespace ptlab {

/// z negated: the direction seen from the other side of the shading surface.
inline Vec3f FlipZ(const Vec3f& w) { return {w.x, w.y, -w.z}; }

/// True when `ref` is two-sided (TwoSidedFlags) and wo is below the shading surface: then the
/// row is shaded with wo, wi (and a sampled wi) mirrored through the surface.
inline bool TwoSidedFlips(const MaterialTables& m, MaterialRef ref, const Vec3f& wo) {
  return wo.z < 0 && m.two_sided.Of(ref);
}

}  // namespace ptlab
