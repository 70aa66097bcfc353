// The shading point of a ray hit: position, normals and the components the hit refers to.
#pragma once

#include "engine/bvh/bvh.h"
#include "engine/core/frame.h"
#include "engine/core/ray.h"
#include "engine/scene/scene.h"

namespace ptlab {

struct SurfaceInteraction {
  Vec3f p;        // world-space hit point, from barycentrics (not o + t d)
  Vec3f ng;       // unit geometric normal, (v1 - v0) x (v2 - v0)
  Frame frame;    // shading frame, z = shading normal
  uint32_t prim = kNoHit;
  MaterialRef material;
  EmitterRef emitter;
};

/// Builds the interaction for a hit (hit.prim must be valid).
SurfaceInteraction MakeInteraction(const Scene& scene, const Hit& hit);

}  // namespace ptlab
