// CS184 scenes: COLLADA 1.4.1 (.dae) files with the course's <technique profile="CGL"> extras.
#pragma once

#include <string>

#include "engine/core/status.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// Loads a COLLADA 1.4.1 scene as CS184's pathtracer reads it (the subset Blender 2.7x exports
/// and the course's CGL extras; docs/cs184.md lists what maps to what):
/// - <asset>: <unit meter> scales the world, <up_axis> X_UP/Y_UP/Z_UP is turned to +y up (as
///   CS184 does, so that environment maps have their zenith up). Other asset children are
///   metadata.
/// - <library_cameras>: perspective xfov/yfov/aspect_ratio/znear/zfar. The film is 480 pixels
///   wide with the camera's aspect ratio; resizing it keeps the vertical field of view.
/// - <library_lights>: point (intensity = its color, W/sr), ambient (a hemisphere of constant
///   radiance above the horizon; black: no emitter), the CGL <area> extra (a one-sided unit
///   square in the light's local xy plane, emitting towards its local -z).
/// - <library_effects>: CGL diffuse, mirror, glass, refraction, microfacet, emission; else the
///   common profile's diffuse color.
/// - <library_geometries>: <mesh> with polylist, triangles, polygons (fan-triangulated), sources
///   read through their accessor's count/stride/offset, POSITION/NORMAL/TEXCOORD inputs; the
///   CGL <sphere radius> extra (a tessellated sphere, see shapes.h).
/// - <library_visual_scenes>: nodes with matrix/translate/rotate/scale applied in order,
///   nested nodes, instance_node, instance_geometry with bind_material, instance_light,
///   instance_camera (exactly one).
/// Techniques of other profiles (e.g. "blender") are application hints and are ignored, as the
/// COLLADA specification says. Any other element is an error "not supported yet: <element> at
/// file:line:col"; malformed content (bad numbers, missing or dangling url/source/target
/// references, accessors reaching past their arrays, indices out of range, cycles of
/// instance_node) is an error naming file:line:col and what was expected.
///
/// The scene gets CS184's defaults: 1 sample per pixel, path tracing with emitter sampling
/// (path_ems) of max depth 1 and 1 light sample; the command line overrides them.
StatusOr<Scene> LoadColladaScene(const std::string& path);

/// As LoadColladaScene, from text in memory; messages name `display_name`.
StatusOr<Scene> LoadColladaSceneFromString(const std::string& text,
                                           const std::string& display_name);

}  // namespace ptlab
