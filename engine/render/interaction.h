// The shading point of a ray hit: position, normals and the components the hit refers to.
#pragma once

#include "engine/bvh/bvh.h"
#include "engine/core/frame.h"
#include "engine/core/ray.h"
#include "engine/scene/scene.h"

namespace ptlab {

struct SurfaceInteraction {
  Vec3f p;        // world-space hit point: from barycentrics (not o + t d); on a sphere
                  // o + t d projected onto the surface
  Vec3f ng;       // unit geometric normal, (v1 - v0) x (v2 - v0); a sphere's outward normal
  Frame frame;    // shading frame, z = shading normal
  uint32_t prim = kNoHit;  // Hit::prim: a triangle row, or kSphereHitBit | sphere row
  MaterialRef material;
  EmitterRef emitter;
};

/// Builds the interaction for a hit of `ray` (hit.prim must be valid). A sphere hit's shading
/// normal is (p - c)/r; spheres never emit.
SurfaceInteraction MakeInteraction(const Scene& scene, const Ray& ray, const Hit& hit);

}  // namespace ptlab
