// The benchmarks' fractal terrain: value noise summed as ridged fBm over a regular grid.
#include "benchmarks/fractal_terrain.h"

#include <cmath>

namespace ptlab {
namespace {

float Hash2(int x, int y) {
  uint32_t h = static_cast<uint32_t>(x) * 0x8da6b343u ^ static_cast<uint32_t>(y) * 0xd8163841u;
  h = (h ^ (h >> 13)) * 0x85ebca6bu;
  h ^= h >> 16;
  return static_cast<float>(h & 0xffffffu) * 0x1p-24f;
}

// Value noise with a smooth fade, in [0, 1).
float ValueNoise(float x, float y) {
  const float fx = std::floor(x), fy = std::floor(y);
  const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
  const float tx = x - fx, ty = y - fy;
  const float sx = tx * tx * (3 - 2 * tx), sy = ty * ty * (3 - 2 * ty);
  const float a = Hash2(ix, iy), b = Hash2(ix + 1, iy), c = Hash2(ix, iy + 1),
              d = Hash2(ix + 1, iy + 1);
  return (a + (b - a) * sx) + ((c + (d - c) * sx) - (a + (b - a) * sx)) * sy;
}

}  // namespace

std::vector<Vec3f> FractalTerrainVertices(int n) {
  std::vector<Vec3f> v(static_cast<size_t>(n) * n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const float x = -1.0f + 2.0f * static_cast<float>(i) / static_cast<float>(n - 1);
      const float y = -1.0f + 2.0f * static_cast<float>(j) / static_cast<float>(n - 1);
      float h = 0.0f, amp = 0.5f, freq = 3.0f;
      for (int o = 0; o < 9; ++o) {
        const float r = 1.0f - std::fabs(2.0f * ValueNoise(x * freq + 17.0f * o, y * freq) - 1.0f);
        h += amp * r * r;
        amp *= 0.5f;
        freq *= 2.03f;
      }
      v[static_cast<size_t>(j) * n + i] = {x, y, 0.45f * h - 0.2f};
    }
  }
  return v;
}

std::array<uint32_t, 3> FractalTerrainTriangle(int n, size_t triangle) {
  const size_t cell = triangle / 2, cells = static_cast<size_t>(n - 1);
  const uint32_t i = static_cast<uint32_t>(cell % cells), j = static_cast<uint32_t>(cell / cells);
  const auto at = [n](uint32_t x, uint32_t y) { return y * static_cast<uint32_t>(n) + x; };
  if (triangle % 2 == 0) return {at(i, j), at(i + 1, j), at(i + 1, j + 1)};
  return {at(i, j), at(i + 1, j + 1), at(i, j + 1)};
}

TriangleTable MakeFractalTerrain(int n) {
  const std::vector<Vec3f> v = FractalTerrainVertices(n);
  TriangleTable t;
  const size_t count = 2 * static_cast<size_t>(n - 1) * static_cast<size_t>(n - 1);
  for (size_t k = 0; k < count; ++k) {
    const std::array<uint32_t, 3> c = FractalTerrainTriangle(n, k);
    t.Append(v[c[0]], v[c[1]], v[c[2]]);
  }
  return t;
}

}  // namespace ptlab
