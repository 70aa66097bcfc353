// Camera ray generation: Nori's perspective projection, with an optional thin lens, and
// Mitsuba's orthographic projection.
#pragma once

#include "engine/core/packet8.h"
#include "engine/core/ray.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// Sets the film to width × height pixels. fov_deg (horizontal) is kept, or, when
/// keep_vertical_fov, recomputed so that the vertical field of view stays the same.
void ResizeFilm(CameraDesc* camera, int width, int height);

/// Precomputed per-render camera state.
class Camera {
 public:
  explicit Camera(const CameraDesc& desc);

  /// Primary ray through continuous film position (px, py) in pixels (row 0 at the top),
  /// using lens sample u in [0,1)² when the aperture is open. d is unit length; t_min/t_max are
  /// the near/far clip distances along the ray, as in Nori. An orthographic camera's ray starts
  /// on its near plane (t_min 0) and ends after far_clip - near_clip, as Mitsuba's.
  Ray GenerateRay(float px, float py, const Vec2f& lens_u) const;

  /// GenerateRay for all eight lanes of *out: lane j is GenerateRay(px[j], py[j], lens_u[j]),
  /// bit for bit. A pinhole camera's lanes go through one loop the compiler vectorises (the
  /// same operations in the same order, each lane exact IEEE arithmetic), and so do an
  /// orthographic camera's; a thin lens takes GenerateRay lane by lane.
  void GenerateRay8(const float* px, const float* py, const Vec2f* lens_u, RayPacket8* out) const;

  int width() const { return desc_.width; }
  int height() const { return desc_.height; }

 private:
  CameraDesc desc_;
  // Orthographic: GenerateRay's ray for film position (sx, sy) in [0, 1]².
  Ray OrthographicRay(float sx, float sy) const;
  void OrthographicRay8(const float* px, const float* py, RayPacket8* out) const;

  float tan_half_fov_ = 0;
  float aspect_ = 1;
  Vec3f ortho_dir_;  // orthographic: the world direction of every ray
};

}  // namespace ptlab
