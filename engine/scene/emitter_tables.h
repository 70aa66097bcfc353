// Emitter components: area lights on meshes (one row per emitting mesh).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/core/aligned.h"
#include "engine/core/vec.h"
#include "engine/scene/refs.h"

namespace ptlab {

/// Diffuse area lights, one-sided (they emit on the side of the shading normal, as in Nori).
/// Sampling is uniform by area over the mesh's triangles: per-light triangle CDFs are stored
/// back to back in `triangle_cdf`, light i owning [cdf_offset[i], cdf_offset[i] + triangle_count).
struct AreaLightTable {
  std::vector<Color3f> radiance;
  std::vector<uint32_t> mesh;            // row in MeshTable
  std::vector<float> area;               // total surface area (world units²)
  std::vector<uint32_t> cdf_offset;
  AlignedVector<float> triangle_cdf;     // normalised, last entry of each light = 1

  size_t size() const { return radiance.size(); }
};

}  // namespace ptlab
