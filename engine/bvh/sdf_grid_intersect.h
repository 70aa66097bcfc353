// Ray-sdfgrid intersection (scalar oracle; simd/traverse8 runs it per lane) and sdfgrid hit ids.
#pragma once

#include <cstdint>

#include "engine/bvh/bvh.h"
#include "engine/core/ray.h"
#include "engine/scene/sdf_grid_table.h"

namespace ptlab {

/// Hit::prim of a hit on sdfgrid row i is kSphereHitBit | kSdfGridHitBit | i: an analytic hit
/// (bit 31, so the triangle-only paths skip it as they skip spheres), told apart from a sphere
/// by bit 30, which no sphere row (< kMaxSpheres = 2^28) sets.
inline constexpr uint32_t kSdfGridHitBit = 0x40000000u;
inline constexpr uint32_t kMaxSdfGrids = 1u << 16;
constexpr bool IsSdfGridHit(uint32_t prim) {
  return prim != kNoHit && (prim & 0x80000000u) && (prim & kSdfGridHitBit);
}
constexpr uint32_t SdfGridHitRow(uint32_t prim) { return prim & ~(0x80000000u | kSdfGridHitBit); }

/// The first t in the open interval (ray.t_min, t_max) where `ray` meets the zero set of grid
/// `row`'s trilinear interpolant; false when there is none. In double: the ray goes into index
/// space (grid point (i, j, k) at (i, j, k)) through the inverse of to_world, is clipped to the
/// grid's box, and walks its cells front to back (3D DDA, Amanatides & Woo). A cell whose eight
/// values are all > 0 or all < 0 is skipped (Mitsuba's occupancy rule); in the others the
/// interpolant along the ray is a cubic in t, split at the roots of its derivative into
/// monotone pieces, and the first piece whose ends differ in sign (or touch 0) is bisected to
/// double precision. t is that root rounded to float.
bool IntersectSdfGrid1(const SdfGridTable& grids, uint32_t row, const Ray& ray, float t_max,
                       float* t);

/// Closest sdfgrid hit before *t_max, rows in order, strictly nearer only (as the spheres').
bool IntersectSdfGrids1(const SdfGridTable& grids, const Ray& ray, float* t_max, uint32_t* prim);

/// True when `ray` meets any grid's surface with t in (ray.t_min, ray.t_max).
bool OccludedSdfGrids1(const SdfGridTable& grids, const Ray& ray);

}  // namespace ptlab
