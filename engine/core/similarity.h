// Whether an affine matrix is a similarity: what keeps an analytic sphere a sphere.
#pragma once

#include <cmath>

#include "engine/core/transform.h"
#include "engine/core/vec.h"

namespace ptlab {

/// True when the upper 3x3 of m is a rotation (or reflection) times one scale factor > 0,
/// which it stores in *scale: its columns are finite, orthogonal and of one length, each to
/// 1e-5 relative (float precision of a composed transform).
inline bool IsSimilarity(const Matrix4& m, float* scale) {
  const Vec3f c[3] = {{m.m[0][0], m.m[1][0], m.m[2][0]},
                      {m.m[0][1], m.m[1][1], m.m[2][1]},
                      {m.m[0][2], m.m[1][2], m.m[2][2]}};
  const float l = Length(c[0]);
  if (!(l > 0) || !std::isfinite(l)) return false;
  constexpr float kTolerance = 1e-5f;
  for (int i = 0; i < 3; ++i) {
    if (!(std::fabs(Length(c[i]) - l) <= kTolerance * l)) return false;
    if (!(std::fabs(Dot(c[i], c[(i + 1) % 3])) <= kTolerance * l * l)) return false;
  }
  *scale = l;
  return true;
}

}  // namespace ptlab
