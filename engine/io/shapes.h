// Mitsuba-style procedural shapes (sphere, rectangle, cube, disk) tessellated into MeshData.
#pragma once

#include "engine/core/vec.h"
#include "engine/io/mesh_builder.h"

namespace ptlab {

/// Longitude segments and latitude rings of the UV sphere.
inline constexpr int kSphereSegments = 64;
inline constexpr int kSphereRings = 32;
/// Rim segments of the disk.
inline constexpr int kDiskSegments = 64;

/// All shapes are returned in object space (the loader applies `toWorld` with AddMesh), with
/// outward, counter-clockwise winding: normalize(cross(v1 - v0, v2 - v0)) is the outward
/// normal, and the per-vertex normals point the same way. Vertices shared by neighbouring
/// triangles have bit-identical positions (seams and poles included), so the meshes are
/// watertight.

/// UV sphere of `radius` around `center`: kSphereRings rings in θ (polar angle from +z) and
/// kSphereSegments segments in φ (from +x towards +y); p = center + radius·(sinθcosφ,
/// sinθsinφ, cosθ). The pole rows are single triangles, the other rows two per cell, so
/// there are 2·kSphereSegments·(kSphereRings−1) = 3968 triangles. Smooth normals (p − center)
/// / radius, uv = (φ/2π, θ/π); the seam column φ = 2π and the poles are duplicated per
/// segment for their uvs. The area is slightly below 4π·radius² (inscribed polyhedron).
/// Precondition: radius > 0.
MeshData MakeSphere(const Vec3f& center, float radius);

/// The square [-1,1]² in the z = 0 plane, normal +z, 4 vertices, 2 triangles, area 4;
/// uv = ((x+1)/2, (y+1)/2).
MeshData MakeRectangle();

/// The cube [-1,1]³: 6 faces × 4 vertices with flat outward normals, 12 triangles, area 24;
/// per-face uv (0,0), (1,0), (1,1), (0,1).
MeshData MakeCube();

/// The unit disk in the z = 0 plane, normal +z: a centre vertex and kDiskSegments rim vertices
/// at angles 2πi/kDiskSegments, kDiskSegments triangles (area (n/2)·sin(2π/n) ≈ 0.9984·π for
/// n = 64); uv = ((x+1)/2, (y+1)/2).
MeshData MakeDisk();

/// As MakeDisk with `segments` (>= 3) rim vertices: the Mitsuba loader's finer disk.
MeshData MakeDisk(int segments);

}  // namespace ptlab
