// Environment-map samples for a batch of rows: SampleEnvironment row by row.
#include "engine/light/environment_batch.h"

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

}  // namespace ptlab
