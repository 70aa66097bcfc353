// The camera as a sensor for light tracing: importance We, the density of its rays' directions,
// and sampling the lens point that sees a given scene point (pinhole and thin lens).
#pragma once

#include "engine/core/vec.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// A lens point connected to a scene point: the film position (sx, sy) in pixels (row 0 at the
/// top, as Camera::GenerateRay takes it) where the point appears, the lens point `p` (world),
/// the unit world direction `w` from p to the scene point, its distance, and `importance`:
/// We(p, w) |cos θ| / pdf_lens(p), which for this camera equals DirectionPdf(w) — the density
/// of the camera's ray directions over the whole film, 1 / (A cos³θ), with A the film's area on
/// the plane at distance 1 and θ the angle between w and the optical axis.
struct CameraConnection {
  float sx = 0, sy = 0;
  Vec3f p, w;
  float distance = 0;
  float importance = 0;
};

/// Camera importance for the camera of `desc` (Nori's perspective camera, optional thin lens).
/// The camera's measurement for pixel j is ∫ h_j(s) L(ray(s)) ds over film positions s (pixel
/// units) with h_j the normalised pixel filter: an unbiased light-tracing estimate of it is a
/// splat h_j(s)·C / N with C the path's contribution computed with `importance` and N the
/// number of camera samples per pixel. The camera transform must be a similarity (rotation,
/// translation, uniform scale), as every scene's lookat is.
class CameraImportance {
 public:
  explicit CameraImportance(const CameraDesc& desc);

  /// Solid-angle density with which the camera's ray through a uniformly chosen film position
  /// leaves its lens point in unit world direction w: 1/(A cos³θ) when w lands on the film
  /// (from lens point `p_lens`, world), else 0.
  float DirectionPdf(const Vec3f& p_lens, const Vec3f& w) const;

  /// Samples a lens point (u_lens: the same numbers GenerateRay takes) that sees world point
  /// `ref`. False when ref is behind the camera, off the film or outside the clip range.
  bool SampleConnection(const Vec3f& ref, const Vec2f& u_lens, CameraConnection* out) const;

  /// Density (area measure, camera space = world for rigid transforms) of the lens point:
  /// 1/(π R²), or 1 for a pinhole (a Dirac).
  float LensPdf() const;
  /// The unit world optical axis (camera +z), the "normal" of the lens.
  const Vec3f& axis() const { return axis_; }
  bool pinhole() const { return desc_.aperture_radius <= 0; }

 private:
  // The film position of camera-space direction d (z > 0) from camera-space lens point o;
  // false when off the film.
  bool FilmPosition(const Vec3f& o, const Vec3f& d, float* sx, float* sy) const;

  CameraDesc desc_;
  Transform world_to_camera_;
  Vec3f axis_;
  float tan_half_fov_ = 0, aspect_ = 1, film_area_ = 1;
};

}  // namespace ptlab
