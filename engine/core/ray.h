// A single ray with its parametric interval, the unit of the scalar oracle.
#pragma once

#include "engine/core/vec.h"

namespace ptlab {

/// Ray o + t d for t in [t_min, t_max]. d need not be normalised for intersection.
struct Ray {
  Vec3f o;
  Vec3f d;
  float t_min = 0.0f;
  float t_max = 1e30f;

  Vec3f At(float t) const { return o + d * t; }
};

}  // namespace ptlab
