// Sanity of a render's setup (see setup_checks.h).
#include "engine/render/setup_checks.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "engine/core/parse_number.h"
#include "engine/scene/scene_limits.h"

namespace ptlab {
namespace {

std::string Num(double v) { return FormatLimit(v); }

bool FiniteWithin(const Vec3f& p, double limit) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) &&
         std::fabs(p.x) <= limit && std::fabs(p.y) <= limit && std::fabs(p.z) <= limit;
}

// Built by appending: GCC 12 warns (-Wrestrict, falsely) on "literal" + std::string&&.
std::string Point(const Vec3f& p) {
  std::string s = "(";
  s += Num(p.x);
  s += ", ";
  s += Num(p.y);
  s += ", ";
  s += Num(p.z);
  s += ")";
  return s;
}

Status CheckCamera(const CameraDesc& c) {
  const std::string size = FilmSizeError(c.width, c.height);
  if (!size.empty()) return Status::Error("camera: " + size);
  const double h = double(c.fov_deg);
  const double aspect = double(c.width) / double(c.height);
  // The vertical field of view follows from the horizontal one and the film's aspect.
  const double v = 2.0 * std::atan(std::tan(h * std::numbers::pi / 360.0) / aspect) * 180.0 /
                   std::numbers::pi;
  const std::string range = FormatRange(kMinFieldOfViewDeg, kMaxFieldOfViewDeg) + " degrees";
  if (!(h >= kMinFieldOfViewDeg && h <= kMaxFieldOfViewDeg))
    return Status::Error("camera: horizontal field of view " + Num(h) + " (film " +
                         std::to_string(c.width) + "x" + std::to_string(c.height) +
                         ") is out of range " + range);
  if (!(v >= kMinFieldOfViewDeg && v <= kMaxFieldOfViewDeg))
    return Status::Error("camera: vertical field of view " + Num(v) + " (from the horizontal " +
                         Num(h) + " and the film's aspect " + Num(aspect) + ", " +
                         std::to_string(c.width) + "x" + std::to_string(c.height) +
                         ") is out of range " + range);
  if (!(std::isfinite(c.near_clip) && c.near_clip > 0 && std::isfinite(c.far_clip) &&
        c.far_clip > c.near_clip))
    return Status::Error("camera: clip planes " + Num(c.near_clip) + ", " + Num(c.far_clip) +
                         " expected finite with 0 < near < far");
  if (!(c.aperture_radius >= 0 && c.aperture_radius <= 1e6f))
    return Status::Error("camera: lens radius " + Num(c.aperture_radius) +
                         " is out of range [0, 1e6]");
  if (c.aperture_radius > 0 &&
      !(c.focus_distance >= 1e-6f && c.focus_distance <= kMaxWorldCoordinate))
    return Status::Error("camera: focus distance " + Num(c.focus_distance) +
                         " is out of range [1e-6, " + Num(kMaxWorldCoordinate) +
                         "] (the scene's coordinates); with a lens radius of " +
                         Num(c.aperture_radius) + " nothing would be in focus");
  const Matrix4& m = c.camera_to_world.matrix();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (!std::isfinite(m.m[i][j]))
        return Status::Error("camera: its world transform holds a non-finite number (row " +
                             std::to_string(i) + ", column " + std::to_string(j) + ")");
  const Vec3f position{m.m[0][3], m.m[1][3], m.m[2][3]};
  if (!FiniteWithin(position, kMaxWorldCoordinate))
    return Status::Error("camera: position " + Point(position) +
                         " is outside the scene's coordinates [-" + Num(kMaxWorldCoordinate) +
                         ", " + Num(kMaxWorldCoordinate) + "]");
  return Status::Ok();
}

}  // namespace

Status CheckRenderSetup(const Scene& scene) {
  PTLAB_RETURN_IF_ERROR(CheckCamera(scene.camera));
  const std::string bounds =
      " is outside the scene's coordinates [-" + Num(kMaxWorldCoordinate) + ", " +
      Num(kMaxWorldCoordinate) + "] or not finite";
  for (size_t i = 0; i < scene.point_lights.size(); ++i)
    if (!FiniteWithin(scene.point_lights.position[i], kMaxWorldCoordinate))
      return Status::Error("point light " + std::to_string(i) + ": position " +
                           Point(scene.point_lights.position[i]) + bounds);
  for (size_t i = 0; i < scene.spot_lights.size(); ++i) {
    if (!FiniteWithin(scene.spot_lights.position[i], kMaxWorldCoordinate))
      return Status::Error("spot light " + std::to_string(i) + ": position " +
                           Point(scene.spot_lights.position[i]) + bounds);
    const Vec3f& a = scene.spot_lights.axis[i];
    if (!(std::fabs(Length(a) - 1.0f) < 1e-3f))
      return Status::Error("spot light " + std::to_string(i) + ": axis " + Point(a) +
                           " is not a unit vector (a degenerate or non-finite transform)");
  }
  for (size_t i = 0; i < scene.projectors.size(); ++i)
    if (!FiniteWithin(scene.projectors.position[i], kMaxWorldCoordinate))
      return Status::Error("projector " + std::to_string(i) + ": position " +
                           Point(scene.projectors.position[i]) + bounds);
  for (size_t i = 0; i < scene.directional_lights.size(); ++i) {
    const Vec3f& d = scene.directional_lights.direction[i];
    if (!(std::fabs(Length(d) - 1.0f) < 1e-3f))
      return Status::Error("directional light " + std::to_string(i) + ": direction " + Point(d) +
                           " is not a unit vector (a degenerate or non-finite transform)");
  }
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const Vec3f c = scene.spheres.Center(i);
    const float r = scene.spheres.radius[i];
    if (!FiniteWithin(c, kMaxWorldCoordinate))
      return Status::Error("sphere " + std::to_string(i) + ": centre " + Point(c) + bounds);
    if (!(r > 0 && r <= kMaxWorldCoordinate))
      return Status::Error("sphere " + std::to_string(i) + ": radius " + Num(r) +
                           " is out of range (0, " + Num(kMaxWorldCoordinate) + "]");
  }
  return Status::Ok();
}

}  // namespace ptlab
