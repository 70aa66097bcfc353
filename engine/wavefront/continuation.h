// The BSDF stage's finish at a batch of sampled vertices of one material tag: each sampled
// path's throughput and state, as the scalar integrators update them, and the spawn stage's
// row of each path that goes on. The scalar oracle of simd/wavefront/continuation8.h; the wavefront's
// `continuation` slot.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/vec.h"
#include "engine/render/interaction.h"

namespace ptlab {

/// What the batch reads: n rows of the BSDF stage's columns (one material tag's group, as the
/// bsdf slot wrote them), each of a different path, and the shading points by queue entry.
struct ContinueBatchInputs {
  const uint32_t* path = nullptr;   // the row's path
  const uint32_t* entry = nullptr;  // its queue entry (the shading point's row of `its`)
  const float *weight_r = nullptr, *weight_g = nullptr, *weight_b = nullptr;
  const float* roulette_scale = nullptr;  // Whitted's roulette only (else null: not read)
  const float* pdf = nullptr;             // 0 (or NaN): no sample
  const float* eta = nullptr;             // the sample's relative index of refraction
  const float *wi_x = nullptr, *wi_y = nullptr, *wi_z = nullptr;  // local, unit
  const SurfaceInteraction* its = nullptr;                        // by queue entry: p is read
  // matB: per row, non-zero where the sample took a delta lobe (ShadeOutputs::delta); null:
  // every row is as rules.specular says.
  const float* delta = nullptr;
};

/// The path state the batch reads and writes, by path id.
struct ContinueBatchPaths {
  Color3f* throughput = nullptr;  // times the sample's weight
  float* eta = nullptr;           // times the sample's eta
  uint32_t* specular = nullptr;   // 1: the last vertex was of a delta material (a flag)
  float* prev_pdf = nullptr;      // the sample's pdf
  Vec3f* prev_p = nullptr;        // the vertex's point
};

/// The spawn stage's rows and the next queue's owners, appended at `rows` (in and out), in row
/// order; each column has room for `rows` + n rows.
struct ContinueBatchOutputs {
  uint32_t* entry = nullptr;  // the shading point's queue entry
  float *wi_x = nullptr, *wi_y = nullptr, *wi_z = nullptr;
  uint32_t* owner = nullptr;  // the path
  size_t rows = 0;
};

/// What every row of the batch shares.
struct ContinueBatchRules {
  bool specular = false;   // the group's tag is a delta material (IsDeltaMaterial)
  bool cut_black = false;  // a path whose throughput turns black ends here
};

/// Per row k, as the wavefront's loop did: nothing unless pdf > 0; then, for path i,
/// throughput[i] *= weight (· roulette_scale first, when given), eta[i] *= eta; the path ends
/// if rules.cut_black and its throughput is black (IsBlack); else specular[i], prev_pdf[i] and
/// prev_p[i] (its[entry].p) are set (specular[i] from in.delta when given) and the row's spawn row (entry, wi) and owner (i) appended.
void ContinuePaths(const ContinueBatchRules& rules, size_t n, const ContinueBatchInputs& in,
                   const ContinueBatchPaths& paths, ContinueBatchOutputs* out);

}  // namespace ptlab
