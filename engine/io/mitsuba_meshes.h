// Mitsuba 3's disk and cylinder tessellated into MeshData, with Mitsuba's uv parameterisation.
#pragma once

#include "engine/io/mesh_builder.h"

namespace ptlab {

/// The unit disk in the z = 0 plane, normal +z, as MakeDisk(segments) (the same triangles, bit
/// for bit: a fan around the centre over `segments` >= 3 rim vertices at φ = 2πi/segments),
/// with Mitsuba's uv = (r, φ/2π): the centre is one vertex per triangle (v at the triangle's
/// middle angle) and the rim vertex at φ = 0 is repeated at the end with v = 1.
MeshData MakeMitsubaDisk(int segments);

/// Mitsuba's open cylinder of radius 1 around the z axis from z = 0 to z = 1 (no caps),
/// `segments` >= 3 quads of two triangles around it, each facing outward; vertex normals
/// (cos φ, sin φ, 0); uv = (φ/2π, z), the seam φ = 2π repeating φ = 0's positions exactly.
/// The area is 2π·sin(π/n)/(π/n) (n = segments): 1.6e-6 below 2π for n = 1024.
MeshData MakeMitsubaCylinder(int segments);

/// Mitsuba's cube [-1, 1]³: six faces of 4 vertices (face normals, flat) and 2 triangles, each
/// face's uv spanning [0, 1]² in Mitsuba's orientation: uv (0, 0) at the corner o and u, v
/// growing along the axes U, V (per face n: o; U, V) — −y: (−1,−1,−1); +z, +x. +y: (1,1,1);
/// −x, −z. +x: (1,−1,1); +y, −z. +z: (−1,−1,1); +y, +x. −x: (−1,−1,−1); +y, +z. −z: (−1,1,−1);
/// −y, +x. (Read off Mitsuba 3's cube.cpp vertex table; a checkerboard with an odd number of
/// checks per face shows any flip.)
MeshData MakeMitsubaCube();

}  // namespace ptlab
