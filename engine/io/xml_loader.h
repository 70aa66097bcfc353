// Scene files: Nori's XML format (plus Mitsuba-style procedural shapes) loaded into a Scene.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/status.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// How `<lookat>` builds the camera frame.
enum class LookatConvention : uint8_t {
  /// Current Nori (and the epfl references): left = normalize(up × dir).
  kNori,
  /// The 2015-16 ETH Nori line that rendered the eth2015 references: left = dir × up and
  /// newUp = left × dir, neither normalised. The image is the left-right mirror of kNori's,
  /// and zoomed by 1 / |up × dir| when `up` is not perpendicular to the view direction
  /// (odyssey: 4.3 %). Only for comparing with those references.
  kNori2015,
};

struct LoadOptions {
  LookatConvention lookat = LookatConvention::kNori;
  /// Mitsuba scene parameters, "name=value" each (`-D name=value`): they override the scene's
  /// <default>s (engine/io/mitsuba_document.h). Nori scenes have no parameters.
  std::vector<std::string> defines = {};
};

/// Loads a Nori-format XML scene. Relative file names inside it resolve against the directory
/// of `path`; `path` is what error messages name. scene.source_path = path.
///
/// Format (wjakob/nori's parser, made strict):
/// - root `<scene>` with children, in any order:
///   `<mesh type=T>` / `<shape type=T>` (same thing), T = obj (string `filename`), sphere
///   (point `center` = 0,0,0; float `radius` = 1), rectangle, cube, disk (see shapes.h); all
///   take transform `toWorld` and at most one `<bsdf>` (default: diffuse 0.5) and one
///   `<emitter type="area">` (color `radiance`, required);
///   exactly one `<camera>`: perspective (float `fov` = 30, horizontal, degrees, in (0, 180);
///   integer `width` = 1280, `height` = 720; float `nearClip` = 1e-4, `farClip` = 1e4;
///   transform `toWorld`) or thinlens (the same plus required floats `apertureRadius` >= 0,
///   0 being a pinhole, and `focusDistance` > 0), optionally with an `<rfilter>` child;
///   at most one `<sampler type="independent|sobol">` (integer `sampleCount` = 1; without one,
///   the default sampler, SamplerDesc::kDefaultSampler);
///   exactly one `<integrator>`: normals, direct_ems, direct_mats, direct_mis, whitted,
///   path_mats, path_ems, path_mis (integer `maxDepth` for whitted/path_*, integer
///   `lightSamples` for direct_ems/direct_mis/path_ems/path_mis, string `heuristic` =
///   balance|power for direct_mis/path_mis; strings `lightSelection` = power|uniform and
///   `triangleSampling` = area|solidAngle wherever `lightSamples` is accepted);
///   at most one `<rfilter>` (here or in the camera): gaussian (float `radius` = 2, `stddev` =
///   0.5), box (`radius` = 0.5), tent (`radius` = 1);
///   any number of infinite `<emitter>`s directly in the scene: envmap (Mitsuba: string
///   `filename` required, an EXR/HDR/PFM/PNG lat-long image resolved like OBJ names; float
///   `scale` = 1, >= 0; string `sampling` = importance|uniform; transform `toWorld`, a rotation)
///   distantdisk (Nori ETH: color `radiance` and float `thetaA` in (0, 180] degrees, both
///   required; transform `toWorld`, a rotation, the cone around its local +z) and constant
///   (Mitsuba: color `radiance`, required; a distant disk of 180°). Environment-map
///   pixels must be finite and >= 0 (NaN, Inf or negative values are an error, not clamped);
///   see engine/light/environment_map.h for the lat-long convention.
/// - `<bsdf>`: diffuse (color `albedo` = 0.5 in [0,1]), mirror, dielectric (float `intIOR` =
///   1.5046, `extIOR` = 1.000277; ptlab's booleans `schlick` and `scaleRadiance` = false),
///   microfacet = Beckmann rough plastic (float `alpha` = 0.1,
///   `intIOR`, `extIOR`, color `kd` = 0.5 in [0,1]), roughconductor (float `alpha` = 0.1,
///   string `material` = Cu, a preset of engine/bsdf/conductor_presets.h, or colors `eta` and
///   `k` instead).
/// - properties: `<boolean|integer|float|string|point|vector|color name=.. value=..>`;
///   point/vector/color take exactly 3 numbers separated by commas and/or whitespace.
/// - `<transform name="toWorld">` with `<translate value>`, `<scale value>`, `<rotate axis
///   angle>` (degrees, right-hand rule), `<matrix value>` (16 numbers, row-major) and
///   `<lookat origin target up>`, applied in order: each one multiplies the accumulated
///   transform from the left. lookat gives the columns (left, newUp, dir, origin) with dir =
///   normalize(target − origin), left = normalize(cross(normalize(up), dir)), newUp =
///   normalize(cross(dir, left)).
///
/// Everything else is an error "file:line:col: message saying what was expected": XML syntax,
/// unknown tags and attributes, missing attributes, properties unknown to that object type,
/// duplicate properties, wrong property types, malformed numbers ("1.2.3", "abc", "nan",
/// "inf", trailing junk), wrong component counts, out-of-range values, singular transforms,
/// a second camera/sampler/integrator/rfilter, a missing camera or integrator, unreadable or
/// faceless OBJ files (the message then also carries the OBJ file:line), unreadable or invalid
/// environment maps, a toWorld of an infinite emitter that is not a rotation, and the features
/// not supported yet: `<test>` roots, `<bsdf>` outside a shape, Mitsuba's spot and
/// directional emitters. Area lights get their CDFs from FinalizeAreaLights before the scene is
/// returned.
StatusOr<Scene> LoadScene(const std::string& path, const LoadOptions& options = {});

/// As LoadScene, from XML text in memory: relative file names resolve against `base_dir`
/// and messages name `display_name`.
StatusOr<Scene> LoadSceneFromString(const std::string& xml, const std::string& base_dir,
                                    const std::string& display_name,
                                    const LoadOptions& options = {});

}  // namespace ptlab
