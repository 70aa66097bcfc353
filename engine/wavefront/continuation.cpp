#include "engine/wavefront/continuation.h"

namespace ptlab {

void ContinuePaths(const ContinueBatchRules& rules, size_t n, const ContinueBatchInputs& in,
                   const ContinueBatchPaths& paths, ContinueBatchOutputs* out) {
  const uint32_t specular = rules.specular ? 1u : 0u;
  // The spawn rows' count and columns in locals: the compiler cannot tell that the stores
  // below leave *out alone, and would load and store it per row.
  size_t m = out->rows;
  uint32_t* const entry = out->entry;
  uint32_t* const owner = out->owner;
  float* const wi_x = out->wi_x;
  float* const wi_y = out->wi_y;
  float* const wi_z = out->wi_z;
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
    paths.specular[i] = in.delta != nullptr ? (in.delta[k] != 0 ? 1u : 0u) : specular;
    paths.prev_pdf[i] = in.pdf[k];
    const uint32_t q = in.entry[k];
    paths.prev_p[i] = in.its[q].p;
    entry[m] = q, wi_x[m] = in.wi_x[k], wi_y[m] = in.wi_y[k], wi_z[m] = in.wi_z[k];
    owner[m++] = i;
  }
  out->rows = m;
}

}  // namespace ptlab
