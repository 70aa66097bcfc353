// A direction sampled on an infinitely distant emitter (environment map, distant disk).
#pragma once

#include "engine/core/vec.h"

namespace ptlab {

/// wi: unit world direction from the scene towards the emitter (the shadow ray's direction);
/// radiance: what the emitter sends back along -wi; pdf: density of wi w.r.t. solid angle (> 0
/// for a returned sample; equal to the emitter's Pdf(wi) up to float rounding).
struct EnvironmentSample {
  Vec3f wi;
  Color3f radiance;
  float pdf = 0.0f;
};

}  // namespace ptlab
