// Vectorized environment maps: importance samples, and radiance and pdf of escaping rays, for
// a batch of rows (plain API).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/wavefront/environment.h"
#include "engine/scene/emitter_tables.h"

namespace ptlab::simd {

/// SampleEnvironment for n rows of map `map`, eight rows per step (hn::CappedTag<float, 8>):
/// the marginal and conditional CDF inversions (a branchless search by gathers), the cell's
/// pdf, the bilinear radiance lookup and the direction run as vectors. Uniform-sampling maps,
/// black maps and the rows after the last full vector take the scalar SampleEnvironment.
/// Oracle: ptlab::SampleEnvironmentBatch. Contract, on every target: the sampled (u, v), hence
/// radiance r, g, b, are bit-identical to the oracle's (its float operations in its order; FMA
/// contraction is off); sinθ, cosθ, sinφ, cosφ come from hwy/contrib/math (≤ 3 ulp) instead of
/// libm, so wi differs by |Δ| ≤ 2e-6 per component (as simd/wavefront/bsdf8.h's directions) and pdf,
/// which divides by sinθ, θ measured from the nearer pole (well conditioned), by ≤ 2e-6
/// relative; no NaN or Inf for numbers in [0, 1] (importance maps clamp others and NaN, as
/// SampleEnvironment does). Seen on venice_sunset_1k: wi 2.4e-7, pdf 2.8e-7.
/// tests/simd/wavefront/environment8_test.cpp.
void SampleEnvironmentBatch(const EnvironmentMapTable& table, uint32_t map, size_t n,
                            const EnvironmentBatchInputs& in, const EnvironmentBatchOutputs& out);

/// EnvironmentRadiance and EnvironmentPdf (when out.pdf is set) of map `map` for n escaping
/// rays, eight per step: the direction's (u, v) (two atan2 from hwy's Atan), the bilinear
/// lookup and the cell's density over 2π² sinθ run as vectors; the rows after the last full
/// vector take the oracle, ptlab::EvalEnvironmentBatch. Contract, on every target: (u, v) is a
/// few ulp off the oracle's (libm's atan2), so the radiance, continuous in (u, v), is within
/// 1e-3 of the largest pixel the lookup reads around it (relative), and the pdf is the
/// oracle's bit for bit (the same float operations on the same local direction) except where
/// u·width or v·height lies within 1e-3 of an integer, where it may be the neighbouring cell's;
/// no NaN or Inf for finite unit directions. Seen on venice_sunset_1k: radiance 9.9e-5.
/// tests/simd/wavefront/environment8_test.cpp.
void EvalEnvironmentBatch(const EnvironmentMapTable& table, uint32_t map, size_t n,
                          const EnvironmentEvalInputs& in, const EnvironmentEvalOutputs& out);

}  // namespace ptlab::simd
