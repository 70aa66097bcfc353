// Camera ray generation: Nori's perspective projection, with an optional thin lens.
#include "engine/render/camera.h"

#include <cmath>

#include "engine/sampling/warp.h"

namespace ptlab {

void ResizeFilm(CameraDesc* camera, int width, int height) {
  if (camera->keep_vertical_fov) {
    // tan(v/2) = tan(h/2) · height / width at the old size; h' from v at the new size.
    const double tan_v = std::tan(double(camera->fov_deg) * kPi / 360.0) * camera->height /
                         camera->width;
    camera->fov_deg = float(2.0 * std::atan(tan_v * width / height) * 180.0 / kPi);
  }
  camera->width = width;
  camera->height = height;
}

Camera::Camera(const CameraDesc& desc)
    : desc_(desc),
      tan_half_fov_(std::tan(Radians(desc.fov_deg) * 0.5f)),
      aspect_(float(desc.width) / float(desc.height)) {}

Ray Camera::GenerateRay(float px, float py, const Vec2f& lens_u) const {
  // Nori maps film (sx, sy) in [0,1]² to the near plane with x' = 1 - 2 sx and
  // y' = (1 - 2 sy) / aspect (in units of tan(fov/2)): camera +x is image left, +y is up.
  const float sx = px / float(desc_.width), sy = py / float(desc_.height);
  const Vec3f p_film{(1.0f - 2.0f * sx) * tan_half_fov_,
                     (1.0f - 2.0f * sy) * tan_half_fov_ / aspect_, 1.0f};
  Vec3f d = Normalize(p_film);
  Vec3f o{0, 0, 0};
  if (desc_.aperture_radius > 0) {
    // Thin lens: the point on the plane of focus (z = focus_distance) stays fixed while the
    // origin moves over the aperture disk, so that radius 0 is exactly the pinhole.
    const Vec2f lens = SampleConcentricDisk(lens_u);
    o = {lens.x * desc_.aperture_radius, lens.y * desc_.aperture_radius, 0.0f};
    const Vec3f focus = p_film * desc_.focus_distance;
    d = Normalize(focus - o);
  }
  const float inv_z = 1.0f / d.z;
  Ray ray;
  ray.o = desc_.camera_to_world.ApplyPoint(o);
  ray.d = Normalize(desc_.camera_to_world.ApplyVector(d));
  // Clip distances are along camera z; the world direction may be scaled by the transform.
  ray.t_min = desc_.near_clip * inv_z;
  ray.t_max = desc_.far_clip * inv_z;
  return ray;
}

}  // namespace ptlab
