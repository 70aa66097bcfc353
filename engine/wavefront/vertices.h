// The sampling stage's decisions at a batch of path vertices of one material group, for every
// integrator and both samplers: the vertex's emitter samples (light_samples picks, each a row of
// the area-light columns or of the other picks, which the wavefront routes to their stages),
// the roulette (Nori's or Whitted's) and the BSDF's numbers, written as rows of the emitter and
// BSDF stages' columns. The independent sampler's numbers are drawn here, from each path's
// stream; Sobol' numbers are drawn before, in batch (Wavefront::DrawVertexNumbers), and read
// from columns. The scalar oracle of simd/wavefront/vertices8.h; the wavefront's `vertices` slot.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/vec.h"
#include "engine/sampling/sampler.h"
#include "engine/scene/scene.h"
#include "engine/wavefront/interaction.h"

namespace ptlab {

/// What the batch reads: n rows, each a queue entry whose hit goes on (all of one
/// MaterialGroup); the shading points and wo stay where the wavefront built them, by queue
/// entry, and the path state by path id (owner of the entry). With rules.sobol, the vertex's
/// numbers, by row: emitter sample s of row k at light_point[s * light_stride + k] (its x picks
/// the emitter and is reused, remapped, as the point's x), the roulette's, the BSDF's lobe and
/// direction at k.
struct VertexBatchInputs {
  const uint32_t* entries = nullptr;        // the rows' queue entries
  const uint32_t* owner = nullptr;          // by queue entry: its path
  const SurfaceInteraction* its = nullptr;  // by queue entry: p and material are read
  const Vec3f* wo = nullptr;                // by queue entry
  const float* eta = nullptr;               // by path (read by Nori's roulette only)
  // Sobol' (rules.sobol) only.
  const Vec2f* light_point = nullptr;
  size_t light_stride = 0;
  const float* roulette = nullptr;
  const float* bsdf_lobe = nullptr;
  const Vec2f* bsdf_direction = nullptr;
};

/// The path state the batch reads and writes, by path id.
struct VertexBatchPaths {
  PathSampler* sampler = nullptr;     // independent: advanced past the row's draws
  Color3f* throughput = nullptr;      // a Nori roulette survivor's is divided by q
  Color3f* nee_throughput = nullptr;  // with emitter samples: the throughput at the vertex
};

/// The emitter stage's area-light rows (the wavefront's EmitterColumns inputs).
struct AreaPickColumns {
  uint32_t *request = nullptr, *entry = nullptr, *light = nullptr;
  float *pick_pmf = nullptr, *ref_x = nullptr, *ref_y = nullptr, *ref_z = nullptr;
  float *wo_x = nullptr, *wo_y = nullptr, *wo_z = nullptr, *u_x = nullptr, *u_y = nullptr;
};

/// The picks of every other emitter (environment maps, distant disks, delta lights), which the
/// wavefront routes to their stages: the request, queue entry, emitter (EmitterRef's bits),
/// pick probability and the point's numbers.
struct OtherPickColumns {
  uint32_t *request = nullptr, *entry = nullptr, *emitter = nullptr;
  float *pick_pmf = nullptr, *u_x = nullptr, *u_y = nullptr;
};

/// The BSDF stage's rows (the wavefront's BsdfColumns inputs).
struct BsdfPickColumns {
  uint32_t *path = nullptr, *entry = nullptr, *material_index = nullptr;
  float *roulette_scale = nullptr, *wo_x = nullptr, *wo_y = nullptr, *wo_z = nullptr;
  float *u_lobe = nullptr, *u_x = nullptr, *u_y = nullptr;
};

/// What the batch writes. Rows are appended to the area, other and BSDF columns at their counts
/// (area_rows, other_rows, bsdf_rows: in and out), in request order (row k's samples s = 0, 1,
/// ... one after the other) and row order. With emitter samples, request first_request +
/// k · light_samples + s belongs to sample s of row k: request_traced[that] = 0 for every one,
/// and nee_paths[first_request / light_samples + k] = the row's path; with one sample per
/// vertex, the requests of rows whose throughput is not finite are appended to `nonfinite` at
/// nonfinite_rows (in and out).
struct VertexBatchOutputs {
  AreaPickColumns area;
  OtherPickColumns other;
  BsdfPickColumns bsdf;
  uint8_t* request_traced = nullptr;
  uint32_t* nee_paths = nullptr;
  uint32_t* nonfinite = nullptr;
  size_t area_rows = 0, other_rows = 0, bsdf_rows = 0, nonfinite_rows = 0;
};

/// The decisions the vertex takes, the same for every row of the batch (the wavefront derives
/// them from the integrator's rules and the group's material).
struct VertexBatchRules {
  enum class Roulette : uint8_t {
    kNone,
    kNori,     // q = min(max component of throughput · η², 0.99); throughput /= q
    kWhitted,  // ends at kWhittedMaxDepth, else goes on with kWhittedContinuation
  };
  int depth = 0;                // DecisionDimension's depth; Whitted's depth limit
  bool emitter_sample = false;  // light_samples emitter samples (when the scene has emitters)
  int light_samples = 1;        // ≥ 1
  bool ends_path = false;       // no BSDF row: the path ends after its emitter samples
  Roulette roulette = Roulette::kNone;  // before the BSDF's numbers
  bool sobol = false;           // the numbers come from the inputs' columns, none are drawn
  uint32_t first_request = 0;   // row 0's sample 0's request; a multiple of light_samples
};

/// Per row k, in the scalar integrators' order of numbers: with rules.emitter_sample, for each
/// sample s the pick number and the point (Get1D, Get2D; with Sobol', the point alone, its x
/// folded), SelectEmitter, and (pick pmf > 0) an area or other row; unless rules.ends_path,
/// the roulette (Nori's: the path ends unless the number is < q, else throughput *= 1/q;
/// Whitted's: it ends at depth ≥ kWhittedMaxDepth without a number, or unless the number is
/// < kWhittedContinuation, else roulette_scale 1/kWhittedContinuation), then the lobe number and
/// direction (DrawBsdfNumbers) into the BSDF row.
void DecideVertices(const Scene& scene, const VertexBatchRules& rules, size_t n,
                    const VertexBatchInputs& in, const VertexBatchPaths& paths,
                    VertexBatchOutputs* out);

}  // namespace ptlab
