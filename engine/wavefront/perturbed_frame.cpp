// normal: the perturbed shading frames of a batch of rows (oracle).
#include "engine/wavefront/perturbed_frame.h"

#include "engine/bsdf/perturbed_frame.h"

namespace ptlab {

void PerturbedFrameBatch(const MaterialTables& m, MaterialTag tag, const uint32_t* material_index,
                         size_t n, const ShadeInputs& in, float* const frame[9]) {
  for (size_t i = 0; i < n; ++i) {
    const int64_t id = m.perturbation.Of(MaterialRef::Make(tag, material_index[i]));
    Frame f;
    if (id >= 0)
      f = PerturbedFrame(m, id, {in.wo.x[i], in.wo.y[i], in.wo.z[i]}, RowTextureSite(in.texture, i));
    const float v[9] = {f.s.x, f.s.y, f.s.z, f.t.x, f.t.y, f.t.z, f.n.x, f.n.y, f.n.z};
    for (int k = 0; k < 9; ++k) frame[k][i] = v[k];
  }
}

}  // namespace ptlab
