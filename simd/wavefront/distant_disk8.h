// Vectorized distant-disk sampling: uniform cone directions for a batch of rows (plain API).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/wavefront/distant_disk.h"
#include "engine/scene/emitter_tables.h"

namespace ptlab::simd {

/// SampleDistantDisk for n rows of disk `disk`, eight rows per step (hn::CappedTag<float, 8>):
/// cosθ uniform over the cone, the azimuth and the frame's rotation run as vectors; a black
/// disk and the rows after the last full vector take the scalar SampleDistantDisk.
/// Oracle: ptlab::SampleDistantDiskBatch. Contract, on every target, for u.x not NaN and u.y
/// finite: radiance and pdf (constants of the disk) and the cone offset s = 1 - cosθ, hence
/// the local z and the radius sinθ, are bit-identical (the oracle's float operations in its
/// order: min, mul, sub, sqrt, max are correctly rounded and FMA contraction is off); sinφ and
/// cosφ come from hwy/contrib/math (≤ 3 ulp on φ ∈ [0, 2π]) instead of libm, so wi differs by
/// |Δ| ≤ 1e-6 per component (the local x, y by ≤ 3 ulp of 1 each, then the frame's three
/// products and two sums); no NaN or Inf for u in [0, 1]². tests/simd/wavefront/distant_disk8_test.cpp.
void SampleDistantDiskBatch(const DistantDiskTable& table, uint32_t disk, size_t n,
                            const EnvironmentBatchInputs& in, const EnvironmentBatchOutputs& out);

}  // namespace ptlab::simd
