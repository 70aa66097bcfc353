// The oracle's kernel table: the scalar reference of every wavefront stage (each slot's oracle
// lives in its stage's file; here the wrappers that hand a slot its part of the accelerator,
// and the table itself).
#include "engine/wavefront/kernels.h"

#include <cstdlib>
#include <cstring>

#include "engine/wavefront/sobol.h"
#include "engine/wavefront/traverse.h"

namespace ptlab {

namespace {

// The traversal slots read the binary BVH of the accelerator.
Mask8 OracleIntersect8(const WavefrontAccel& accel, const RayPacket8& rays, Mask8 active,
                       HitPacket8* hits) {
  return Intersect8(*accel.bvh, rays, active, hits);
}

Mask8 OracleOccluded8(const WavefrontAccel& accel, const RayPacket8& rays, Mask8 active) {
  return Occluded8(*accel.bvh, rays, active);
}

void OracleAreaLight(const WavefrontAccel&, const Scene& scene, TriangleSampling mode, size_t n,
                     const AreaLightBatchInputs& in, const AreaLightBatchOutputs& out) {
  SampleAreaLightBatch(scene, mode, n, in, out);
}

void OracleInteraction(const WavefrontAccel&, const Scene& scene, const RayPacket8* rays,
                       const HitPacket8* hits, const Mask8* hit_mask, size_t packets,
                       const InteractionRows& out, HitLists* lists) {
  MakeInteractionBatch(scene, rays, hits, hit_mask, packets, out, lists);
}

}  // namespace

WavefrontKernels OracleWavefrontKernels(const Bvh& bvh) {
  return {.accel = {.bvh = &bvh},
          .intersect8 = OracleIntersect8,
          .occluded8 = OracleOccluded8,
          .sobol2d = ScrambledSobol2DBatch,
          .sobol1d = ScrambledSobol1DBatch,
          .camera_paths = StartCameraPaths,
          .bsdf = ShadeBatch,
          .splat = SplatSamples,
          .area_light = OracleAreaLight,
          .area_request = AreaEmitterRequestBatch,
          .shadow_rows = CompactShadowRows,
          .environment = SampleEnvironmentBatch,
          .environment_eval = EvalEnvironmentBatch,
          .distant_disk = SampleDistantDiskBatch,
          .interaction = OracleInteraction,
          .spawn = SpawnRayBatch,
          .vertices = DecideVertices,
          .continuation = ContinuePaths,
          .emission = AddAreaEmissions,
          .name = "scalar-oracle"};
}

bool ForceScalar() {
  const char* v = std::getenv("PTLAB_FORCE_SCALAR");
  return v != nullptr && v[0] != '\0' && std::strcmp(v, "0") != 0;
}

}  // namespace ptlab
