// Vectorized interaction stage: per-target instantiation and dispatch of simd/wavefront/interaction8-inl.h.
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/wavefront/interaction8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/wavefront/interaction8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

void MakeInteractionRowsTarget(const Scene& scene, const TriangleRows& tri_rows,
                               const RayPacket8* rays, const HitPacket8* hits,
                               const Mask8* hit_mask, size_t packets, const InteractionRows& out,
                               HitLists* lists) {
  MakeInteractionRowsKernel(scene, tri_rows, rays, hits, hit_mask, packets, out, lists);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/wavefront/interaction8.h"

namespace ptlab::simd {

HWY_EXPORT(MakeInteractionRowsTarget);

void MakeInteractionBatch(const Scene& scene, const TriangleRows& tri_rows, const RayPacket8* rays,
                          const HitPacket8* hits, const Mask8* hit_mask, size_t packets,
                          const InteractionRows& out, HitLists* lists) {
  HWY_DYNAMIC_DISPATCH(MakeInteractionRowsTarget)
  (scene, tri_rows, rays, hits, hit_mask, packets, out, lists);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
