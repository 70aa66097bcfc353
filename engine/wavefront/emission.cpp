#include "engine/wavefront/emission.h"

#include "engine/render/integrator_common.h"

namespace ptlab {

void AddAreaEmissions(const Scene& scene, const EmissionBatchRules& rules, size_t n,
                      const EmissionBatchInputs& in, const EmissionBatchPaths& paths) {
  const bool power = scene.integrator.power_heuristic;
  for (size_t k = 0; k < n; ++k) {
    const uint32_t q = in.entry[k];
    const uint32_t i = in.owner[q];
    const RayPacket8& packet = in.rays[q / kPacketWidth];
    const size_t j = q % kPacketWidth;
    const Vec3f d{packet.dir_x[j], packet.dir_y[j], packet.dir_z[j]};
    const SurfaceInteraction& its = in.its[q];
    const Color3f Le = integrator::Emitted(scene, its, -d / Length(d));
    if (IsBlack(Le)) continue;
    float w = 1.0f;
    if (rules.nee && !paths.specular[i]) {
      w = rules.mis
              ? integrator::MisWeight(paths.prev_pdf[i],
                                      integrator::EmitterPdf(scene, its, paths.prev_p[i]), power)
              : 0.0f;
    }
    paths.L[i] += paths.throughput[i] * Le * w;
  }
}

}  // namespace ptlab
