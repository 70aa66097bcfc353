// The wavefront's spawn stage: the next rays of the paths that go on, from their shading points
// and sampled local directions, written straight into ray packets.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>

#include "engine/bvh/ray_offset.h"
#include "engine/core/frame.h"
#include "engine/core/packet8.h"
#include "engine/core/ray.h"
#include "engine/render/interaction.h"

namespace ptlab {

/// One row per path that goes on, in the order its ray takes in the next queue: the row of
/// its shading point in the interaction stage's columns and the sampled direction wi in that
/// point's shading frame (unit, as the bsdf slot wrote it).
struct SpawnInputs {
  const uint32_t* entry = nullptr;
  const float* wi_x = nullptr;
  const float* wi_y = nullptr;
  const float* wi_z = nullptr;
};

/// The next ray from shading point row q of `points` along local direction wi_local, as the
/// scalar integrators spawn it from the SurfaceInteraction that InteractionAt builds from that
/// row: wi = Frame(n).ToWorld(wi_local), origin integrator::SpawnOrigin (p offset along the
/// geometric normal on wi's side), t in [0, inf).
inline Ray SpawnRayAt(const InteractionColumns& points, size_t q, const Vec3f& wi_local) {
  const Frame frame(Vec3f{points.n_x[q], points.n_y[q], points.n_z[q]});
  const Vec3f p{points.p_x[q], points.p_y[q], points.p_z[q]};
  const Vec3f ng{points.ng_x[q], points.ng_y[q], points.ng_z[q]};
  const Vec3f wi = frame.ToWorld(wi_local);
  return Ray{OffsetRayOrigin(p, Dot(ng, wi) >= 0 ? ng : -ng), wi, 0.0f,
             std::numeric_limits<float>::infinity()};
}

/// The wavefront's spawn slot: row k's ray (SpawnRayAt of points row in.entry[k]) into lane
/// k % 8 of out[k / 8], for k in [0, n); the lanes after row n - 1 in the last packet are
/// zero (as RayQueue::Push leaves them). `out` holds (n + 7) / 8 packets; the rows of
/// `points` that in.entry names are those of hits (written by the interaction slot).
/// SIMD twin: simd::SpawnRayBatch (simd/spawn8.h).
void SpawnRayBatch(const InteractionColumns& points, size_t n, const SpawnInputs& in,
                   RayPacket8* out);

}  // namespace ptlab
