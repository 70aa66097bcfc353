// Emitter components: area lights on meshes, environment maps, distant disks, delta lights and
// projectors.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/core/aligned.h"
#include "engine/core/frame.h"
#include "engine/core/vec.h"
#include "engine/scene/refs.h"
#include "engine/scene/texture_tables.h"

namespace ptlab {

/// Diffuse area lights, one-sided (they emit on the side of the shading normal, as in Nori).
/// Sampling is uniform by area over the mesh's triangles: per-light triangle CDFs are stored
/// back to back in `triangle_cdf`, light i owning [cdf_offset[i], cdf_offset[i] + triangle_count).
struct AreaLightTable {
  std::vector<Color3f> radiance;
  std::vector<uint32_t> mesh;            // row in MeshTable
  std::vector<float> area;               // total surface area (world units²)
  std::vector<uint32_t> cdf_offset;
  AlignedVector<float> triangle_cdf;     // normalised, last entry of each light = 1
  /// Guide tables of the CDFs (engine/sampling/guide_table.h), triangle_count + 1 entries per
  /// light from guide_offset[i]: O(1) expected triangle choice, same result as the full search.
  std::vector<uint32_t> guide_offset;
  AlignedVector<uint32_t> triangle_guide;
  /// Mitsuba's textured `radiance` (AreaLightRadianceAt, engine/light/area_light.h): empty
  /// when no area light of the scene is textured, else one entry per row (kNoTexture: the
  /// constant `radiance`). A textured row emits its texture at the point's surface uv; its
  /// `radiance` holds the texture's mean (the selection power). Points are still sampled
  /// uniformly by area.
  std::vector<uint32_t> texture;

  size_t size() const { return radiance.size(); }
  bool Textured(size_t i) const { return !texture.empty() && texture[i] != kNoTexture; }
};

/// How an environment map's emitter samples directions (XML string `sampling`).
enum class EnvironmentSampling : uint8_t {
  kUniform,     // uniform over the sphere, pdf 1/(4π)
  kImportance,  // piecewise constant over the pixels, ∝ luminance × sinθ (the default)
};

/// Where an environment map's pixel rows sit in θ (its columns always sit at u = (i + ½)/W).
enum class EnvironmentRows : uint8_t {
  kCentred,  // row j at v = (j + ½)/H, the centre of its band (ptlab's own, CS184's, Nori's)
  kAtPoles,  // row j at v = j/(H − 1): row 0 on the north pole, row H − 1 on the south pole
             // (Mitsuba 3's envmap: its θ texture coordinate aligns the corners)
};

/// Environment maps (Mitsuba `envmap`), one row per emitter; built by AddEnvironmentMap
/// (engine/light/environment_map.h), which documents the lat-long convention. Per-row columns
/// index into pooled columns: pixels (premultiplied by `scale`, row-major, row 0 = up) at
/// pixel_offset, as texels of four floats (r, g, b, 0: a bilinear lookup's 2 × 2 pixels then
/// share two cache lines instead of six); the importance distribution (engine/sampling/distribution2d.h layout) at
/// marginal_offset (nv + 1 floats) and conditional_offset (nv × (width + 1) floats, nv =
/// EnvironmentCellRows: height for kCentred rows, max(height − 1, 1) for kAtPoles rows),
/// each CDF with its guide table beside it at the same offsets (engine/sampling/guide_table.h:
/// n + 1 entries for a CDF of n bins). Uniform rows store no distribution. A scene without
/// environment maps holds empty vectors.
/// Floats per texel of EnvironmentMapTable::texels: r, g, b and a zero pad.
inline constexpr size_t kEnvironmentTexel = 4;

struct EnvironmentMapTable {
  std::vector<int32_t> width, height;
  std::vector<uint32_t> pixel_offset, marginal_offset, conditional_offset;
  std::vector<EnvironmentSampling> sampling;
  std::vector<EnvironmentRows> rows;
  std::vector<Frame> to_world;             // rotation: local (s, t, n) axes in world space
  std::vector<float> luminance_integral;   // ≈ ∫ luminance dω (sr); 0 = black: never sampled
  AlignedVector<float> texels;             // pooled pixels, kEnvironmentTexel floats each
  AlignedVector<float> marginal_cdf, conditional_cdf;  // pooled importance CDFs
  AlignedVector<uint32_t> marginal_guide, conditional_guide;  // their guide tables

  size_t size() const { return width.size(); }
};

/// Nori (ETH) `distantdisk` emitters: constant radiance inside a cone of half-angle thetaA
/// around the world axis to_world.n, zero outside; thetaA = 180° is a constant environment.
struct DistantDiskTable {
  std::vector<Color3f> radiance;
  // ω (unit) is inside iff |ω - axis|² <= max_chord2 = 2 (1 - cos thetaA), +inf for 180°: the
  // chord form stays accurate in float for narrow cones, where cos ω·axis ≈ 1 does not.
  std::vector<float> max_chord2;
  std::vector<float> solid_angle;  // 2π (1 - cos thetaA), sr, computed in double
  std::vector<Frame> to_world;     // rotation: the cone axis is to_world.n

  size_t size() const { return radiance.size(); }
};

/// Point lights (Nori's `point`): a position and the power emitted in all directions (W per
/// channel); radiant intensity power / 4π, so the irradiance at distance r is power / (4π r²).
/// Delta lights: reached by emitter sampling only.
struct PointLightTable {
  std::vector<Vec3f> position;
  std::vector<Color3f> power;

  size_t size() const { return position.size(); }
};

/// Directional lights (COLLADA `<directional>`, pbrt's `distant`): parallel light travelling
/// along `direction` (world, unit). `radiance` is what CS184 and pbrt call it: the irradiance
/// (W/m² per channel) on a surface facing the light, so a Lambertian surface of albedo a lit
/// head-on sends out a·radiance/π. Delta lights: reached by emitter sampling only.
struct DirectionalLightTable {
  std::vector<Vec3f> direction;
  std::vector<Color3f> radiance;

  size_t size() const { return direction.size(); }
};

/// Spot lights (COLLADA `<spot>`, Mitsuba `spot`): a point at `position` sending radiant
/// intensity intensity · cos(θ)^exponent · ramp(θ) (W/sr per channel) at angle θ from `axis`
/// (world, unit) while cos θ > cos_half_angle, and nothing outside; the irradiance falls off as
/// 1/r² as for point lights. ramp(θ) is Mitsuba's linear falloff: 1 while cos θ >= cos_beam,
/// else (cutoff - θ) · inv_transition (cutoff = the cone's half-angle in radians,
/// inv_transition = 1 / (cutoff - beam width)). COLLADA rows have exponent ≥ 0 and no ramp
/// (cos_beam = cos_half_angle); Mitsuba rows have exponent 0. Delta lights: reached by emitter
/// sampling only.
struct SpotLightTable {
  std::vector<Vec3f> position, axis;
  std::vector<Color3f> intensity;
  std::vector<float> cos_half_angle, exponent;
  std::vector<float> cos_beam, cutoff, inv_transition;
  /// Mitsuba's projected `texture` (SpotIntensity, engine/light/spot_light.h): empty when no
  /// spot of the scene has one, else one entry per row (kNoTexture: none). A textured row's
  /// intensity is multiplied by the texture at uv = 0.5 + 0.5 (x, y) / (z tan cutoff), (x, y,
  /// z) the direction in the light's frame `texture_frame` (rotation; n = axis).
  std::vector<uint32_t> texture;
  std::vector<Frame> texture_frame;

  size_t size() const { return position.size(); }
};

/// Projectors (Mitsuba `projector`): a pinhole at `position` projecting an image through the
/// frustum |x/z| <= tan_half_x, |y/z| <= tan_half_y of its local frame `to_world` (rotation;
/// it looks along to_world.n). The image is the irradiance on the virtual image plane z = 1 at
/// image coordinates (u, v) = (0.5 - x/(2 z tan_half_x), 0.5 - y/(2 z tan_half_y)), row v = 0
/// at the top as a camera's film (ProjectorIrradiance, engine/light/projector.h, looks it up);
/// `scale` multiplies it. Delta lights: reached by emitter sampling only.
struct ProjectorTable {
  std::vector<Vec3f> position;
  std::vector<Frame> to_world;
  std::vector<float> tan_half_x, tan_half_y, scale;
  std::vector<Color3f> irradiance;  // the constant image; a textured row: the image's mean
  /// The image as a texture row (ProjectorIrradiance): empty when no projector of the scene
  /// has a textured image, else one entry per row (kNoTexture: the constant `irradiance`).
  std::vector<uint32_t> texture;

  size_t size() const { return position.size(); }
};

/// Selection of an emitter by power, over Scene::emitters in order: pmf and CDF (with a guide
/// table) of each emitter's power (luminance of its emitted flux; infinite and directional
/// emitters as seen by a disk of the scene's bounding-sphere radius, pbrt's convention), and for
/// each emitter table row its position in Scene::emitters. Empty when the scene has no emitters.
struct EmitterSelectionTable {
  std::vector<float> power;        // luminance flux (W) per emitter, for messages and tests
  std::vector<float> pmf;          // selection probability per emitter (sums to 1)
  AlignedVector<float> cdf;        // normalised, last entry = 1
  AlignedVector<uint32_t> guide;   // emitters.size() + 1 entries
  std::vector<uint32_t> slot_area, slot_environment, slot_disk, slot_point, slot_directional,
      slot_spot;
  std::vector<uint32_t> slot_projector;

  size_t size() const { return pmf.size(); }
};

}  // namespace ptlab
