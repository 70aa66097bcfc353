// Sanity of a render's setup after the scene files and every flag are applied: a camera,
// lens or light that would make a degenerate image (black, constant, or a film one pixel
// high) is an error that says which parameter and its accepted range, not an image.
#pragma once

#include "engine/core/status.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// Smallest and largest field of view, in degrees, on either image axis: below, the film is a
/// few ulps of float wide (xfov 1e-30 rendered a constant image); above, tan(fov/2) is so
/// large that almost every pixel looks along the image plane (yfov 179 at a huge aspect
/// rendered black).
inline constexpr double kMinFieldOfViewDeg = 1e-3;
inline constexpr double kMaxFieldOfViewDeg = 179.0;

/// OK when the camera (film size, both fields of view, clip planes, lens and focus, a finite
/// world frame within kMaxWorldCoordinate) and the lights (finite positions within
/// kMaxWorldCoordinate, unit directions, spheres' centres and radii) make a proper image;
/// else "camera: ..." / "point light 2: ..." with the value and the accepted range.
Status CheckRenderSetup(const Scene& scene);

}  // namespace ptlab
