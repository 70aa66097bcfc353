// The spawn stage's oracle: SpawnRayAt row by row.
#include "engine/wavefront/spawn.h"

namespace ptlab {

void SpawnRayBatch(const SurfaceInteraction* its, size_t n, const SpawnInputs& in,
                   RayPacket8* out) {
  for (size_t k = 0; k < n; ++k) {
    const Vec3f wi_local{in.wi_x[k], in.wi_y[k], in.wi_z[k]};
    SetLaneRay(&out[k / kPacketWidth], int(k % kPacketWidth),
               SpawnRayAt(its[in.entry[k]], wi_local));
  }
  // The last packet's lanes without a row: zero, as a packet that RayQueue::Push starts.
  for (size_t k = n; k % kPacketWidth != 0; ++k) {
    SetLaneRay(&out[k / kPacketWidth], int(k % kPacketWidth), Ray{{}, {}, 0.0f, 0.0f});
  }
}

}  // namespace ptlab
