// The emitter stage's finish of a batch of area-light samples (shadow ray, BSDF, MIS weight,
// contribution) over SoA columns: the scalar oracle of simd/wavefront/area_request8.h.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/vec.h"
#include "engine/render/integrator_common.h"
#include "engine/render/interaction.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// What the batch reads: n rows, each an area-light sample (the area_light stage's outputs) for
/// a shading point. The shading points stay where the wavefront built them, AoS by queue entry
/// (no copy into columns of what the stage reads once): row c's is its[entry[c]], of which
/// the kernels read ng, the frame (the SIMD kernel its n: the frame is Frame(n)) and the
/// material; its position and wo (local direction to the viewer) come as columns (ref: the
/// area_light stage's reference points, its[entry[c]].p; the wavefront has both at hand when
/// it writes the row). The light sample: p, n, ng, pdf (solid angle; 0: no sample) as
/// AreaLightBatchOutputs has them, its light (for the radiance, AreaLightTable::radiance) and
/// the probability pick_pmf with which it was picked.
struct AreaRequestInputs {
  const SurfaceInteraction* its = nullptr;
  const uint32_t* entry = nullptr;
  const float *ref_x = nullptr, *ref_y = nullptr, *ref_z = nullptr;
  const float *wo_x = nullptr, *wo_y = nullptr, *wo_z = nullptr;
  const uint32_t* light = nullptr;
  const float* pick_pmf = nullptr;
  const float *p_x = nullptr, *p_y = nullptr, *p_z = nullptr;
  const float *n_x = nullptr, *n_y = nullptr, *n_z = nullptr;
  const float *ng_x = nullptr, *ng_y = nullptr, *ng_z = nullptr;
  const float* pdf = nullptr;
  /// The sample's radiance (AreaLightBatchOutputs' le columns) when the scene has textured
  /// area lights; null: the light's, AreaLightTable::radiance.
  const float *le_r = nullptr, *le_g = nullptr, *le_b = nullptr;

  /// The inputs of rows [i, n): the columns from row i on, the same shading points.
  AreaRequestInputs From(size_t i) const {
    const bool le = le_r != nullptr;
    return {its,      entry + i, ref_x + i,    ref_y + i, ref_z + i, wo_x + i, wo_y + i,
            wo_z + i, light + i, pick_pmf + i, p_x + i,   p_y + i,   p_z + i,  n_x + i,
            n_y + i,  n_z + i,   ng_x + i,     ng_y + i,  ng_z + i,  pdf + i,
            le ? le_r + i : nullptr, le ? le_g + i : nullptr, le ? le_b + i : nullptr};
  }
};

/// What the batch writes, every row: EmitterSampleRequest as columns. traced 1: the shadow ray
/// from o along d (not normalised: t over [0, 1) reaches the offset light point) and the
/// contribution f·Le·|cos θi|·w / pdf_light; traced 0: no ray, and o, d, contribution are 0.
struct AreaRequestOutputs {
  uint8_t* traced = nullptr;
  float *o_x = nullptr, *o_y = nullptr, *o_z = nullptr;
  float *d_x = nullptr, *d_y = nullptr, *d_z = nullptr;
  float *r = nullptr, *g = nullptr, *b = nullptr;

  AreaRequestOutputs From(size_t i) const {
    return {traced + i, o_x + i, o_y + i, o_z + i, d_x + i, d_y + i, d_z + i, r + i, g + i, b + i};
  }
};

/// Writes request `req` into row c of `out` (zeros when it traces nothing).
inline void SetAreaRequestRow(const AreaRequestOutputs& out, size_t c,
                              const integrator::EmitterSampleRequest& req) {
  const Vec3f o = req.traced ? req.shadow.o : Vec3f{}, d = req.traced ? req.shadow.d : Vec3f{};
  const Color3f L = req.traced ? req.contribution : Color3f{};
  out.traced[c] = uint8_t(req.traced);
  out.o_x[c] = o.x, out.o_y[c] = o.y, out.o_z[c] = o.z;
  out.d_x[c] = d.x, out.d_y[c] = d.y, out.d_z[c] = d.z;
  out.r[c] = L.r, out.g[c] = L.g, out.b[c] = L.b;
}

/// The area_request stage for n rows whose shading points all have material tag `tag` (the
/// wavefront groups its area-light rows by tag, so the SIMD twin runs one material's BSDF
/// kernel per batch; this oracle reads each row's own material and does not need it):
/// integrator::AreaEmitterSampleRequest per row, MIS-weighted against BSDF sampling when `mis`
/// (with the scene's heuristic). Bit-identical to the scalar integrators' emitter samples.
void AreaEmitterRequestBatch(const Scene& scene, MaterialTag tag, bool mis, size_t n,
                             const AreaRequestInputs& in, const AreaRequestOutputs& out);

}  // namespace ptlab
