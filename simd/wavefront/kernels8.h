// simd/'s table of the wavefront's stage kernels (engine/wavefront/wavefront.h).
#pragma once

#include "engine/wavefront/wavefront.h"
#include "simd/bvh8.h"
#include "simd/triangle_rows.h"

namespace ptlab::simd {

/// The SIMD table: intersect8 / occluded8 run simd::Intersect8 / simd::Occluded8 on `bvh8`
/// (each with its default options), sobol2d / sobol1d the 8-wide Sobol' batches (simd/wavefront/sobol8.h),
/// bsdf simd::ShadeBatch (simd/wavefront/bsdf8.h), splat simd::SplatSamples (simd/wavefront/splat8.h),
/// area_light simd::SampleAreaLightBatch (simd/wavefront/area_light8.h) on `rows`, area_request
/// simd::AreaEmitterRequestBatch (simd/wavefront/area_request8.h), interaction
/// simd::MakeInteractionBatch (simd/wavefront/interaction8.h) on `rows`, spawn simd::SpawnRayBatch
/// (simd/wavefront/spawn8.h). `bvh8` and `rows` (BuildTriangleRows of the scene rendered) must outlive
/// the table; `name` is the Highway target (DispatchedTargetName).
/// Its oracle: OracleWavefrontKernels on the binary Bvh that `bvh8` was collapsed from.
WavefrontKernels SimdWavefrontKernels(const Bvh8& bvh8, const TriangleRows& rows);

}  // namespace ptlab::simd
