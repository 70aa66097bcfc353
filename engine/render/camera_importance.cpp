// Camera importance and lens connections (see camera_importance.h).
#include "engine/render/camera_importance.h"

#include <cmath>

#include "engine/sampling/warp.h"

namespace ptlab {

CameraImportance::CameraImportance(const CameraDesc& desc)
    : desc_(desc),
      world_to_camera_(desc.camera_to_world.Inverted()),
      axis_(Normalize(desc.camera_to_world.ApplyVector({0, 0, 1}))),
      tan_half_fov_(std::tan(Radians(desc.fov_deg) * 0.5f)),
      aspect_(float(desc.width) / float(desc.height)) {
  // GenerateRay's film spans x' ∈ [-T, T], y' ∈ [-T/aspect, T/aspect] on the plane z = 1.
  film_area_ = 4.0f * tan_half_fov_ * tan_half_fov_ / aspect_;
}

float CameraImportance::LensPdf() const {
  const float r = desc_.aperture_radius;
  return r > 0 ? 1.0f / (kPi * r * r) : 1.0f;
}

bool CameraImportance::FilmPosition(const Vec3f& o, const Vec3f& d, float* sx, float* sy) const {
  if (!(d.z > 0)) return false;
  // The point of the plane of focus on the ray, back on the plane z = 1 (GenerateRay's p_film):
  // for a pinhole o = 0 and this is d / d.z.
  const float focus = desc_.aperture_radius > 0 ? desc_.focus_distance : 1.0f;
  const Vec3f on_focus = o + d * (focus / d.z);
  const float fx = on_focus.x / focus, fy = on_focus.y / focus;
  // Inverse of x' = (1 - 2 sx/W) T and y' = (1 - 2 sy/H) T / aspect.
  *sx = 0.5f * (1.0f - fx / tan_half_fov_) * float(desc_.width);
  *sy = 0.5f * (1.0f - fy * aspect_ / tan_half_fov_) * float(desc_.height);
  return *sx >= 0 && *sx < float(desc_.width) && *sy >= 0 && *sy < float(desc_.height);
}

float CameraImportance::DirectionPdf(const Vec3f& p_lens, const Vec3f& w) const {
  const Vec3f o = world_to_camera_.ApplyPoint(p_lens);
  const Vec3f d = Normalize(world_to_camera_.ApplyVector(w));
  float sx, sy;
  if (!FilmPosition(o, d, &sx, &sy)) return 0.0f;
  const float c = d.z;
  return 1.0f / (film_area_ * c * c * c);
}

bool CameraImportance::SampleConnection(const Vec3f& ref, const Vec2f& u_lens,
                                        CameraConnection* out) const {
  Vec3f o{0, 0, 0};
  if (desc_.aperture_radius > 0) {
    const Vec2f lens = SampleConcentricDisk(u_lens);
    o = {lens.x * desc_.aperture_radius, lens.y * desc_.aperture_radius, 0.0f};
  }
  const Vec3f q = world_to_camera_.ApplyPoint(ref);
  const Vec3f dq = q - o;
  const float len = Length(dq);
  if (!(len > 0)) return false;
  const Vec3f d = dq / len;
  if (!FilmPosition(o, d, &out->sx, &out->sy)) return false;
  out->p = desc_.camera_to_world.ApplyPoint(o);
  const Vec3f to = ref - out->p;
  out->distance = Length(to);
  if (!(out->distance > 0)) return false;
  out->w = to / out->distance;
  // The clip range of GenerateRay: t ∈ [near, far] / d.z along the unit world direction.
  if (out->distance * d.z < desc_.near_clip || out->distance * d.z > desc_.far_clip) return false;
  const float c = d.z;
  out->importance = 1.0f / (film_area_ * c * c * c);
  return std::isfinite(out->importance);
}

}  // namespace ptlab
