// Emitter selection by power.
#include "engine/light/light_selection.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/sampling/guide_table.h"
#include "engine/scene/world_bounds.h"

namespace ptlab {
namespace {

// Radius of a sphere around the scene's world geometry (0 without any; WorldBounds): the disk an
// infinite or directional emitter shines on, pbrt's measure of such a light's power.
double SceneRadius(const Scene& scene) {
  Vec3f lo, hi;
  if (!WorldBounds(scene, &lo, &hi)) return 0.0;
  return 0.5 * double(Length(hi - lo));
}

constexpr double kPiD = 3.14159265358979323846;

}  // namespace

void BuildEmitterSelection(Scene* scene) {
  EmitterSelectionTable& t = scene->emitter_selection;
  const size_t n = scene->emitters.size();
  t = EmitterSelectionTable{};
  t.slot_area.assign(scene->area_lights.size(), 0);
  t.slot_environment.assign(scene->environment_maps.size(), 0);
  t.slot_disk.assign(scene->distant_disks.size(), 0);
  t.slot_point.assign(scene->point_lights.size(), 0);
  t.slot_directional.assign(scene->directional_lights.size(), 0);
  t.slot_spot.assign(scene->spot_lights.size(), 0);
  t.slot_projector.assign(scene->projectors.size(), 0);
  if (n == 0) return;
  const double radius = SceneRadius(*scene);
  // An infinite or directional emitter in a scene without geometry lights nothing; a unit
  // disk keeps it selectable.
  const double disk_area = kPiD * std::max(radius * radius, 1.0);
  t.power.resize(n);
  double total = 0;
  for (size_t k = 0; k < n; ++k) {
    const EmitterRef e = scene->emitters[k];
    const uint32_t i = e.index();
    double power = 0;
    switch (e.tag()) {
      case EmitterTag::kArea:
        t.slot_area[i] = uint32_t(k);
        power = kPiD * double(scene->area_lights.area[i]) *
                double(Luminance(scene->area_lights.radiance[i]));
        break;
      case EmitterTag::kEnvironment:
        t.slot_environment[i] = uint32_t(k);
        power = disk_area * double(scene->environment_maps.luminance_integral[i]);
        break;
      case EmitterTag::kDistantDisk:
        t.slot_disk[i] = uint32_t(k);
        power = disk_area * double(scene->distant_disks.solid_angle[i]) *
                double(Luminance(scene->distant_disks.radiance[i]));
        break;
      case EmitterTag::kPoint:
        t.slot_point[i] = uint32_t(k);
        power = double(Luminance(scene->point_lights.power[i]));
        break;
      case EmitterTag::kDirectional:
        // pbrt-v4's DistantLight::Phi: the irradiance over the disk the scene's bounding sphere
        // casts.
        t.slot_directional[i] = uint32_t(k);
        power = disk_area * double(Luminance(scene->directional_lights.radiance[i]));
        break;
      case EmitterTag::kSpot: {
        t.slot_spot[i] = uint32_t(k);
        const SpotLightTable& s = scene->spot_lights;
        if (s.inv_transition[i] > 0) {
          // Mitsuba's spot (exponent 0): ∫ ramp dω = 2π [(1 - cos β) + ∫_β^γ (γ - θ)/(γ - β)
          // sin θ dθ], the second term (w cos β + sin β - sin γ) / w with w = γ - β.
          const double gamma = double(s.cutoff[i]);
          const double w = 1.0 / double(s.inv_transition[i]), beta = gamma - w;
          power = 2.0 * kPiD *
                  ((1.0 - std::cos(beta)) +
                   (w * std::cos(beta) + std::sin(beta) - std::sin(gamma)) / w) *
                  double(Luminance(s.intensity[i]));
          break;
        }
        // ∫ cos^e θ dω over the cone cos θ > c: 2π (1 - c^(e+1)) / (e + 1).
        const double c = std::max(double(s.cos_half_angle[i]), 0.0);
        const double e1 = double(s.exponent[i]) + 1.0;
        power = 2.0 * kPiD * (1.0 - std::pow(c, e1)) / e1 * double(Luminance(s.intensity[i]));
        break;
      }
      case EmitterTag::kProjector: {
        // The constant image's irradiance π·scale·E on the plane z = 1 over the frustum's
        // window there, (2 tan_half_x)(2 tan_half_y).
        t.slot_projector[i] = uint32_t(k);
        const ProjectorTable& p = scene->projectors;
        power = kPiD * double(p.scale[i]) * double(Luminance(p.irradiance[i])) * 4.0 *
                double(p.tan_half_x[i]) * double(p.tan_half_y[i]);
        break;
      }
    }
    power = std::isfinite(power) ? std::max(power, 0.0) : 0.0;
    t.power[k] = float(power);
    total += power;
  }
  t.pmf.resize(n);
  t.cdf.resize(n);
  double running = 0;
  for (size_t k = 0; k < n; ++k) {
    const double p = total > 0 ? double(t.power[k]) / total : 1.0 / double(n);
    t.pmf[k] = float(p);
    running += p;
    t.cdf[k] = float(std::min(running, 1.0));
  }
  // The last emitter with a non-zero probability ends the CDF at exactly 1.
  for (size_t k = n; k-- > 0;) {
    t.cdf[k] = 1.0f;
    if (t.pmf[k] > 0) break;
  }
  t.guide.resize(n + 1);
  BuildGuideTable(t.cdf.data(), uint32_t(n), t.guide.data());
}

}  // namespace ptlab
