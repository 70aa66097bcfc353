// The world box of a scene's geometry, which the infinite and directional emitters shine on.
#pragma once

#include "engine/core/vec.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// The box around the scene's triangle rows that belong to no shape group, its analytic
/// spheres, and each instance's group box moved by the instance's to_world (its 8 corners).
/// False (lo, hi untouched) when the scene has no geometry.
bool WorldBounds(const Scene& scene, Vec3f* lo, Vec3f* hi);

}  // namespace ptlab
