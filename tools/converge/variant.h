// Variants of a scene for `ptlab converge`: Mitsuba -D style overrides of the loaded scene.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "engine/core/status.h"
#include "engine/render/render.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// A named set of overrides, e.g. "integrator=path_mis,heuristic=power".
struct Variant {
  std::string name;  // the spec as given (or "scene" for no overrides)
  std::vector<std::pair<std::string, std::string>> settings;  // key, value in spec order
};

/// What a variant changes: the scene's descriptions, and the execution path.
struct VariantTarget {
  explicit VariantTarget(Scene* s) : scene(s) {}
  Scene* scene;
  bool scalar = false;  // render with the scalar oracle's kernels instead of simd/'s
  AdaptiveSampling adaptive;  // off unless the variant sets it
};

/// Parses "key=value[,key=value...]" (an empty spec is the scene as loaded). Keys:
///   integrator   normals|direct_ems|direct_mats|direct_mis|whitted|path_mats|path_ems|path_mis
///   heuristic    balance|power
///   lightSamples integer >= 1
///   maxDepth     integer >= -1 (-1: unbounded)
///   sampling     uniform|importance (every environment map)
///   sampler      independent|sobol
///   lights       uniform|power (emitter selection)
///   triangles    area|solidAngle (points on area-light triangles)
///   path         packet|scalar
///   adaptive     BATCH:TOLERANCE (CS184's -a: integer batch >= 2, tolerance > 0), or off
/// An unknown key or a malformed value is an error naming the key and what was expected.
StatusOr<Variant> ParseVariant(const std::string& spec);

/// Applies a parsed variant (settings in order). Fails when the scene cannot take a setting
/// (e.g. importance sampling of a map that was loaded with uniform sampling).
Status ApplyVariant(const Variant& variant, VariantTarget* target);

/// The keys ParseVariant accepts, for messages and --help.
std::string VariantKeys();

}  // namespace ptlab
