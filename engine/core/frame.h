// Orthonormal shading frame around a unit normal (z = normal), the local space of every BSDF.
#pragma once

#include <cmath>

#include "engine/core/vec.h"

namespace ptlab {

/// Right-handed orthonormal basis (s, t, n). Built branch-free from n after
/// Duff et al. 2017, "Building an Orthonormal Basis, Revisited" (JCGT 6(1)).
struct Frame {
  Vec3f s, t, n;

  Frame() : s{1, 0, 0}, t{0, 1, 0}, n{0, 0, 1} {}
  explicit Frame(const Vec3f& normal) : n(normal) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    s = {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
    t = {b, sign + n.y * n.y * a, -n.y};
  }
  Vec3f ToLocal(const Vec3f& v) const { return {Dot(v, s), Dot(v, t), Dot(v, n)}; }
  Vec3f ToWorld(const Vec3f& v) const { return s * v.x + t * v.y + n * v.z; }
};

}  // namespace ptlab
