// The render path's packet traversal backend (engine/render/packet_render.h) on simd/traverse8.
#pragma once

#include "engine/render/packet_render.h"
#include "simd/bvh8.h"

namespace ptlab::simd {

/// A backend whose intersect8 / occluded8 run simd::Intersect8 / simd::Occluded8 on `bvh`
/// (default Traverse8Options; the oracle when simd::ForceScalar() is set). `bvh` must outlive
/// the backend; `name` is the Highway target (Traverse8TargetName).
TraversalBackend8 PacketTraversalBackend(const Bvh8& bvh);

}  // namespace ptlab::simd
