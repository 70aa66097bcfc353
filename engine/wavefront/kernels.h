// The typed table of the wavefront's stage kernels, which the scalar oracle (engine/, kernels.cpp
// and each stage's file) and simd/ (simd/wavefront/kernels8.h) each implement once.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "engine/bvh/bvh.h"
#include "engine/core/packet8.h"
#include "engine/render/camera.h"
#include "engine/render/filter.h"
#include "engine/render/integrator.h"
#include "engine/render/packet_render.h"
#include "engine/wavefront/area_light.h"
#include "engine/wavefront/area_request.h"
#include "engine/wavefront/bsdf.h"
#include "engine/wavefront/camera_paths.h"
#include "engine/wavefront/continuation.h"
#include "engine/wavefront/distant_disk.h"
#include "engine/wavefront/emission.h"
#include "engine/wavefront/environment.h"
#include "engine/wavefront/interaction.h"
#include "engine/wavefront/shadow_rows.h"
#include "engine/wavefront/spawn.h"
#include "engine/wavefront/splat.h"
#include "engine/wavefront/vertices.h"

namespace ptlab {

namespace simd {
struct Bvh8;          // simd/bvh8.h; engine/ only hands them to the SIMD table's kernels
struct TriangleRows;  // simd/triangle_rows.h
}  // namespace simd

/// What the kernels read beside the scene's tables, world space. The oracle's traversal
/// kernels read `bvh`, simd/'s read `bvh8` (a BVH8 collapsed from it), and simd/'s interaction
/// and area-light kernels `rows` (the scene's triangles as 64-byte rows); a table leaves the
/// others null. All must outlive the table.
struct WavefrontAccel {
  const Bvh* bvh = nullptr;
  const simd::Bvh8* bvh8 = nullptr;
  const simd::TriangleRows* rows = nullptr;
};

/// The stage kernels of the wavefront, one table per implementation: OracleWavefrontKernels
/// (engine/, the reference) and simd::SimdWavefrontKernels (simd/wavefront/kernels8.h). Every
/// slot is set. The wavefront calls them in a fixed order with the same inputs whichever table
/// it runs, so a table whose kernels meet their contracts renders the oracle's image.
struct WavefrontKernels {
  WavefrontAccel accel;

  // Traversal stage. Oracle: ptlab::Intersect8 / ptlab::Occluded8 (engine/wavefront/traverse.h);
  // SIMD: simd::Intersect8 / simd::Occluded8 (simd/traverse8.h), bit-identical to Intersect1 /
  // Occluded1 lane by lane: only lanes in `active` are read, and
  // a lane that misses or is inactive is not written.
  Mask8 (*intersect8)(const WavefrontAccel& accel, const RayPacket8& rays, Mask8 active,
                      HitPacket8* hits) = nullptr;
  Mask8 (*occluded8)(const WavefrontAccel& accel, const RayPacket8& rays, Mask8 active) = nullptr;

  // Sampling stage: the Sobol' sampler's batch draws (engine/wavefront/sobol.h; contract:
  // bit-identical to those oracles). The wavefront draws a decision's numbers for all its
  // paths with one call when the scene's sampler is `sobol`.
  void (*sobol2d)(const uint32_t* pixel_seed, const uint32_t* index, uint32_t dim, size_t n,
                  float* x, float* y) = nullptr;
  void (*sobol1d)(const uint32_t* pixel_seed, const uint32_t* index, uint32_t dim, size_t n,
                  float* x) = nullptr;
  // Sampling stage, the camera paths: each new path's PathSampler and (independent sampler)
  // its film and lens numbers, one call per wave, before the camera rays (engine/wavefront/
  // camera_paths.h). Oracle: ptlab::StartCameraPaths; SIMD: simd::StartCameraPaths,
  // bit-identical (simd/wavefront/camera_paths8.h).
  void (*camera_paths)(SamplerType type, uint64_t seed, uint64_t width, size_t n,
                       const CameraPathInputs& in, const CameraPathOutputs& out) = nullptr;

  // BSDF stage: one material's kernel over a contiguous batch of rows that all have tag `tag`
  // (the wavefront writes each continuing entry's row into its tag's group of rows and calls
  // this once per tag present; engine/wavefront/bsdf.h). Oracle: ptlab::ShadeBatch
  // (BsdfSampleDirection per row, so the oracle table keeps the scalar path's bits); SIMD:
  // simd::ShadeBatch, within the contract of simd/wavefront/bsdf8.h. The wavefront samples only
  // (in.wl.x == nullptr: f and pdf_l are not written).
  void (*bsdf)(const MaterialTables& m, MaterialTag tag, const uint32_t* material_index, size_t n,
               const ShadeInputs& in, const ShadeOutputs& out) = nullptr;

  // Splat stage: a wave's finite samples, in the scalar loop's order, into the film block
  // through the filter's precomputed table (PixelFilter::Eval). Oracle: ptlab::SplatSamples
  // (engine/wavefront/splat.h: FilmBlock::Splat per sample); SIMD: simd::SplatSamples,
  // bit-identical (simd/wavefront/splat8.h).
  void (*splat)(const PixelFilter& filter, const FilmSamples& samples, FilmBlock* block) = nullptr;

  // Emitter stage: the wave's area-light samples (every emitter sample whose pick is an area
  // light) as batches over SoA columns (engine/wavefront/area_light.h), one call per group of rows
  // of area_request below (the kernel does not care which rows it gets); the area_request slot
  // finishes them. Oracle: ptlab::SampleAreaLightBatch (SampleAreaLight per row); SIMD:
  // simd::SampleAreaLightBatch, bit-identical (simd/wavefront/area_light8.h).
  void (*area_light)(const WavefrontAccel& accel, const Scene& scene, TriangleSampling mode,
                     size_t n, const AreaLightBatchInputs& in,
                     const AreaLightBatchOutputs& out) = nullptr;

  // Emitter stage, the area-light samples' finish: shadow ray, BSDF evaluation, MIS weight
  // (when `mis`) and contribution of each sample (engine/wavefront/area_request.h), one
  // call per material tag on the rows whose shading point has that tag (the wavefront writes
  // each area-light row into its tag's group of rows, as for the bsdf slot; the shading points
  // are read where the wavefront keeps them, by queue entry); the wavefront then queues each
  // traced row's shadow ray. Oracle: ptlab::AreaEmitterRequestBatch
  // (integrator::AreaEmitterSampleRequest per row, so the oracle table keeps the scalar path's
  // bits); SIMD: simd::AreaEmitterRequestBatch, shadow rays bit-identical and contributions
  // within simd::ShadeBatch's evaluation contract (simd/wavefront/area_request8.h).
  void (*area_request)(const Scene& scene, MaterialTag tag, bool mis, size_t n,
                       const AreaRequestInputs& in, const AreaRequestOutputs& out) = nullptr;

  // Emitter stage, the shadow queue's rows: an area_request batch's traced rows (request,
  // shadow ray, contribution) compacted in row order, one call per material tag, which the
  // wavefront then copies into the shadow queue's packets a packet at a time (no branch per
  // row on the flag). Oracle: ptlab::CompactShadowRows; SIMD: simd::CompactShadowRows,
  // bit-identical (simd/wavefront/shadow_rows8.h).
  size_t (*shadow_rows)(size_t n, const ShadowRowInputs& in, const ShadowRowOutputs& out) = nullptr;

  // Emitter stage, environment maps: the wave's samples of one map (every emitter sample whose
  // pick is environment map `map`) as one batch over SoA columns (engine/wavefront/
  // environment.h), one call per map picked; the wavefront finishes each returned sample
  // (pdf > 0) with integrator::InfiniteEmitterSampleRequest. Oracle:
  // ptlab::SampleEnvironmentBatch (SampleEnvironment per row); SIMD:
  // simd::SampleEnvironmentBatch, radiance bit-identical, wi and pdf within 2e-6
  // (simd/wavefront/environment8.h).
  void (*environment)(const EnvironmentMapTable& table, uint32_t map, size_t n,
                      const EnvironmentBatchInputs& in,
                      const EnvironmentBatchOutputs& out) = nullptr;

  // Shading stage, escaped rays: EnvironmentRadiance and (out.pdf set) EnvironmentPdf of map
  // `map` for a wave's escaping rays (world directions as SoA columns), one call per map; the
  // wavefront sums the maps' light as integrator::Escaped does. Oracle:
  // ptlab::EvalEnvironmentBatch (the two functions per row); SIMD: simd::EvalEnvironmentBatch,
  // radiance within 1e-3 of the pixels it reads, pdf bit-identical away from cell edges
  // (simd/wavefront/environment8.h).
  void (*environment_eval)(const EnvironmentMapTable& table, uint32_t map, size_t n,
                           const EnvironmentEvalInputs& in,
                           const EnvironmentEvalOutputs& out) = nullptr;

  // Emitter stage, distant disks: as the environment slot, one call per disk picked (rows: the
  // wave's samples of disk `disk`, same columns), each returned sample finished with
  // integrator::InfiniteEmitterSampleRequest. Oracle: ptlab::SampleDistantDiskBatch
  // (SampleDistantDisk per row); SIMD: simd::SampleDistantDiskBatch, radiance and pdf
  // bit-identical, wi within 1e-6 (simd/wavefront/distant_disk8.h).
  void (*distant_disk)(const DistantDiskTable& table, uint32_t disk, size_t n,
                       const EnvironmentBatchInputs& in,
                       const EnvironmentBatchOutputs& out) = nullptr;

  // Interaction stage: a wave's hit records -> the shading stage's rows
  // (engine/wavefront/interaction.h, InteractionRows): the SurfaceInteraction of each hit (its
  // frame, material and emitter; uv only in a scene with textures: only they read it) and wo,
  // the direction back along the ray in its frame; row = queue entry, 8 rows per packet. And the wave's hit lists (HitLists, same
  // header): every hit's queue entry and those of the hits on area lights, in queue order, and
  // the hits per material group; the shading stage adds emission over the area list only and
  // the sampling stage takes the entry list and group counts as they are. Oracle:
  // ptlab::MakeInteractionBatch (MakeInteraction and LocalDirectionBack per hit row, so the
  // oracle table keeps the scalar path's bits, and each hit row's list entries); SIMD:
  // simd::MakeInteractionBatch, bit-identical on the hit rows and in the lists' counts and
  // entries, and may write the other rows of a packet with a hit and the lists' room past their
  // counts (simd/wavefront/interaction8.h).
  void (*interaction)(const WavefrontAccel& accel, const Scene& scene, const RayPacket8* rays,
                      const HitPacket8* hits, const Mask8* hit_mask, size_t packets,
                      const InteractionRows& out, HitLists* lists) = nullptr;

  // Spawn stage: the next rays of the paths that go on after the BSDF stage, one row per path
  // in next-queue order (the wavefront writes each row's shading-point entry and local wi as it
  // updates the path's state), row k into lane k % 8 of out[k / 8], the last packet's other
  // lanes zero. Oracle: ptlab::SpawnRayBatch (SpawnRayAt per row: Frame::ToWorld and
  // integrator::SpawnOrigin, the scalar path's bits); SIMD: simd::SpawnRayBatch, bit-identical
  // (simd/wavefront/spawn8.h).
  void (*spawn)(const SurfaceInteraction* its, size_t n, const SpawnInputs& in,
                RayPacket8* out) = nullptr;

  // Sampling stage, the decisions at a material group's vertices (engine/wavefront/
  // vertices.h), for every integrator and both samplers: each vertex's emitter samples (area
  // lights to the emitter stage's columns, the other emitters' picks to the wavefront, which
  // routes them), the roulette (Nori's, Whitted's) and BSDF numbers as the rows of the emitter
  // and BSDF stages' columns, one call per group. Oracle: ptlab::DecideVertices (the scalar
  // integrators' operations per row, so the oracle table keeps the scalar path's bits); SIMD:
  // simd::DecideVertices, bit-identical (simd/wavefront/vertices8.h; it hands the rows it
  // does not vectorize, a batch's last partial vector and guide-table emitter selection, to
  // the oracle function).
  void (*vertices)(const Scene& scene, const VertexBatchRules& rules, size_t n,
                   const VertexBatchInputs& in, const VertexBatchPaths& paths,
                   VertexBatchOutputs* out) = nullptr;

  // BSDF stage, its finish (engine/wavefront/continuation.h): after the bsdf slot, each sampled
  // path's throughput, eta, specular flag, previous pdf and point, and the spawn row and next
  // queue owner of each path that goes on, one call per material tag on the tag's rows of the
  // BSDF columns (each row of a different path), appending at the running count of spawn rows.
  // Oracle: ptlab::ContinuePaths (the scalar integrators' operations per row, so the oracle
  // table keeps the scalar path's bits); SIMD: simd::ContinuePaths, bit-identical
  // (simd/wavefront/continuation8.h).
  void (*continuation)(const ContinueBatchRules& rules, size_t n, const ContinueBatchInputs& in,
                       const ContinueBatchPaths& paths, ContinueBatchOutputs* out) = nullptr;

  // Shading stage, the hits on area lights (HitLists' area entries, engine/wavefront/
  // emission.h): each hit's emitted light toward its ray, MIS-weighted against the
  // emitter sampling of the vertex before, added to its path, one call per wave. Oracle:
  // ptlab::AddAreaEmissions (the scalar integrators' operations per row, so the oracle table
  // keeps the scalar path's bits); SIMD: simd::AddAreaEmissions, bit-identical up to NaN
  // payloads (simd/wavefront/emission8.h).
  void (*emission)(const Scene& scene, const EmissionBatchRules& rules, size_t n,
                   const EmissionBatchInputs& in, const EmissionBatchPaths& paths) = nullptr;

  // Not in the table, row by row in the wavefront (PrepareEmitterSampleFrom): the delta lights
  // (point, and the CS184 directional and spot lights, engine/light/delta_light.h). Their
  // "sample" draws no numbers: the light's one position or direction and a falloff, a handful
  // of operations per row, less than a batch's gather into columns and scatter back would cost.
  // Also scalar in every table: the finish of the infinite and delta lights' emitter samples
  // (BSDF evaluation, MIS weight, shadow-ray setup; integrator::InfiniteEmitterSampleRequest,
  // PrepareEmitterSampleFrom); the area lights' is the area_request slot.

  /// For logs: "scalar-oracle" or the Highway target the SIMD kernels dispatch to.
  const char* name = "";
};

/// The oracle's table: Intersect1 / Occluded1 lane by lane on `bvh` and the scalar Sobol'
/// batches. `bvh` must outlive the table.
WavefrontKernels OracleWavefrontKernels(const Bvh& bvh);

/// True when PTLAB_FORCE_SCALAR is set (to anything but "" or "0"): the tools then render with
/// OracleWavefrontKernels, as `--scalar` does. The kernels themselves never read it.
bool ForceScalar();

}  // namespace ptlab
