// Environment-map samples for a batch of rows: the columns and the oracle of the SIMD batch.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/light/environment_sample.h"
#include "engine/scene/emitter_tables.h"

namespace ptlab {

/// A batch's numbers as columns: row i is SampleEnvironment's u = (u_x[i], u_y[i]).
struct EnvironmentBatchInputs {
  const float *u_x = nullptr, *u_y = nullptr;
};

/// What a batch writes per row: EnvironmentSample's wi (unit, world), radiance (r, g, b) and
/// solid-angle pdf. Every row is written; a row without a sample (a black map) is all zero.
struct EnvironmentBatchOutputs {
  float *wi_x = nullptr, *wi_y = nullptr, *wi_z = nullptr;
  float *r = nullptr, *g = nullptr, *b = nullptr;
  float* pdf = nullptr;
};

/// SampleEnvironment(table, map, u) for n rows of one map (row `map` of the table): the oracle
/// of simd::SampleEnvironmentBatch (simd/wavefront/environment8.h), bit-identical to SampleEnvironment
/// row by row.
void SampleEnvironmentBatch(const EnvironmentMapTable& table, uint32_t map, size_t n,
                            const EnvironmentBatchInputs& in, const EnvironmentBatchOutputs& out);

/// A batch of escaping rays as columns: row i is the world direction (w_x[i], w_y[i], w_z[i])
/// (unit, pointing away from the scene).
struct EnvironmentEvalInputs {
  const float *w_x = nullptr, *w_y = nullptr, *w_z = nullptr;
};

/// What an evaluation writes per row: EnvironmentRadiance (r, g, b) and, when pdf is not null,
/// EnvironmentPdf (the density with which SampleEnvironment produces the direction, for MIS).
struct EnvironmentEvalOutputs {
  float *r = nullptr, *g = nullptr, *b = nullptr;
  float* pdf = nullptr;
};

/// EnvironmentRadiance and EnvironmentPdf of map `map` for n escaping rays: the oracle of
/// simd::EvalEnvironmentBatch, bit-identical to the two functions row by row.
void EvalEnvironmentBatch(const EnvironmentMapTable& table, uint32_t map, size_t n,
                          const EnvironmentEvalInputs& in, const EnvironmentEvalOutputs& out);

/// Writes s into row i of `out`.
inline void SetEnvironmentRow(const EnvironmentBatchOutputs& out, size_t i,
                              const EnvironmentSample& s) {
  out.wi_x[i] = s.wi.x, out.wi_y[i] = s.wi.y, out.wi_z[i] = s.wi.z;
  out.r[i] = s.radiance.r, out.g[i] = s.radiance.g, out.b[i] = s.radiance.b;
  out.pdf[i] = s.pdf;
}

/// SampleEnvironment for row i of a batch (all zero where it returns no sample).
EnvironmentSample SampleEnvironmentRow(const EnvironmentMapTable& table, uint32_t map,
                                       const EnvironmentBatchInputs& in, size_t i);

}  // namespace ptlab
