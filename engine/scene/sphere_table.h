// Analytic spheres (CS184's CGL <sphere>): centre, radius and material per row, world space.
#pragma once

#include <cstddef>
#include <vector>

#include "engine/core/aligned.h"
#include "engine/core/vec.h"
#include "engine/scene/refs.h"

namespace ptlab {

/// One row per sphere. The columns traversal reads (centre, radius) apart from the material,
/// which only shading reads. Spheres never emit (an emissive CGL sphere stays a mesh).
struct SphereTable {
  AlignedVector<float> center_x, center_y, center_z, radius;
  std::vector<MaterialRef> material;

  size_t size() const { return radius.size(); }
  Vec3f Center(size_t i) const { return {center_x[i], center_y[i], center_z[i]}; }
  void Append(const Vec3f& center, float r, MaterialRef m) {
    center_x.push_back(center.x), center_y.push_back(center.y), center_z.push_back(center.z);
    radius.push_back(r);
    material.push_back(m);
  }
};

}  // namespace ptlab
