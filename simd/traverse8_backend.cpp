// The render path's packet traversal backend (engine/render/packet_render.h) on simd/traverse8.
#include "simd/traverse8_backend.h"

#include "simd/sampler8.h"
#include "simd/traverse8.h"

namespace ptlab::simd {
namespace {

Mask8 BackendIntersect8(const void* accel, const RayPacket8& rays, Mask8 active, HitPacket8* hits) {
  return Intersect8(*static_cast<const Bvh8*>(accel), rays, active, hits);
}

Mask8 BackendOccluded8(const void* accel, const RayPacket8& rays, Mask8 active) {
  return Occluded8(*static_cast<const Bvh8*>(accel), rays, active);
}

}  // namespace

TraversalBackend8 PacketTraversalBackend(const Bvh8& bvh) {
  TraversalBackend8 b;
  b.accel = &bvh;
  b.intersect8 = BackendIntersect8;
  b.occluded8 = BackendOccluded8;
  b.sobol2d = simd::ScrambledSobol2DBatch;
  b.sobol1d = simd::ScrambledSobol1DBatch;
  b.name = Traverse8TargetName();
  return b;
}

}  // namespace ptlab::simd
