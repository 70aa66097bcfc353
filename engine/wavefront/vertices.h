// The sampling stage's decisions at a batch of path vertices of one material group, with the
// independent sampler: the emitter pick of the vertex's one emitter sample, Nori's Russian
// roulette and the BSDF's numbers, written as rows of the emitter and BSDF stages' columns.
// The scalar oracle of simd/wavefront/vertices8.h; the wavefront's `vertices` slot.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/vec.h"
#include "engine/render/interaction.h"
#include "engine/sampling/sampler.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// What the batch reads: n rows, each a queue entry whose hit goes on (all of one
/// MaterialGroup); the shading points and wo stay where the wavefront built them, by queue
/// entry, and the path state by path id (owner of the entry).
struct VertexBatchInputs {
  const uint32_t* entries = nullptr;        // the rows' queue entries
  const uint32_t* owner = nullptr;          // by queue entry: its path
  const SurfaceInteraction* its = nullptr;  // by queue entry: p and material are read
  const Vec3f* wo = nullptr;                // by queue entry
  const float* eta = nullptr;               // by path (read by the roulette only)
};

/// The path state the batch reads and writes, by path id.
struct VertexBatchPaths {
  PathSampler* sampler = nullptr;     // independent; advanced past the row's draws
  Color3f* throughput = nullptr;      // a roulette survivor's is divided by its continuation
  Color3f* nee_throughput = nullptr;  // with an emitter sample: the throughput at the vertex
};

/// The emitter stage's area-light rows (the wavefront's EmitterColumns inputs).
struct AreaPickColumns {
  uint32_t *request = nullptr, *entry = nullptr, *light = nullptr;
  float *pick_pmf = nullptr, *ref_x = nullptr, *ref_y = nullptr, *ref_z = nullptr;
  float *wo_x = nullptr, *wo_y = nullptr, *wo_z = nullptr, *u_x = nullptr, *u_y = nullptr;
};

/// The BSDF stage's rows (the wavefront's BsdfColumns inputs).
struct BsdfPickColumns {
  uint32_t *path = nullptr, *entry = nullptr, *material_index = nullptr;
  float *roulette_scale = nullptr, *wo_x = nullptr, *wo_y = nullptr, *wo_z = nullptr;
  float *u_lobe = nullptr, *u_x = nullptr, *u_y = nullptr;
};

/// What the batch writes. Rows are appended to the area and BSDF columns at their counts
/// (area_rows, bsdf_rows: in and out), in row order. With emitter samples, request
/// first_request + k belongs to row k: request_traced[that] = 0 and nee_paths[that] = its
/// path, for every row; the requests of rows whose throughput is not finite are appended to
/// `nonfinite` at nonfinite_rows (in and out).
struct VertexBatchOutputs {
  AreaPickColumns area;
  BsdfPickColumns bsdf;
  uint8_t* request_traced = nullptr;
  uint32_t* nee_paths = nullptr;
  uint32_t* nonfinite = nullptr;
  size_t area_rows = 0, bsdf_rows = 0, nonfinite_rows = 0;
};

/// The decisions the vertex takes, the same for every row of the batch.
struct VertexBatchRules {
  int depth = 0;                // DecisionDimension's depth (unused by `independent`)
  bool emitter_sample = false;  // one emitter sample (the pick, then the point)
  bool roulette = false;        // Nori's roulette (from depth 3), before the BSDF's numbers
  uint32_t first_request = 0;   // the request of row 0 (with emitter_sample)
};

/// True when the batch serves `scene`: at least one emitter and every emitter an area light
/// (each pick goes to the area-light columns), picked uniformly or by power from at most
/// kScanUpperBoundMax emitters (SelectEmitter's scan; the SIMD twin has no guide tables).
bool VertexBatchFits(const Scene& scene);

/// Per row k, in the wavefront's per-path order of numbers: with rules.emitter_sample, the pick
/// number and the point (Get1D, Get2D), SelectEmitter, and (pick pmf > 0) the area row; then
/// with rules.roulette, q = min(max component of throughput · η², 0.99), and the path ends
/// unless the number is < q (else throughput *= 1/q); then the lobe number and direction
/// (DrawBsdfNumbers) into the BSDF row, roulette_scale 1. `scene` must fit (VertexBatchFits).
void DecideVertices(const Scene& scene, const VertexBatchRules& rules, size_t n,
                    const VertexBatchInputs& in, const VertexBatchPaths& paths,
                    VertexBatchOutputs* out);

}  // namespace ptlab
