// Vectorized sampling-stage decisions at a batch of path vertices: the emitter samples' picks,
// the roulette and the BSDF numbers, with the independent sampler's draws or Sobol' numbers
// from columns (plain API).
#pragma once

#include <cstddef>

#include "engine/wavefront/vertices.h"
#include "engine/scene/scene.h"

namespace ptlab::simd {

/// ptlab::DecideVertices, one row per 64-bit lane (hn::CappedTag<uint64_t, 8>: 8 rows per
/// step on AVX3, 4 on AVX2): the rows' paths, shading points, wo and path state are gathered,
/// each draw's PCG32 state is jumped to from the path's state (Pcg32JumpOf; with Sobol' the
/// numbers are loaded from their columns), the pick scans the selection CDF (or scales u for a
/// uniform one; with Sobol' u is remapped as SelectEmitter's u_remapped), and the area, other
/// and BSDF rows are compress-stored in row order; the path state is scattered back. With more
/// than one emitter sample per vertex the samples go first, one per lane in request order (a
/// lane's draws jump 3 s steps further). The rows after the last whole vector, and every row
/// of a batch whose selection needs the guide table (power over more than kScanUpperBoundMax
/// emitters), take the oracle itself.
/// Oracle: ptlab::DecideVertices. Contract: every output bit-identical to the oracle's on every
/// target (integer PCG32 steps; the roulette's float operations in the oracle's order, with
/// std::max / std::min's choice on NaN). tests/simd/wavefront/vertices8_test.cpp.
void DecideVertices(const Scene& scene, const VertexBatchRules& rules, size_t n,
                    const VertexBatchInputs& in, const VertexBatchPaths& paths,
                    VertexBatchOutputs* out);

}  // namespace ptlab::simd
