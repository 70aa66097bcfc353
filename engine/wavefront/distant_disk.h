// Distant-disk samples for a batch of rows: the oracle of the SIMD batch.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/light/environment_sample.h"
#include "engine/scene/emitter_tables.h"
#include "engine/wavefront/environment.h"

namespace ptlab {

// A distant disk's sample is an EnvironmentSample (wi, radiance, pdf) drawn from two numbers,
// as an environment map's is, so its batch reads and writes the same columns.

/// SampleDistantDisk(table, disk, u) for n rows of one disk (row `disk` of the table), u =
/// (in.u_x[i], in.u_y[i]); every output row is written, all zero for a black disk. The oracle
/// of simd::SampleDistantDiskBatch (simd/wavefront/distant_disk8.h), bit-identical to SampleDistantDisk
/// row by row.
void SampleDistantDiskBatch(const DistantDiskTable& table, uint32_t disk, size_t n,
                            const EnvironmentBatchInputs& in, const EnvironmentBatchOutputs& out);

/// SampleDistantDisk for row i of a batch (all zero where it returns no sample).
EnvironmentSample SampleDistantDiskRow(const DistantDiskTable& table, uint32_t disk,
                                       const EnvironmentBatchInputs& in, size_t i);

}  // namespace ptlab
