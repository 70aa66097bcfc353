// Vectorized finish of the BSDF stage: each sampled path's throughput and state, and the spawn
// rows of the paths that go on (plain API).
#pragma once

#include <cstddef>

#include "engine/wavefront/continuation.h"

namespace ptlab::simd {

/// ptlab::ContinuePaths, one row per 32-bit lane (hn::CappedTag<float, 8>: 8 rows per step on
/// AVX2 and AVX3, 4 on 128-bit targets): the rows' throughput, eta and shading points are
/// gathered by path and queue entry, and the path state scattered back, every lane of the
/// vector (a lane that must not change a column writes back the bits it gathered; the rows'
/// paths are distinct, so no two lanes write one path; on 256-bit targets the throughput and
/// point rows go as one 3-lane masked store per lane after a transpose); the spawn rows and
/// owners are compress-stored in row order. The rows after the last whole vector take the
/// oracle. Every row's path and entry must index the path state and `its` (rows without a
/// sample are read too).
/// Oracle: ptlab::ContinuePaths. Contract: every output and the whole path state bit-identical
/// to the oracle's on every target (the same float multiplies in the same order, the same
/// comparisons on NaN), except the payload of a product of two NaNs (either factor's: the
/// compiler may commute a multiply; the bsdf slot's weights are finite, so the wavefront never
/// multiplies two). tests/simd/wavefront/continuation8_test.cpp.
void ContinuePaths(const ContinueBatchRules& rules, size_t n, const ContinueBatchInputs& in,
                   const ContinueBatchPaths& paths, ContinueBatchOutputs* out);

}  // namespace ptlab::simd
