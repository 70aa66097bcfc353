// Bidirectional path tracing (Veach, ch. 10) and the particle tracer: the scalar oracle.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/core/ray.h"
#include "engine/light/emission.h"
#include "engine/render/camera_importance.h"
#include "engine/render/integrator.h"
#include "engine/sampling/sampler.h"

namespace ptlab {

/// True for the integrators that trace light subpaths and splat into other pixels (bdpt,
/// ptracer): they run on the scalar path (RenderTileScalar) with a light film beside the
/// camera's (render.cpp).
constexpr bool IsBidirectional(IntegratorDesc::Type type) {
  return type == IntegratorDesc::Type::kBdpt || type == IntegratorDesc::Type::kPtracer;
}

/// A light-tracing contribution (strategy t = 1) landing at film position (sx, sy) (pixels):
/// the path's contribution with the camera's importance (CameraImportance), MIS weight
/// included; the film divides it by the samples per pixel and spreads it with the normalised
/// pixel filter (LightFilm).
struct LightSplat {
  float sx = 0, sy = 0;
  Color3f value;
};

/// Per-render state of the bidirectional integrators.
struct BidirectionalSetup {
  explicit BidirectionalSetup(const Scene& scene)
      : camera(scene.camera), sphere(BoundingSphereOf(scene)) {}
  CameraImportance camera;
  SceneSphere sphere;
};

/// Most vertices of a subpath when maxDepth is unbounded (-1); Russian roulette ends paths long
/// before (a path this long carries ~0.99^250 of its weight).
inline constexpr int kBidirectionalMaxVertices = 256;

/// First sampler depth of the light subpath's decisions: the light subpath's vertex k draws
/// the dimensions of DecisionDimension(kLightSubpathDepth + k, ...) (its emission: k = 0), far
/// from the camera subpath's (which are path_mis's), so the Sobol' sampler keeps the two apart.
inline constexpr int kLightSubpathDepth = 1 << 12;

/// One pixel sample of `bdpt` or `ptracer` (scene.integrator.type), for the camera ray `ray`
/// through film position (sx, sy): returns the radiance of the strategies with t >= 2 camera
/// vertices (s = 0 and connections; for ptracer only emitters seen directly) and appends the
/// t = 1 strategies' contributions to *splats. MIS: power heuristic or balance
/// (scene.integrator.power_heuristic); maxDepth as for path_mis (s + t - 2 bounces).
Color3f LiBidirectional(const RenderContext& ctx, const BidirectionalSetup& setup, const Ray& ray,
                        PathSampler& sampler, RayCounters* counters,
                        std::vector<LightSplat>* splats);

}  // namespace ptlab
