// The subpath walks of bidirectional path tracing as a state machine: a walk hands out its next
// ray, the caller traces it (one ray alone, or a batch of walks' rays through packet traversal)
// and hands back the hit; the walk records the vertex and draws its next direction. The same
// steps in the same order per path whoever traces, so a batch renders the one-ray-at-a-time
// oracle's bits whenever its traversal returns the oracle's hits. Internal to bdpt*.
#pragma once

#include "engine/bvh/bvh.h"
#include "engine/render/bdpt_vertex.h"
#include "engine/sampling/sampler.h"

namespace ptlab::bdpt {

// A subpath being extended: its vertices path[0..n) are recorded; `ray` (when active) leaves
// path[n - 1] with solid-angle density pdf_dir carrying throughput beta.
struct Walk {
  Ray ray;
  Color3f beta;
  Color3f ratio{1, 1, 1};  // the product of the BSDF weights, for Russian roulette
  float pdf_dir = 0.0f;
  float eta = 1.0f;
  int bounce = 0;
  int n = 0;
  int max_vertices = 0;
  bool light_subpath = false;
  bool infinite_origin = false;  // light subpath from infinity: fix its first hit's density
  bool active = false;           // `ray` waits to be traced
};

// The camera subpath from camera ray `ray` (camera[0] is the lens point), up to max_vertices.
void StartCameraWalk(const BidirectionalSetup& setup, const Ray& ray, int max_vertices,
                     Subpath* camera, Walk* walk);

// The light subpath: emitter, emission, light[0]; draws the emission's numbers.
void StartLightWalk(const Scene& scene, const BidirectionalSetup& setup, int max_vertices,
                    PathSampler& sampler, Subpath* light, Walk* walk);

// Hands back the hit of walk->ray (null: it escaped): records the vertex, then Russian
// roulette and the BSDF sample; walk->active says whether a next ray waits.
void StepWalk(const Scene& scene, const BidirectionalSetup& setup, const Hit* hit,
              PathSampler& sampler, Subpath* path, Walk* walk);

}  // namespace ptlab::bdpt
