#include "engine/render/continue_batch.h"

namespace ptlab {

void ContinuePaths(const ContinueBatchRules& rules, size_t n, const ContinueBatchInputs& in,
                   const ContinueBatchPaths& paths, ContinueBatchOutputs* out) {
  const uint32_t specular = rules.specular ? 1u : 0u;
  for (size_t k = 0; k < n; ++k) {
    if (!(in.pdf[k] > 0)) continue;  // no sample (BsdfSampleDirection false)
    const uint32_t i = in.path[k];
    const Color3f weight{in.weight_r[k], in.weight_g[k], in.weight_b[k]};
    if (in.roulette_scale != nullptr) {
      paths.throughput[i] *= weight * in.roulette_scale[k];
    } else {
      paths.throughput[i] *= weight;
    }
    paths.eta[i] *= in.eta[k];
    if (rules.cut_black && IsBlack(paths.throughput[i])) continue;
    paths.specular[i] = specular;
    paths.prev_pdf[i] = in.pdf[k];
    const uint32_t q = in.entry[k];
    paths.prev_p[i] = in.its[q].p;
    const size_t m = out->rows++;
    out->entry[m] = q, out->wi_x[m] = in.wi_x[k], out->wi_y[m] = in.wi_y[k];
    out->wi_z[m] = in.wi_z[k], out->owner[m] = i;
  }
}

}  // namespace ptlab
