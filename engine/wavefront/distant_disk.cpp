// Distant-disk samples for a batch of rows: SampleDistantDisk row by row.
#include "engine/wavefront/distant_disk.h"

#include "engine/light/distant_disk.h"

namespace ptlab {

EnvironmentSample SampleDistantDiskRow(const DistantDiskTable& table, uint32_t disk,
                                       const EnvironmentBatchInputs& in, size_t i) {
  EnvironmentSample s;
  if (!SampleDistantDisk(table, disk, {in.u_x[i], in.u_y[i]}, &s)) return EnvironmentSample{};
  return s;
}

void SampleDistantDiskBatch(const DistantDiskTable& table, uint32_t disk, size_t n,
                            const EnvironmentBatchInputs& in, const EnvironmentBatchOutputs& out) {
  for (size_t i = 0; i < n; ++i)
    SetEnvironmentRow(out, i, SampleDistantDiskRow(table, disk, in, i));
}

}  // namespace ptlab
