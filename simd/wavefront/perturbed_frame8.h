// normal: vectorized perturbed shading frames (plain API), the SIMD twin of
// engine/wavefront/perturbed_frame.h.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/wavefront/bsdf.h"

namespace ptlab::simd {

/// ptlab::PerturbedFrameBatch eight rows per vector (PerturbedFrame8 of
/// simd/wavefront/perturbed_frame8-inl.h). Contract: bit-identical to the oracle on every
/// compiled target (tests/simd/wavefront/perturbed_frame8_test.cpp).
void PerturbedFrameBatch(const MaterialTables& m, MaterialTag tag, const uint32_t* material_index,
                         size_t n, const ShadeInputs& in, float* const frame[9]);

}  // namespace ptlab::simd
