// The light image of light tracing: splats at arbitrary film positions, each spread with the
// pixel filter normalised per pixel, added to the camera's film divided by the samples per pixel.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/core/vec.h"
#include "engine/render/film.h"
#include "engine/render/filter.h"

namespace ptlab {

/// Sums of light-tracing contributions per pixel (r, g, b), image-sized. A contribution C at
/// film position s adds C · f(s - c_j) / Z_j to pixel j (centre c_j), where f is the separable
/// pixel filter and Z_j its integral over the film: the expectation of the camera's weighted
/// mean Σ f L / Σ f for samples spread uniformly over the film, so the light image and the
/// camera image are filtered alike, also at the border. The pixel's light value is its sum
/// divided by the samples per pixel (one light subpath per camera sample).
class LightFilm {
 public:
  LightFilm(const PixelFilter& filter, int width, int height);

  /// Adds contribution `value` at film position (sx, sy) (pixels; off-film positions add
  /// nothing).
  void Splat(float sx, float sy, const Color3f& value);
  /// Adds every sum of other (same size) into this film.
  void Add(const LightFilm& other);
  void Clear();

  /// A copy of `camera` (the whole image) whose pixels resolve to the camera's value plus this
  /// film's sum / spp: Σ w·L + sum · Σ w / spp over Σ w, so that FilmBlock::Resolve and
  /// everything reading the film see the combined image. Pixels without camera weight stay.
  void ComposeInto(const FilmBlock& camera, uint32_t spp, FilmBlock* out) const;

  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<float>& sums() const { return sum_; }

 private:
  const PixelFilter* filter_;
  int width_, height_;
  std::vector<float> inv_zx_, inv_zy_;  // 1 / the filter's integral over the film, per column/row
  std::vector<float> sum_;              // r, g, b per pixel, rows
};

}  // namespace ptlab
