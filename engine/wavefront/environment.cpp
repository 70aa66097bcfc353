// Environment-map samples and evaluations for a batch of rows: SampleEnvironment,
// EnvironmentRadiance and EnvironmentPdf row by row.
#include "engine/wavefront/environment.h"

#include "engine/light/environment_map.h"

namespace ptlab {

EnvironmentSample SampleEnvironmentRow(const EnvironmentMapTable& table, uint32_t map,
                                       const EnvironmentBatchInputs& in, size_t i) {
  EnvironmentSample s;
  if (!SampleEnvironment(table, map, {in.u_x[i], in.u_y[i]}, &s)) return EnvironmentSample{};
  return s;
}

void SampleEnvironmentBatch(const EnvironmentMapTable& table, uint32_t map, size_t n,
                            const EnvironmentBatchInputs& in, const EnvironmentBatchOutputs& out) {
  for (size_t i = 0; i < n; ++i) SetEnvironmentRow(out, i, SampleEnvironmentRow(table, map, in, i));
}

void EvalEnvironmentBatch(const EnvironmentMapTable& table, uint32_t map, size_t n,
                          const EnvironmentEvalInputs& in, const EnvironmentEvalOutputs& out) {
  for (size_t i = 0; i < n; ++i) {
    const Vec3f w{in.w_x[i], in.w_y[i], in.w_z[i]};
    Color3f L;
    if (out.pdf) {
      out.pdf[i] = EnvironmentRadianceAndPdf(table, map, w, &L);  // one (u, v) for both
    } else {
      L = EnvironmentRadiance(table, map, w);
    }
    out.r[i] = L.r, out.g[i] = L.g, out.b[i] = L.b;
  }
}

}  // namespace ptlab
