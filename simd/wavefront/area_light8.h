// Vectorized emitter sampling: area-light samples for a batch of shading points (plain API).
#pragma once

#include <cstddef>

#include "engine/scene/scene.h"
#include "engine/wavefront/area_light.h"
#include "simd/triangle_rows.h"

namespace ptlab::simd {

/// SampleAreaLight for n rows, eight rows per step (hn::CappedTag<float, 8>): each lane picks
/// its triangle as PickAreaLightTriangle does (guide table and CDF; the per-light values held in
/// vectors when the scene has at most 8 lights, gathered otherwise; a lane whose guide bucket
/// misses takes the scalar pick), then the point uniform by area, the shading normal
/// (interpolated vertex normals or the geometric one), the geometric normal and the solid-angle
/// pdf run as vectors over the triangles' rows and vertex normal rows of `tri_rows`
/// (BuildTriangleRows of `scene`), loaded and transposed. kSolidAngle batches, and the rows
/// after the last full vector, take the scalar SampleAreaLight row by row (Arvo's construction
/// stays scalar). With out.le_r given (textured area lights), each lane's radiance too: the
/// surface uv interpolated from the mesh's vertex uvs and the light's texture there
/// (EvalTexture8; area_radiance8-inl.h), or the light's constant radiance.
/// Oracle: ptlab::SampleAreaLightBatch. Contract: every output bit-identical to the oracle's
/// on every target (the oracle's float operations in its order; FMA contraction is off, and
/// Highway's Sqrt and Div are correctly rounded). tests/simd/wavefront/area_light8_test.cpp.
void SampleAreaLightBatch(const Scene& scene, const TriangleRows& tri_rows, TriangleSampling mode,
                          size_t n, const AreaLightBatchInputs& in,
                          const AreaLightBatchOutputs& out);

}  // namespace ptlab::simd
