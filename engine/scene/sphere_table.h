// Analytic spheres (CS184's CGL <sphere>): centre, radius and material per row, world space.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "engine/core/aligned.h"
#include "engine/core/vec.h"
#include "engine/scene/refs.h"

namespace ptlab {

/// One row per sphere. The columns traversal reads (centre, radius) apart from the material,
/// which only shading reads. Spheres never emit (an emissive CGL sphere stays a mesh).
/// A sphere's frame for its surface coordinates: a rotation (row-major 3x3) taking a world
/// direction from the centre into the sphere's object frame, where SphereUv applies (Mitsuba's
/// sphere: uv from to_object · p, so a rotated sphere turns its texture with it).
using SphereUvFrame = std::array<float, 9>;
inline constexpr SphereUvFrame kSphereUvIdentity = {1, 0, 0, 0, 1, 0, 0, 0, 1};

/// a · b (row-major 3x3).
inline SphereUvFrame ComposeSphereUvFrames(const SphereUvFrame& a, const SphereUvFrame& b) {
  SphereUvFrame c{};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      c[3 * r + k] = a[3 * r] * b[k] + a[3 * r + 1] * b[3 + k] + a[3 * r + 2] * b[6 + k];
  return c;
}

struct SphereTable {
  AlignedVector<float> center_x, center_y, center_z, radius;
  std::vector<MaterialRef> material;
  std::vector<SphereUvFrame> uv_frame;  // per row; identity unless a loader sets one

  size_t size() const { return radius.size(); }
  Vec3f Center(size_t i) const { return {center_x[i], center_y[i], center_z[i]}; }
  void Append(const Vec3f& center, float r, MaterialRef m,
              const SphereUvFrame& frame = kSphereUvIdentity) {
    center_x.push_back(center.x), center_y.push_back(center.y), center_z.push_back(center.z);
    radius.push_back(r);
    material.push_back(m);
    uv_frame.push_back(frame);
  }
};

}  // namespace ptlab
