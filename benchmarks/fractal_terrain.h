// The benchmarks' 1 M-triangle fractal terrain (ridged fBm, no data files) and their view of it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/core/vec.h"
#include "engine/scene/geometry_tables.h"

namespace ptlab {

/// Grid size of the benchmark terrain: 725 x 725 vertices, 1,048,352 triangles.
inline constexpr int kTerrainGridSize = 725;

/// Vertices of a ridged fBm height field over [-1, 1]^2 (world units, z up), n x n of them
/// row-major: vertex (i, j) at [j n + i]. n >= 2.
std::vector<Vec3f> FractalTerrainVertices(int n);

/// The 2 (n-1)^2 triangles of the n x n grid as indices into FractalTerrainVertices: cell
/// (i, j) in row-major order gives triangles 2 c and 2 c + 1 (c = j (n-1) + i), split along
/// the diagonal from (i, j) to (i+1, j+1).
std::array<uint32_t, 3> FractalTerrainTriangle(int n, size_t triangle);

/// The terrain's triangles in that order (n = kTerrainGridSize: 1,048,352 of them).
TriangleTable MakeFractalTerrain(int n);

/// The camera the benchmarks look at the terrain with (Nori's lookat: +x to the image's left).
struct TerrainView {
  Vec3f eye, target, up;
  float fov_deg;  // horizontal
  int width, height;
};
inline constexpr TerrainView kTerrainView{
    {0.0f, -1.55f, 0.75f}, {0.0f, 0.2f, -0.05f}, {0.0f, 0.0f, 1.0f}, 50.0f, 768, 512};

}  // namespace ptlab
