// The frame of a rotation given as a transform (emitter and lens orientations in scene files).
#pragma once

#include <cmath>

#include "engine/core/frame.h"
#include "engine/core/transform.h"

namespace ptlab {

/// The frame whose axes are the columns of `to_world`'s upper 3x3 (normalised), when that 3x3 is
/// orthonormal within 1e-4 (a rotation: no scale or shear); false otherwise.
inline bool RotationFrameOf(const Transform& to_world, Frame* frame) {
  const Matrix4& m = to_world.matrix();
  const Vec3f c[3] = {{m.m[0][0], m.m[1][0], m.m[2][0]},
                      {m.m[0][1], m.m[1][1], m.m[2][1]},
                      {m.m[0][2], m.m[1][2], m.m[2][2]}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!(std::fabs(Dot(c[i], c[j]) - (i == j ? 1.0f : 0.0f)) <= 1e-4f)) return false;
  frame->s = Normalize(c[0]), frame->t = Normalize(c[1]), frame->n = Normalize(c[2]);
  return true;
}

}  // namespace ptlab
