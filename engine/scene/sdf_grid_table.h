// Signed-distance grids (Mitsuba 3's `sdfgrid` shape): a grid of signed distances whose surface
// is the zero set of their trilinear interpolant over the unit box [0, 1]^3 of object space.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/core/aligned.h"
#include "engine/core/transform.h"
#include "engine/core/vec.h"
#include "engine/scene/refs.h"

namespace ptlab {

/// How an sdfgrid's shading normal is made (Mitsuba's `normals` property).
enum class SdfNormals : uint8_t {
  kAnalytic,  // the gradient of the trilinear interpolant of the hit's cell (= the geometric one)
  kSmooth,    // the cell gradients of the 8 cells around the nearest grid point, unit, blended
              // trilinearly (Hansson-Söderlund, Evans & Akenine-Möller, JCGT 11(3), 2022)
};

/// One row per placed grid (an instanced grid is one row per instance), world space through
/// its to_world. Grid point (i, j, k) of an nx × ny × nz grid sits at object point
/// (i / (nx − 1), j / (ny − 1), k / (nz − 1)); its value is
/// values[offset + (k ny + j) nx + i] (x fastest, the order of Mitsuba's .vol files). Grids
/// never emit and have no surface coordinates (uv = (0, 0), as in Mitsuba).
struct SdfGridTable {
  std::vector<uint32_t> nx, ny, nz, offset;  // per row: grid points per axis (>= 2), first value
  std::vector<Transform> to_world;           // per row: object [0, 1]^3 -> world
  std::vector<MaterialRef> material;
  std::vector<SdfNormals> normals;
  AlignedVector<float> values;  // all rows' grid values

  size_t size() const { return nx.size(); }
  float Value(size_t row, uint32_t i, uint32_t j, uint32_t k) const {
    return values[offset[row] + (size_t(k) * ny[row] + j) * nx[row] + i];
  }
  /// A copy of row `from` of `src` (its values too) placed by `to_world`.
  void AppendPlaced(const SdfGridTable& src, size_t from, const Transform& placed,
                    MaterialRef m) {
    nx.push_back(src.nx[from]), ny.push_back(src.ny[from]), nz.push_back(src.nz[from]);
    offset.push_back(uint32_t(values.size()));
    const size_t n = size_t(src.nx[from]) * src.ny[from] * src.nz[from];
    values.insert(values.end(), src.values.begin() + src.offset[from],
                  src.values.begin() + src.offset[from] + n);
    to_world.push_back(placed);
    material.push_back(m);
    normals.push_back(src.normals[from]);
  }
  void Append(uint32_t x, uint32_t y, uint32_t z, const std::vector<float>& v,
              const Transform& t, MaterialRef m, SdfNormals how) {
    nx.push_back(x), ny.push_back(y), nz.push_back(z);
    offset.push_back(uint32_t(values.size()));
    values.insert(values.end(), v.begin(), v.end());
    to_world.push_back(t);
    material.push_back(m);
    normals.push_back(how);
  }
  void Truncate(size_t rows) {
    if (rows >= size()) return;
    values.resize(offset[rows]);
    for (auto* c : {&nx, &ny, &nz, &offset}) c->resize(rows);
    to_world.resize(rows), material.resize(rows), normals.resize(rows);
  }
};

}  // namespace ptlab
