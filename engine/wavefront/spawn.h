// The wavefront's spawn stage: the next rays of the paths that go on, from their shading points
// and sampled local directions, written straight into ray packets.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/packet8.h"
#include "engine/core/ray.h"
#include "engine/render/integrator_common.h"
#include "engine/render/interaction.h"

namespace ptlab {

/// One row per path that goes on, in the order its ray takes in the next queue: the queue
/// entry of its shading point (its row in the interaction stage's SurfaceInteraction rows) and
/// the sampled direction wi in that point's shading frame (unit, as the bsdf slot wrote it).
struct SpawnInputs {
  const uint32_t* entry = nullptr;
  const float* wi_x = nullptr;
  const float* wi_y = nullptr;
  const float* wi_z = nullptr;
};

/// The next ray from shading point `its` along local direction wi_local, as the scalar
/// integrators spawn it: wi = its.frame.ToWorld(wi_local), origin integrator::SpawnOrigin (p
/// offset along the geometric normal on wi's side), t in [0, inf).
inline Ray SpawnRayAt(const SurfaceInteraction& its, const Vec3f& wi_local) {
  const Vec3f wi = its.frame.ToWorld(wi_local);
  return Ray{integrator::SpawnOrigin(its, wi), wi, 0.0f, integrator::kInfinity};
}

/// The wavefront's spawn slot: row k's ray (SpawnRayAt of its[in.entry[k]]) into lane k % 8 of
/// out[k / 8], for k in [0, n); the lanes after row n - 1 in the last packet are zero (as
/// RayQueue::Push leaves them). `out` holds (n + 7) / 8 packets; the rows of `its` that
/// in.entry names are those of hits, as the interaction slot writes them (frame = Frame(n)).
/// SIMD twin: simd::SpawnRayBatch (simd/wavefront/spawn8.h).
void SpawnRayBatch(const SurfaceInteraction* its, size_t n, const SpawnInputs& in, RayPacket8* out);

}  // namespace ptlab
