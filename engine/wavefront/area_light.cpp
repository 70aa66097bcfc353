// Emitter stage, area lights: the scalar oracle (engine/wavefront/area_light.h).
#include "engine/wavefront/area_light.h"

namespace ptlab {

void SampleAreaLightBatch(const Scene& scene, TriangleSampling mode, size_t n,
                          const AreaLightBatchInputs& in, const AreaLightBatchOutputs& out) {
  for (size_t i = 0; i < n; ++i) {
    SetAreaLightRow(out, i,
                    SampleAreaLight(scene, in.light[i], AreaLightRowRef(in, i), mode,
                                    AreaLightRowU(in, i)));
  }
}

}  // namespace ptlab
