// normal: the perturbed shading frames of a batch of rows (the oracle of
// simd/wavefront/perturbed_frame8.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/wavefront/bsdf.h"

namespace ptlab {

/// frame[k][i] for k = s.x, s.y, s.z, t.x, t.y, t.z, n.x, n.y, n.z: PerturbedFrame
/// (engine/bsdf/perturbed_frame.h) of row (tag, material_index[i]) for in.wo's row i at
/// RowTextureSite(in.texture, i); rows that are not perturbed get the identity frame.
void PerturbedFrameBatch(const MaterialTables& m, MaterialTag tag, const uint32_t* material_index,
                         size_t n, const ShadeInputs& in, float* const frame[9]);

}  // namespace ptlab
