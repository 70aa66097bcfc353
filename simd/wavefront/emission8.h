// Vectorized light of the area-light hits in the shading stage (plain API).
#pragma once

#include <cstddef>

#include "engine/wavefront/emission.h"

namespace ptlab::simd {

/// ptlab::AddAreaEmissions, eight rows per step (hn::CappedTag<float, 8>): the rays'
/// directions, shading points and path state gathered, Emitted, EmitterPdf (triangles sampled
/// by area) and MisWeight lane-wise in the oracle's float operations and order, each row's L
/// gathered, added to in the rows whose Le is not black, and scattered back; the rows after
/// the last whole vector, and every row when the scene samples its light triangles by solid
/// angle (with nee and mis) or has no area lights, take the oracle. Oracle:
/// ptlab::AddAreaEmissions. Contract: L bit-identical on every target (the rows' paths are
/// distinct, as the oracle's contract says), except the payload and sign of a NaN: of a sum or
/// product of two NaNs x86 returns the first operand, and the compiler may swap the operands.
/// A NaN L stays NaN (a sample the film drops). tests/simd/wavefront/emission8_test.cpp.
void AddAreaEmissions(const Scene& scene, const EmissionBatchRules& rules, size_t n,
                      const EmissionBatchInputs& in, const EmissionBatchPaths& paths);

}  // namespace ptlab::simd
