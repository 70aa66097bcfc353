// Distant disk emitter: a cone of constant radiance, sampled uniformly over its solid angle.
#include "engine/light/distant_disk.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/scene/scene_limits.h"

namespace ptlab {
namespace {

bool InCone(const DistantDiskTable& t, uint32_t row, const Vec3f& w) {
  const Vec3f d = w - t.to_world[row].n;
  return Dot(d, d) <= t.max_chord2[row];
}

}  // namespace

StatusOr<uint32_t> AddDistantDisk(const Color3f& radiance, float theta_a_deg, const Frame& to_world,
                                  const std::string& name, DistantDiskTable* table) {
  if (!(radiance.r >= 0 && radiance.g >= 0 && radiance.b >= 0 && radiance.r <= kMaxRadiance &&
        radiance.g <= kMaxRadiance && radiance.b <= kMaxRadiance))
    return Status::Error(name + ": distant disk radiance must have components in [0, 1e20]");
  if (!(theta_a_deg > 0.0f && theta_a_deg <= 180.0f)) {
    char buffer[48];
    std::snprintf(buffer, sizeof(buffer), "%g", double(theta_a_deg));
    return Status::Error(name + ": thetaA = " + buffer +
                         " is out of range; expected a half-angle in degrees in (0, 180]");
  }
  const double theta = double(theta_a_deg) * (3.14159265358979323846 / 180.0);
  // 1 - cos θ = 2 sin²(θ/2), without cancellation for small cones.
  const double one_minus_cos = 2.0 * std::sin(theta / 2) * std::sin(theta / 2);
  if (!(2.0 * 3.14159265358979323846 * one_minus_cos >= kMinDistantDiskSolidAngle)) {
    char buffer[48];
    std::snprintf(buffer, sizeof(buffer), "%g", double(theta_a_deg));
    return Status::Error(name + ": thetaA = " + buffer +
                         " degrees gives a cone too small to sample; expected a solid angle >= " +
                         "1e-12 sr (thetaA >= 3.3e-5 degrees)");
  }
  table->radiance.push_back(radiance);
  table->max_chord2.push_back(theta_a_deg == 180.0f ? INFINITY : float(2.0 * one_minus_cos));
  table->solid_angle.push_back(float(2.0 * 3.14159265358979323846 * one_minus_cos));
  table->to_world.push_back(to_world);
  return uint32_t(table->size() - 1);
}

Color3f DistantDiskRadiance(const DistantDiskTable& t, uint32_t row, const Vec3f& w_world) {
  return InCone(t, row, w_world) ? t.radiance[row] : Color3f{};
}

bool SampleDistantDisk(const DistantDiskTable& t, uint32_t row, const Vec2f& u,
                       EnvironmentSample* out) {
  if (IsBlack(t.radiance[row])) return false;
  // Uniform in cosθ over [cos thetaA, 1]: 1 - cosθ = s = u (1 - cos thetaA), sinθ = sqrt(s (2 - s))
  // (accurate for narrow cones, unlike sqrt(1 - cos²θ)).
  const float s = std::min(u.x, 1.0f) * (t.solid_angle[row] * kInv2Pi);
  const float r = std::sqrt(std::max(0.0f, s * (2.0f - s))), phi = 2 * kPi * u.y;
  out->wi = t.to_world[row].ToWorld({r * std::cos(phi), r * std::sin(phi), 1.0f - s});
  out->radiance = t.radiance[row];
  out->pdf = 1.0f / t.solid_angle[row];
  return true;
}

float DistantDiskPdf(const DistantDiskTable& t, uint32_t row, const Vec3f& w_world) {
  if (IsBlack(t.radiance[row])) return 0.0f;
  return InCone(t, row, w_world) ? 1.0f / t.solid_angle[row] : 0.0f;
}

}  // namespace ptlab
