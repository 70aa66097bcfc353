// Vectorized spawn stage: the next rays of the paths that go on, into ray packets (plain API).
#pragma once

#include <cstddef>

#include "engine/core/packet8.h"
#include "engine/render/interaction.h"
#include "engine/wavefront/spawn.h"

namespace ptlab::simd {

/// ptlab::SpawnRayBatch, eight rows per step (hn::CappedTag<float, 8>): each packet of eight
/// rows gathers its shading points' p, ng and n by in.entry, rebuilds their frame from n as
/// Frame(n) does (the rows' frames are Frame(n): see ptlab::SpawnRayBatch), turns wi into
/// world space, offsets the origin (OffsetRayOrigin's integer step, or its fixed step near
/// zero) and stores the packet with whole-vector stores; the last, partial packet takes the
/// oracle row by row.
/// Oracle: ptlab::SpawnRayBatch. Contract: every output bit-identical to the oracle's on every
/// target (its float operations in its order; FMA contraction is off, Highway's Div is
/// correctly rounded and its float -> int conversion truncates as the cast does for |x| <= 256).
/// Inputs: finite points at least 256 ulps below the largest float, unit normals.
/// tests/simd/wavefront/spawn8_test.cpp.
void SpawnRayBatch(const SurfaceInteraction* its, size_t n, const SpawnInputs& in,
                   RayPacket8* out);

}  // namespace ptlab::simd
