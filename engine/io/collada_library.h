// COLLADA <library_lights> and <library_cameras>: a light or a camera as CS184 reads it, before
// the node tree places it in the scene (collada_loader.cpp).
#pragma once

#include <pugixml.hpp>

#include "engine/core/status.h"
#include "engine/core/transform.h"
#include "engine/core/vec.h"
#include "engine/io/collada_document.h"
#include "engine/scene/scene.h"

namespace ptlab::collada {

/// The film CS184 students render at is 480 pixels wide (its AppConfig).
inline constexpr int kDefaultFilmWidth = 480;

/// A light of <library_lights> as CS184 reads it (directional and spot lights as COLLADA
/// defines them: CS184 reads no spot light).
struct LightDesc {
  enum class Kind { kPoint, kAmbient, kArea, kDirectional, kSpot };
  Kind kind = Kind::kPoint;
  Color3f color;
  float falloff_angle = 180.0f;   // spot: the full cone angle, degrees (COLLADA's default)
  float falloff_exponent = 0.0f;  // spot: the cos θ exponent (COLLADA's default)
};

/// Reads a <light>: its technique_common type (ambient, directional, point, spot) or the CGL
/// <area> extra, its color (at most kMaxRadiance) and a spot's falloff.
Status ReadLight(const Document& doc, const pugi::xml_node& light, LightDesc* desc);

/// Reads a <camera>'s <perspective> optics: the horizontal field of view (from xfov, or yfov
/// with aspect_ratio), a film kDefaultFilmWidth wide at the file's aspect, znear and zfar.
Status ReadCamera(const Document& doc, const pugi::xml_node& camera, CameraDesc* desc);

/// Adds the light of `light` (read as `desc`; not an area light, which is a mesh the node tree
/// adds) at the node transform `world` of its <instance_light> `instance`: a point light of
/// CS184's intensity, a directional or spot light down the node's local -z, or CS184's
/// ambient light as a distant disk over the upper hemisphere (+y).
Status PlaceLight(const Document& doc, const pugi::xml_node& instance, const pugi::xml_node& light,
                  const LightDesc& desc, const Matrix4& world, Scene* scene);

}  // namespace ptlab::collada
