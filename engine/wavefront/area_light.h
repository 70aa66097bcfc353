// Emitter stage, area lights: the batch of area-light samples a wave draws (the columns it
// reads and writes) and the scalar oracle, SampleAreaLight (engine/light/area_light.h) row by
// row; SIMD twin simd::SampleAreaLightBatch (simd/wavefront/area_light8.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/light/area_light.h"

namespace ptlab {

/// A batch of area-light samples as columns, row i: light[i] (row in AreaLightTable), the
/// reference point ref (x, y, z) and the numbers u (x, y) of SampleAreaLight.
struct AreaLightBatchInputs {
  const uint32_t* light = nullptr;
  const float *ref_x = nullptr, *ref_y = nullptr, *ref_z = nullptr;
  const float *u_x = nullptr, *u_y = nullptr;
};

/// What a batch writes per row: AreaLightSample's p, n, ng and pdf; its radiance only into
/// le_r, le_g, le_b when they are given (a scene with textured area lights: the radiance is
/// then the point's; otherwise it is the light's, AreaLightTable::radiance). Every row is
/// written; pdf 0 = no valid sample.
struct AreaLightBatchOutputs {
  float *p_x = nullptr, *p_y = nullptr, *p_z = nullptr;
  float *n_x = nullptr, *n_y = nullptr, *n_z = nullptr;
  float *ng_x = nullptr, *ng_y = nullptr, *ng_z = nullptr;
  float* pdf = nullptr;
  float *le_r = nullptr, *le_g = nullptr, *le_b = nullptr;
};

/// SampleAreaLight for n rows: the oracle of simd::SampleAreaLightBatch (simd/wavefront/area_light8.h)
/// and the oracle table's area_light kernel,
/// bit-identical to SampleAreaLight row by row.
void SampleAreaLightBatch(const Scene& scene, TriangleSampling mode, size_t n,
                          const AreaLightBatchInputs& in, const AreaLightBatchOutputs& out);

/// Writes s into row i of `out`.
inline void SetAreaLightRow(const AreaLightBatchOutputs& out, size_t i, const AreaLightSample& s) {
  out.p_x[i] = s.p.x, out.p_y[i] = s.p.y, out.p_z[i] = s.p.z;
  out.n_x[i] = s.n.x, out.n_y[i] = s.n.y, out.n_z[i] = s.n.z;
  out.ng_x[i] = s.ng.x, out.ng_y[i] = s.ng.y, out.ng_z[i] = s.ng.z;
  out.pdf[i] = s.pdf;
  if (out.le_r != nullptr)
    out.le_r[i] = s.radiance.r, out.le_g[i] = s.radiance.g, out.le_b[i] = s.radiance.b;
}

/// Row i of a batch's inputs as SampleAreaLight's reference point and numbers.
inline Vec3f AreaLightRowRef(const AreaLightBatchInputs& in, size_t i) {
  return {in.ref_x[i], in.ref_y[i], in.ref_z[i]};
}
inline Vec2f AreaLightRowU(const AreaLightBatchInputs& in, size_t i) { return {in.u_x[i], in.u_y[i]}; }

}  // namespace ptlab
