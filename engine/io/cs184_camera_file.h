// CS184 pathtracer camera settings files (its `C` key writes one, `-c FILE` reads it).
#pragma once

#include <string>

#include "engine/core/status.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// Sets `camera` from a CS184 camera settings file, the whitespace-separated numbers its
/// Camera::dump_settings writes, in this order:
///   hFov vFov ar nClip fClip / pos (3) targetPos (3) / phi theta r minR maxR /
///   c2w (3x3, row-major) / screenW screenH screenDist [/ focalDistance lensRadius]
/// (28 numbers; 30 when the course version writes the lens line). Used: the position, the
/// frame of c2w (columns: right, up, back; the view is -back), vFov (the film keeps its size
/// and the horizontal field follows its aspect, as `-r` does for a .dae), nClip/fClip, and the
/// lens line when present. The orbit state (targetPos, phi, theta, r, minR, maxR), hFov, ar and
/// the screen size are read and checked but not used. Errors name `display_name`, the line and
/// the value: a non-number, 27 or fewer or 29 or 31 and more numbers, fields of view outside
/// (0, 180), clip planes not 0 < nClip < fClip, a c2w without a view direction or with up along
/// it, a negative lens radius or focal distance <= 0.
Status ApplyCs184CameraSettings(const std::string& text, const std::string& display_name,
                                CameraDesc* camera);

/// As ApplyCs184CameraSettings, reading the file at `path` (checked with CheckInputFile).
Status ReadCs184CameraFile(const std::string& path, CameraDesc* camera);

}  // namespace ptlab
