// Scalar integrators (the oracle): normals, direct_{ems,mats,mis}, whitted, path_{mats,ems,mis}.
#pragma once

#include <cstdint>

#include "engine/bvh/bvh.h"
#include "engine/core/ray.h"
#include "engine/sampling/sampler.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// Read-only state shared by all render threads.
struct RenderContext {
  const Scene& scene;
  const Bvh& bvh;
};

/// Per-thread counters, summed for progress and statistics.
struct RayCounters {
  uint64_t rays = 0;
};

/// Radiance arriving along the camera ray, by the scene's integrator, with the random numbers
/// of `sampler` (the camera ray took its pixel and lens dimensions). Never NaN by design; the
/// caller still drops non-finite samples.
Color3f Li(const RenderContext& ctx, const Ray& ray, PathSampler& sampler,
           RayCounters* counters);

/// Empty when the scene can be rendered by Li, else a message naming what is not supported.
std::string UnsupportedFeature(const Scene& scene);

}  // namespace ptlab
