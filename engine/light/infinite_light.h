// Dispatch over the infinitely distant emitters (environment maps, distant disks) of a scene.
#pragma once

#include "engine/core/vec.h"
#include "engine/light/distant_disk.h"
#include "engine/light/environment_map.h"
#include "engine/light/environment_sample.h"
#include "engine/scene/refs.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// True for the emitter tags handled here (kEnvironment, kDistantDisk).
constexpr bool IsInfiniteLight(EmitterRef e) {
  return e.valid() && (e.tag() == EmitterTag::kEnvironment || e.tag() == EmitterTag::kDistantDisk);
}

/// Radiance arriving from world direction w (unit, pointing away from the scene) from infinite
/// emitter e; black for any other emitter.
inline Color3f InfiniteLightRadiance(const Scene& scene, EmitterRef e, const Vec3f& w) {
  switch (e.tag()) {
    case EmitterTag::kEnvironment:
      return EnvironmentRadiance(scene.environment_maps, e.index(), w);
    case EmitterTag::kDistantDisk:
      return DistantDiskRadiance(scene.distant_disks, e.index(), w);
    case EmitterTag::kArea:
    case EmitterTag::kPoint:
    case EmitterTag::kDirectional:
    case EmitterTag::kSpot:
    case EmitterTag::kProjector:
      return {};
  }
  return {};  // an invalid ref
}

/// Samples a direction towards infinite emitter e (solid-angle pdf in out->pdf). Returns false
/// when it emits nothing (black), in the measure-zero pole case, or for any other emitter.
inline bool SampleInfiniteLight(const Scene& scene, EmitterRef e, const Vec2f& u,
                                EnvironmentSample* out) {
  switch (e.tag()) {
    case EmitterTag::kEnvironment:
      return SampleEnvironment(scene.environment_maps, e.index(), u, out);
    case EmitterTag::kDistantDisk:
      return SampleDistantDisk(scene.distant_disks, e.index(), u, out);
    case EmitterTag::kArea:
    case EmitterTag::kPoint:
    case EmitterTag::kDirectional:
    case EmitterTag::kSpot:
    case EmitterTag::kProjector:
      return false;
  }
  return false;  // an invalid ref
}

/// Solid-angle density with which SampleInfiniteLight(e) produces world direction w (unit);
/// 0 for any other emitter. For MIS with BSDF sampling of escaping rays.
inline float InfiniteLightPdf(const Scene& scene, EmitterRef e, const Vec3f& w) {
  switch (e.tag()) {
    case EmitterTag::kEnvironment:
      return EnvironmentPdf(scene.environment_maps, e.index(), w);
    case EmitterTag::kDistantDisk:
      return DistantDiskPdf(scene.distant_disks, e.index(), w);
    case EmitterTag::kArea:
    case EmitterTag::kPoint:
    case EmitterTag::kDirectional:
    case EmitterTag::kSpot:
    case EmitterTag::kProjector:
      return 0.0f;
  }
  return 0.0f;  // an invalid ref
}

/// InfiniteLightRadiance (into *radiance) and InfiniteLightPdf of e and w together, bit for bit
/// (an environment map maps w to (u, v) once for both).
inline float InfiniteLightRadianceAndPdf(const Scene& scene, EmitterRef e, const Vec3f& w,
                                         Color3f* radiance) {
  if (e.valid() && e.tag() == EmitterTag::kEnvironment)
    return EnvironmentRadianceAndPdf(scene.environment_maps, e.index(), w, radiance);
  *radiance = InfiniteLightRadiance(scene, e, w);
  return InfiniteLightPdf(scene, e, w);
}

/// Radiance seen by a ray leaving the scene along w (unit): the sum over every environment map
/// and distant disk. Black (and free) when the scene has none.
inline Color3f EscapedRadiance(const Scene& scene, const Vec3f& w) {
  Color3f sum;
  for (uint32_t i = 0; i < scene.environment_maps.size(); ++i)
    sum += EnvironmentRadiance(scene.environment_maps, i, w);
  for (uint32_t i = 0; i < scene.distant_disks.size(); ++i)
    sum += DistantDiskRadiance(scene.distant_disks, i, w);
  return sum;
}

}  // namespace ptlab
