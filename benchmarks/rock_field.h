// The benchmarks' many-object scene: a field of small closed rocks over a ground quad (no data
// files), a few million triangles in many small, separate objects, where the fractal terrain
// is one connected surface.
#pragma once

#include <cstdint>

#include "engine/scene/geometry_tables.h"

namespace ptlab {

/// Rocks in the benchmark field: 16,384 of them, 144 triangles each (2,359,298 triangles with
/// the ground's two).
inline constexpr uint32_t kRockFieldRocks = 16384;

/// Triangles of one rock: a latitude-longitude sphere of 12 slices and 8 rings of vertices
/// (two poles, six rings between), each vertex pushed in or out by up to 30 % of the radius.
inline constexpr uint32_t kRockTriangles = 144;

/// The ground quad over [-1.2, 1.2]^2 at z = -0.2 (two triangles), then `rocks` rocks, each a
/// closed mesh of kRockTriangles triangles: centres uniform in [-1, 1]^2 x [-0.2, 0.5] (the
/// lowest half sunk into the ground), radii 0.01-0.04, stretched 0.6-1.4 along each axis and
/// turned about a random axis. Deterministic (fixed seed): the same triangles every call.
TriangleTable MakeRockField(uint32_t rocks);

}  // namespace ptlab
