// Emission sampling: where a light subpath starts (a point and a direction leaving an emitter),
// with its densities in area and solid-angle measure, for every emitter kind.
#pragma once

#include <cstdint>

#include "engine/core/vec.h"
#include "engine/scene/refs.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// A sphere around every triangle and analytic sphere of the scene: infinitely distant
/// emitters (environment maps, distant disks, directional lights) start their light subpaths
/// on a disk of this radius facing the light, centred on the sphere's centre, pushed out by one
/// radius. A scene without geometry gets the unit sphere at the origin.
struct SceneSphere {
  Vec3f center;
  float radius = 1.0f;
};
SceneSphere BoundingSphereOf(const Scene& scene);

/// One emitted ray: origin p, unit direction w (leaving the light, the direction light
/// travels), and the light it carries towards w.
/// - area light: p on the mesh (shading normal n, geometric ng), w cosine-distributed around n,
///   `radiance` = L_e(p, w), pdf_pos = 1/area (area), pdf_dir = cos θ/π (solid angle);
/// - point and spot light: p = the light's position, `radiance` = the intensity I(w) (W/sr),
///   pdf_pos = 1 (a Dirac in position: delta_position), pdf_dir uniform over the sphere
///   (point) or over the spot's cone;
/// - projector: p = its position, w through a point uniform on its image window at z = 1,
///   `radiance` = the intensity π·scale·E(uv)/cos³θ (DeltaLightIntensity), pdf_pos = 1,
///   pdf_dir = 1/(4 tan_half_x tan_half_y cos³θ);
/// - environment map and distant disk: w = -(direction sampled from the emitter's own
///   distribution), p on the scene disk (SceneSphere) perpendicular to w, `radiance` = L(-w),
///   pdf_pos = 1/(π r²) (area of the disk), pdf_dir = the emitter's solid-angle density of -w;
/// - directional light: w = its direction (delta_direction, pdf_dir = 1), p on the scene disk,
///   `radiance` = its irradiance E, pdf_pos = 1/(π r²).
/// `infinite` marks the last three kinds (the light vertex is at infinity, its "position" a
/// direction). pdf_pos and pdf_dir exclude the probability of choosing the emitter.
struct EmissionSample {
  Vec3f p, n, ng, w;
  Color3f radiance;
  float pdf_pos = 0.0f, pdf_dir = 0.0f;
  uint32_t prim = 0;  // area light: the triangle row of p
  bool infinite = false, delta_position = false, delta_direction = false;
};

/// Samples emitter e: u_pos picks the point (area lights: the triangle by area, then uniform
/// within it; infinite emitters: the point on the disk), u_dir the direction. False when the
/// emitter sends nothing (black, zero area); *out is then unspecified.
bool SampleEmission(const Scene& scene, const SceneSphere& sphere, EmitterRef e,
                    const Vec2f& u_pos, const Vec2f& u_dir, EmissionSample* out);

/// Densities of SampleEmission for emitter e producing the ray that leaves the emitter at p
/// (area lights, shading normal n) in unit direction w: *pdf_pos (area measure, 1 for delta
/// positions) and *pdf_dir (solid angle; for infinite emitters the density of the direction
/// -w the emitter's distribution samples; 1 for the directional light's fixed direction).
void EmissionPdf(const Scene& scene, const SceneSphere& sphere, EmitterRef e, const Vec3f& n,
                 const Vec3f& w, float* pdf_pos, float* pdf_dir);

/// True for the emitters whose light subpath starts at infinity (environment map, distant disk,
/// directional light).
constexpr bool StartsAtInfinity(EmitterRef e) {
  return e.valid() && (e.tag() == EmitterTag::kEnvironment || e.tag() == EmitterTag::kDistantDisk ||
                       e.tag() == EmitterTag::kDirectional);
}

/// Radiant intensity (W/sr) of a point light, spot light or projector towards unit direction w
/// (leaving it); black for other emitters, outside a spot's cone or a projector's frustum.
Color3f DeltaLightIntensity(const Scene& scene, EmitterRef e, const Vec3f& w);

}  // namespace ptlab
