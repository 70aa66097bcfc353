// simd/'s table of the wavefront's stage kernels: simd/traverse8, simd/wavefront/sobol8,
// simd/wavefront/camera_paths8, simd/wavefront/bsdf8,
// simd/wavefront/splat8, simd/wavefront/area_light8, simd/wavefront/area_request8, simd/wavefront/environment8, simd/wavefront/distant_disk8,
// simd/wavefront/interaction8, simd/wavefront/spawn8, simd/wavefront/vertices8, simd/wavefront/continuation8, simd/wavefront/shadow_rows8,
// simd/wavefront/emission8.
#include "simd/wavefront/kernels8.h"

#include "simd/dispatched_target.h"
#include "simd/wavefront/area_request8.h"
#include "simd/wavefront/continuation8.h"
#include "simd/wavefront/distant_disk8.h"
#include "simd/wavefront/emission8.h"
#include "simd/wavefront/area_light8.h"
#include "simd/wavefront/environment8.h"
#include "simd/wavefront/interaction8.h"
#include "simd/wavefront/sobol8.h"
#include "simd/wavefront/bsdf8.h"
#include "simd/wavefront/camera_paths8.h"
#include "simd/wavefront/shadow_rows8.h"
#include "simd/wavefront/spawn8.h"
#include "simd/wavefront/splat8.h"
#include "simd/traverse8.h"
#include "simd/wavefront/vertices8.h"

namespace ptlab::simd {
namespace {

Mask8 SimdIntersect8(const WavefrontAccel& accel, const RayPacket8& rays, Mask8 active,
                     HitPacket8* hits) {
  return Intersect8(*accel.bvh8, rays, active, hits);
}

Mask8 SimdOccluded8(const WavefrontAccel& accel, const RayPacket8& rays, Mask8 active) {
  return Occluded8(*accel.bvh8, rays, active);
}

void SimdAreaLight(const WavefrontAccel& accel, const Scene& scene, TriangleSampling mode, size_t n,
                   const AreaLightBatchInputs& in, const AreaLightBatchOutputs& out) {
  SampleAreaLightBatch(scene, *accel.rows, mode, n, in, out);
}

void SimdInteraction(const WavefrontAccel& accel, const Scene& scene, const RayPacket8* rays,
                     const HitPacket8* hits, const Mask8* hit_mask, size_t packets,
                     const InteractionRows& out, HitLists* lists) {
  MakeInteractionBatch(scene, *accel.rows, rays, hits, hit_mask, packets, out, lists);
}

}  // namespace

WavefrontKernels SimdWavefrontKernels(const Bvh8& bvh8, const TriangleRows& rows) {
  return {.accel = {.bvh8 = &bvh8, .rows = &rows},
          .intersect8 = SimdIntersect8,
          .occluded8 = SimdOccluded8,
          .sobol2d = ScrambledSobol2DBatch,
          .sobol1d = ScrambledSobol1DBatch,
          .camera_paths = StartCameraPaths,
          .bsdf = ShadeBatch,
          .splat = SplatSamples,
          .area_light = SimdAreaLight,
          .area_request = AreaEmitterRequestBatch,
          .shadow_rows = CompactShadowRows,
          .environment = SampleEnvironmentBatch,
          .environment_eval = EvalEnvironmentBatch,
          .distant_disk = SampleDistantDiskBatch,
          .interaction = SimdInteraction,
          .spawn = SpawnRayBatch,
          .vertices = DecideVertices,
          .continuation = ContinuePaths,
          .emission = AddAreaEmissions,
          .name = DispatchedTargetName()};
}

}  // namespace ptlab::simd
