// The limits ptlab enforces on a scene when it is loaded (and on command-line overrides), so
// that no input can overflow the arithmetic or the memory of the renderer.
#pragma once

#include <cstdint>
#include <string>

namespace ptlab {

/// Largest world-space coordinate magnitude a scene may hold. Bounds sums (doubled centroids),
/// extents and SAH costs (two extents times a triangle count) then stay finite in float.
inline constexpr float kMaxWorldCoordinate = 1e12f;

/// Largest radiance (or power) component an emitter may have. Film sums over millions of samples
/// and environment-map sampling tables (sums of all pixels) then stay finite in float.
inline constexpr float kMaxRadiance = 1e20f;

/// Smallest solid angle of a distant disk, in steradians: its sampling pdf 1/solid angle then
/// stays finite (thetaA >= about 3.2e-5 degrees).
inline constexpr double kMinDistantDiskSolidAngle = 1e-12;

/// Largest image side, in pixels.
inline constexpr int64_t kMaxFilmSide = int64_t(1) << 16;
/// Largest image, in pixels (8192 x 8192): the film's accumulators (16 bytes a pixel) and the
/// output image then take about 1.75 GiB.
inline constexpr int64_t kMaxFilmPixels = int64_t(1) << 26;

/// Largest pixel filter radius, in pixels (Nori's filters use 0.5 to 2).
inline constexpr float kMaxFilterRadius = 8.0f;

/// Empty when width x height is a film ptlab can allocate; else what is wrong, with the limit.
inline std::string FilmSizeError(int64_t width, int64_t height) {
  if (width < 1 || height < 1 || width > kMaxFilmSide || height > kMaxFilmSide)
    return "image size " + std::to_string(width) + "x" + std::to_string(height) +
           " is out of range; expected each side in 1.." + std::to_string(kMaxFilmSide);
  if (width * height > kMaxFilmPixels)
    return "image size " + std::to_string(width) + "x" + std::to_string(height) + " has " +
           std::to_string(width * height) + " pixels; expected at most " +
           std::to_string(kMaxFilmPixels) + " (8192x8192)";
  return "";
}

/// Largest sample count a scene file may ask for: the maximum of `ptlab render -s` (a Mitsuba
/// sample_count of 2e9 in a 600-byte file rendered for hours).
inline constexpr int kMaxSampleCount = 1 << 20;

}  // namespace ptlab
