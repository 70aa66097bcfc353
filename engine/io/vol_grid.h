// Mitsuba's binary grid-volume files (.vol, version 3, float32): the sdfgrid's signed distances.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/status.h"

namespace ptlab {

/// A grid of nx × ny × nz points with `channels` floats each, x fastest then y, z, channel
/// innermost: values[((k ny + j) nx + i) channels + c].
struct VolGrid {
  uint32_t nx = 0, ny = 0, nz = 0, channels = 0;
  std::vector<float> values;
};

/// Parses a .vol file's bytes: "VOL", version byte 3, int32 encoding 1 (float32), int32 sizes
/// x, y, z, int32 channel count, six float32 of a bounding box (read, unused: ptlab places the
/// grid by the shape's to_world, as Mitsuba's sdfgrid does), then the little-endian float32
/// values. Errors name `display_name` and what was expected; every value must be finite.
StatusOr<VolGrid> ParseVolGrid(const std::string& bytes, const std::string& display_name);
/// Reads and parses the file at `path` (CheckInputFile's rules).
StatusOr<VolGrid> LoadVolGrid(const std::string& path);

}  // namespace ptlab
