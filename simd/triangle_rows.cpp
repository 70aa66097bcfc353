// The SIMD hit kernels' triangle rows (plain C++: no Highway code here).
#include "simd/triangle_rows.h"

#include <cstring>

#include "engine/core/memory.h"

namespace ptlab::simd {

static_assert(sizeof(MaterialRef) == 4 && sizeof(EmitterRef) == 4 && sizeof(uint32_t) == 4,
              "a row holds the refs' bits as floats");
static_assert(sizeof(TriangleRows) == 2 * sizeof(AlignedVector<float>),
              "a member added to TriangleRows must be counted in TriangleRowsBytes");

TriangleRows BuildTriangleRows(const Scene& scene) {
  const TriangleTable& t = scene.triangles;
  const TriangleShadingTable& sh = scene.shading;
  TriangleRows rows;
  rows.triangles.resize(t.size() * kTriangleRowFloats);
  for (size_t i = 0; i < t.size(); ++i) {
    float* row = rows.triangles.data() + i * kTriangleRowFloats;
    const float v[9] = {t.v0_x[i], t.v0_y[i], t.v0_z[i], t.v1_x[i], t.v1_y[i],
                        t.v1_z[i], t.v2_x[i], t.v2_y[i], t.v2_z[i]};
    std::memcpy(row + kRowV0, v, sizeof(v));
    const uint32_t refs[5] = {sh.material[i].bits, scene.meshes.emitter[sh.mesh[i]].bits,
                              sh.vertex0[i], sh.vertex1[i], sh.vertex2[i]};
    std::memcpy(row + kRowMaterial, refs, sizeof(refs));
  }
  const VertexTable& vt = scene.vertices;
  rows.normals.resize(vt.n_x.size() * 4);
  for (size_t i = 0; i < vt.n_x.size(); ++i) {
    float* row = rows.normals.data() + i * 4;
    row[0] = vt.n_x[i], row[1] = vt.n_y[i], row[2] = vt.n_z[i];
  }
  return rows;
}

size_t TriangleRowsBytes(const TriangleRows& rows) {
  return VectorsBytes(rows.triangles, rows.normals);
}

}  // namespace ptlab::simd
