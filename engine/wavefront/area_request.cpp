// The emitter stage's finish of a batch of area-light samples: the scalar oracle.
#include "engine/wavefront/area_request.h"

namespace ptlab {

void AreaEmitterRequestBatch(const Scene& scene, MaterialTag /*tag*/, bool mis, size_t n,
                             const AreaRequestInputs& in, const AreaRequestOutputs& out) {
  for (size_t c = 0; c < n; ++c) {
    AreaLightSample ls;
    ls.p = {in.p_x[c], in.p_y[c], in.p_z[c]};
    ls.n = {in.n_x[c], in.n_y[c], in.n_z[c]};
    ls.ng = {in.ng_x[c], in.ng_y[c], in.ng_z[c]};
    ls.pdf = in.pdf[c];
    ls.radiance = in.le_r != nullptr ? Color3f{in.le_r[c], in.le_g[c], in.le_b[c]}
                                     : scene.area_lights.radiance[in.light[c]];
    const Vec3f wo{in.wo_x[c], in.wo_y[c], in.wo_z[c]};
    SetAreaRequestRow(out, c,
                      integrator::AreaEmitterSampleRequest(scene, in.its[in.entry[c]], wo, mis, ls,
                                                           in.pick_pmf[c]));
  }
}

}  // namespace ptlab
