// Camera ray generation: Nori's perspective projection, with an optional thin lens, and
// Mitsuba's orthographic projection.
#include "engine/render/camera.h"

#include <cmath>
#include <cstring>

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
      aspect_(float(desc.width) / float(desc.height)),
      ortho_dir_(Normalize(desc.camera_to_world.ApplyVector({0, 0, 1}))) {}

Ray Camera::OrthographicRay(float sx, float sy) const {
  // Mitsuba's orthographic_projection: film (sx, sy) to (1 - 2 sx, (1 - 2 sy) / aspect) on
  // the plane z = near_clip (camera +x is image left, as the perspective camera's).
  Ray ray;
  ray.o = desc_.camera_to_world.ApplyPoint(
      {1.0f - 2.0f * sx, (1.0f - 2.0f * sy) / aspect_, desc_.near_clip});
  ray.d = ortho_dir_;
  ray.t_min = 0.0f;
  ray.t_max = desc_.far_clip - desc_.near_clip;
  return ray;
}

void Camera::OrthographicRay8(const float* px, const float* py, RayPacket8* out) const {
  // OrthographicRay with ApplyPoint written out (the same operations in the same order).
  constexpr int kLanes = int(kPacketWidth);
  const auto& m = desc_.camera_to_world.matrix().m;
  const float a00 = m[0][0], a01 = m[0][1], a02 = m[0][2], a03 = m[0][3], a10 = m[1][0],
              a11 = m[1][1], a12 = m[1][2], a13 = m[1][3], a20 = m[2][0], a21 = m[2][1],
              a22 = m[2][2], a23 = m[2][3], a30 = m[3][0], a31 = m[3][1], a32 = m[3][2],
              a33 = m[3][3];
  const float width = float(desc_.width), height = float(desc_.height), aspect = aspect_;
  const float z = desc_.near_clip, t_max = desc_.far_clip - desc_.near_clip;
  float in_x[kPacketWidth], in_y[kPacketWidth];
  float o_x[kPacketWidth], o_y[kPacketWidth], o_z[kPacketWidth];
  std::memcpy(in_x, px, sizeof(in_x));
  std::memcpy(in_y, py, sizeof(in_y));
  for (int j = 0; j < kLanes; ++j) {
    const float sx = in_x[j] / width, sy = in_y[j] / height;
    const float x = 1.0f - 2.0f * sx, y = (1.0f - 2.0f * sy) / aspect;
    const float wx = a00 * x + a01 * y + a02 * z + a03;
    const float wy = a10 * x + a11 * y + a12 * z + a13;
    const float wz = a20 * x + a21 * y + a22 * z + a23;
    const float w = a30 * x + a31 * y + a32 * z + a33;
    const bool affine = w == 1.0f;
    o_x[j] = affine ? wx : wx / w;
    o_y[j] = affine ? wy : wy / w;
    o_z[j] = affine ? wz : wz / w;
  }
  std::memcpy(out->org_x, o_x, sizeof(o_x));
  std::memcpy(out->org_y, o_y, sizeof(o_y));
  std::memcpy(out->org_z, o_z, sizeof(o_z));
  for (int j = 0; j < kLanes; ++j) {
    out->dir_x[j] = ortho_dir_.x, out->dir_y[j] = ortho_dir_.y, out->dir_z[j] = ortho_dir_.z;
    out->t_min[j] = 0.0f, out->t_max[j] = t_max;
  }
}

Ray Camera::GenerateRay(float px, float py, const Vec2f& lens_u) const {
  // Nori maps film (sx, sy) in [0,1]² to the near plane with x' = 1 - 2 sx and
  // y' = (1 - 2 sy) / aspect (in units of tan(fov/2)): camera +x is image left, +y is up.
  const float sx = px / float(desc_.width), sy = py / float(desc_.height);
  if (desc_.projection == CameraDesc::Projection::kOrthographic) return OrthographicRay(sx, sy);
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

void Camera::GenerateRay8(const float* px, const float* py, const Vec2f* lens_u,
                          RayPacket8* out) const {
  constexpr int kLanes = int(kPacketWidth);
  if (desc_.projection == CameraDesc::Projection::kOrthographic) {
    OrthographicRay8(px, py, out);
    return;
  }
  if (desc_.aperture_radius > 0) {
    for (int j = 0; j < kLanes; ++j) SetLaneRay(out, j, GenerateRay(px[j], py[j], lens_u[j]));
    return;
  }
  // GenerateRay's pinhole branch with the transform written out: the origin is the image of
  // (0, 0, 0), the same for every lane; the direction's operations are GenerateRay's, in order.
  // Inputs, matrix and results are locals, so that no store may alias a load.
  const Vec3f o = desc_.camera_to_world.ApplyPoint(Vec3f{0, 0, 0});
  const auto& m = desc_.camera_to_world.matrix().m;
  const float a00 = m[0][0], a01 = m[0][1], a02 = m[0][2], a10 = m[1][0], a11 = m[1][1],
              a12 = m[1][2], a20 = m[2][0], a21 = m[2][1], a22 = m[2][2];
  const float width = float(desc_.width), height = float(desc_.height);
  const float tan_half_fov = tan_half_fov_, aspect = aspect_;
  const float near_clip = desc_.near_clip, far_clip = desc_.far_clip;
  float in_x[kPacketWidth], in_y[kPacketWidth];
  float d_x[kPacketWidth], d_y[kPacketWidth], d_z[kPacketWidth], t0[kPacketWidth],
      t1[kPacketWidth];
  std::memcpy(in_x, px, sizeof(in_x));
  std::memcpy(in_y, py, sizeof(in_y));
  for (int j = 0; j < kLanes; ++j) {
    const float sx = in_x[j] / width, sy = in_y[j] / height;
    const float fx = (1.0f - 2.0f * sx) * tan_half_fov;
    const float fy = (1.0f - 2.0f * sy) * tan_half_fov / aspect;
    const float fz = 1.0f;
    const float inv_len = 1.0f / std::sqrt(fx * fx + fy * fy + fz * fz);  // Normalize
    const float dx = fx * inv_len, dy = fy * inv_len, dz = fz * inv_len;
    const float inv_z = 1.0f / dz;
    const float wx = a00 * dx + a01 * dy + a02 * dz;  // ApplyVector
    const float wy = a10 * dx + a11 * dy + a12 * dz;
    const float wz = a20 * dx + a21 * dy + a22 * dz;
    const float inv_wlen = 1.0f / std::sqrt(wx * wx + wy * wy + wz * wz);
    d_x[j] = wx * inv_wlen, d_y[j] = wy * inv_wlen, d_z[j] = wz * inv_wlen;
    t0[j] = near_clip * inv_z;
    t1[j] = far_clip * inv_z;
  }
  for (int j = 0; j < kLanes; ++j) out->org_x[j] = o.x, out->org_y[j] = o.y, out->org_z[j] = o.z;
  std::memcpy(out->dir_x, d_x, sizeof(d_x));
  std::memcpy(out->dir_y, d_y, sizeof(d_y));
  std::memcpy(out->dir_z, d_z, sizeof(d_z));
  std::memcpy(out->t_min, t0, sizeof(t0));
  std::memcpy(out->t_max, t1, sizeof(t1));
}

}  // namespace ptlab
