// Vectorized finish of area-light emitter samples: shadow ray, BSDF, MIS weight and
// contribution for a batch of one material's shading points (plain API).
#pragma once

#include <cstddef>

#include "engine/wavefront/area_request.h"
#include "engine/scene/scene.h"

namespace ptlab::simd {

/// ptlab::AreaEmitterRequestBatch (integrator::AreaEmitterSampleRequest per row) for n rows
/// whose shading points all have material tag `tag`, eight rows per vector
/// (hn::CappedTag<float, 8>), in chunks of 64 rows: the shading point's ng, n (the frame's s
/// and t are rebuilt from it) and material row gathered from the AoS shading points by queue
/// entry, wi, its validity, wi in the local frame and
/// the shadow ray's offset endpoints as vectors (the oracle's float operations in its order,
/// FMA contraction off; OffsetRayOrigin as integer bit arithmetic); then the chunk's BSDF
/// evaluation (f, and its pdf for the MIS weight) as one eval-only simd::ShadeBatch of `tag`
/// (simd/wavefront/bsdf8-inl.h) over the rows whose geometry allows a sample (compacted: on sphere
/// lights half the sampled points face away); then the MIS weight and contribution as vectors.
/// Delta materials write untraced rows without evaluating; the rows after the last full vector take
/// the oracle. Contract (tests/simd/wavefront/area_request8_test.cpp, every compiled target):
/// - traced, o and d bit-identical to the oracle's, except for rows where the BSDF kernel's f
///   is black on one side only (f underflowing to 0; none seen) or a contribution is not finite
///   (the oracle's Inf; this kernel does not trace such a row);
/// - the contribution within simd::ShadeBatch's f and pdf contract: per channel
///   |Δ| ≤ 1e-4 |oracle| + 1e-30 (seen: 4.7e-7 relative, on rough plastic
///   and conductor rows);
/// - every output finite; untraced rows are 0.
void AreaEmitterRequestBatch(const Scene& scene, MaterialTag tag, bool mis, size_t n,
                             const AreaRequestInputs& in, const AreaRequestOutputs& out);

}  // namespace ptlab::simd
