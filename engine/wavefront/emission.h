// The shading stage's light from the area lights that rays hit: each hit's emitted radiance
// toward its ray, MIS-weighted against the emitter sampling of the vertex before, added to its
// path. The scalar oracle of simd/wavefront/emission8.h; the wavefront's `emission` slot.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/packet8.h"
#include "engine/core/vec.h"
#include "engine/scene/scene.h"
#include "engine/wavefront/interaction.h"

namespace ptlab {

/// The hits the batch reads: n queue entries (HitLists::area_entries) and, by queue entry,
/// the ray (lane q % 8 of packet q / 8), its path and its shading point.
struct EmissionBatchInputs {
  const uint32_t* entry = nullptr;
  const RayPacket8* rays = nullptr;
  const uint32_t* owner = nullptr;
  const SurfaceInteraction* its = nullptr;
};

/// The path state, by path id: read, except L.
struct EmissionBatchPaths {
  const Color3f* throughput = nullptr;
  const uint32_t* specular = nullptr;  // 1: the vertex before was of a delta material
  const float* prev_pdf = nullptr;     // the BSDF sample's pdf at the vertex before
  const Vec3f* prev_p = nullptr;       // the vertex before
  Color3f* L = nullptr;                // += the light
};

/// The integrator's switches the weight depends on.
struct EmissionBatchRules {
  bool nee = false;  // emitter sampling at vertices: a non-specular bounce's hit is weighted
  bool mis = false;  // ... by MIS against it (else 0: emitter sampling counted this light)
};

/// Per row k, for the entry q = in.entry[k] and its path i = in.owner[q], the wavefront's
/// former AddEmission: Le = Emitted(its[q], -d / |d|) with d the ray's direction; nothing if Le
/// is black; else L[i] += throughput[i] · Le · w, where w = 1, or (rules.nee and the vertex
/// before not specular) MisWeight(prev_pdf[i], EmitterPdf(its[q], prev_p[i]), power heuristic)
/// with rules.mis and 0 without. The rows' paths are distinct (one ray per path in a queue).
void AddAreaEmissions(const Scene& scene, const EmissionBatchRules& rules, size_t n,
                      const EmissionBatchInputs& in, const EmissionBatchPaths& paths);

}  // namespace ptlab
