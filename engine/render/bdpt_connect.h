// The connection strategies of bidirectional path tracing, cut at their shadow ray: Prepare
// draws the strategy's numbers and computes its unweighted contribution and the segment to test;
// the caller traces the segments (alone or in packets) and Finish weights the unoccluded ones
// by MIS. Internal to bdpt*.
#pragma once

#include "engine/render/bdpt_vertex.h"
#include "engine/sampling/sampler.h"

namespace ptlab::bdpt {

// One strategy (s, t) of one sample with a contribution, waiting for its shadow ray.
struct Connection {
  int s = 0, t = 0;
  bool shadow = false;   // needs its segment unoccluded (every strategy but s = 0)
  float sx = 0, sy = 0;  // t = 1: the film position it lands at
  Color3f value;         // s = 0: with its MIS weight; else without
};

// Strategy (s, t) (t >= 2, or t = 1 with s >= 2) of the subpaths light[0..) and camera[0..):
// false when it contributes nothing. Else *out, the segment to test in *shadow (out->shadow),
// and for s = 1 or t = 1 the sampled vertex in *endpoint (the other vertex of the connection).
bool PrepareConnection(const Scene& scene, const BidirectionalSetup& setup, Subpath& light, int s,
                       Subpath& camera, int t, PathSampler& sampler, bool ptracer, Connection* out,
                       Ray* shadow, Vertex* endpoint);

// The contribution of connection c whose segment is free, MIS weight included (for t = 1
// appended to *splats, and 0 returned). `endpoint`: Prepare's sampled vertex.
Color3f FinishConnection(const Scene& scene, const BidirectionalSetup& setup, Subpath& light,
                         Subpath& camera, const Connection& c, const Vertex& endpoint, bool ptracer,
                         std::vector<LightSplat>* splats);

}  // namespace ptlab::bdpt
