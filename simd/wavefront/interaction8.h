// Vectorized interaction stage: hit records -> shading points for a wave's packets (plain API).
#pragma once

#include <cstddef>

#include "engine/core/packet8.h"
#include "engine/scene/scene.h"
#include "engine/wavefront/interaction.h"
#include "simd/triangle_rows.h"

namespace ptlab::simd {

/// ptlab::MakeInteractionBatch into rows (the wavefront's interaction slot), eight lanes per
/// step: for the triangle hits of a packet their rows in `tri_rows` (BuildTriangleRows of
/// `scene`: vertices, material and emitter refs, vertex rows) and vertex normal rows are loaded
/// and transposed, the interpolation and normalizations of MakeInteraction / ShadingNormalAt
/// run as vectors, then Frame(n) and wo (-d / |d| in the frame), stored into the
/// SurfaceInteraction rows through 4x4 transposes; sphere lanes take the scalar
/// MakeInteraction lane by lane; in a scene with textures (only there) the triangle hits' uv
/// (SurfaceUvAt: the vertex uvs gathered and interpolated, the mesh's has_uvs read lane by
/// lane). Every row of a vector of lanes with a triangle hit is written:
/// rows of lanes that did not hit get finite floats (vertex 0 of triangle 0 and its geometric
/// frame) and are otherwise unspecified. out.its and out.wo need 8 rows per packet. The hit
/// lists (HitLists) from the refs in registers: entries compressed into the lists lane by
/// lane, groups counted per vector; past each list's count its room may be written.
/// Oracle: ptlab::MakeInteractionBatch (rows). Contract: the hit rows bit-identical to the
/// oracle's on every target (the scalar float operations in their order, FMA contraction off,
/// correctly rounded Sqrt and Div), the lists' counts and entries [0, count) equal to the
/// oracle's; tests/simd/wavefront/interaction8_test.cpp.
void MakeInteractionBatch(const Scene& scene, const TriangleRows& tri_rows, const RayPacket8* rays,
                          const HitPacket8* hits, const Mask8* hit_mask, size_t packets,
                          const InteractionRows& out, HitLists* lists);

}  // namespace ptlab::simd
