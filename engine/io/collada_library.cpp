// COLLADA <library_lights> and <library_cameras> as CS184 reads them (collada_library.h).
#include "engine/io/collada_library.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <string>
#include <string_view>

#include "engine/core/vec.h"
#include "engine/io/collada_transform.h"
#include "engine/light/distant_disk.h"
#include "engine/scene/scene_limits.h"

namespace ptlab::collada {
namespace {

// A spot's cos(θ)^e falls to 1/e at 1 - cos θ ≈ 1/e: beyond this exponent that is under
// ~1,000 float steps of cos θ below 1, a beam float cannot render faithfully.
constexpr float kMaxFalloffExponent = 1.0e4f;

Status ReadSpotFalloff(const Document& doc, const pugi::xml_node& spot, LightDesc* desc) {
  PTLAB_RETURN_IF_ERROR(doc.OptionalFloat(spot, "falloff_angle", &desc->falloff_angle));
  PTLAB_RETURN_IF_ERROR(doc.OptionalFloat(spot, "falloff_exponent", &desc->falloff_exponent));
  if (!(desc->falloff_angle > 0 && desc->falloff_angle <= 180))
    return doc.Error(spot.child("falloff_angle"),
                      "falloff_angle is out of range; expected the full cone angle in degrees, "
                      "in (0, 180]");
  if (!(desc->falloff_exponent >= 0 && desc->falloff_exponent <= kMaxFalloffExponent))
    return doc.Error(spot.child("falloff_exponent"),
                      "falloff_exponent is out of range; expected a number in [0, " +
                          std::to_string(int(kMaxFalloffExponent)) + "]");
  return Status::Ok();
}

Status CheckRadiance(const Document& doc, const pugi::xml_node& node, const Color3f& c) {
  if (!(MaxComponent(c) <= kMaxRadiance))
    return doc.Error(node, "a light color above " + std::to_string(kMaxRadiance));
  return Status::Ok();
}

// The world direction of a light node's local -z (unit); an error when the node's transform
// collapses it.
Status LightAxis(const Document& doc, const pugi::xml_node& instance, const Matrix4& world,
                 Vec3f* axis) {
  const Vec3f d = ApplyVector(world, {0, 0, -1});
  const float length = Length(d);
  if (!(length > 0) || !std::isfinite(length))
    return doc.Error(instance, "the light's node transform has no direction (local -z)");
  *axis = d / length;
  return Status::Ok();
}

}  // namespace

Status ReadLight(const Document& doc, const pugi::xml_node& light, LightDesc* desc) {
  PTLAB_RETURN_IF_ERROR(doc.CheckChildren(light, {"technique_common", "asset"}, true));
  const pugi::xml_node common = light.child("technique_common");
  if (!common) return doc.Error(light, "<light> has no <technique_common>");
  PTLAB_RETURN_IF_ERROR(
      doc.CheckChildren(common, {"ambient", "directional", "point", "spot"}));
  pugi::xml_node kind;
  for (const pugi::xml_node child : common.children())
    if (child.type() == pugi::node_element) {
      if (kind) return doc.Error(child, "a second light type in <technique_common>");
      kind = child;
    }
  if (!kind) return doc.Error(common, "<technique_common> names no light type");
  // The CGL <area> extra makes the light a CS184 area light, whatever the common type.
  if (const pugi::xml_node cgl = doc.CglTechnique(light)) {
    PTLAB_RETURN_IF_ERROR(doc.CheckChildren(cgl, {"area"}));
    const pugi::xml_node area = cgl.child("area");
    if (!area) return doc.Error(cgl, "the CGL technique of a light has no <area>");
    PTLAB_RETURN_IF_ERROR(doc.CheckChildren(area, {"color"}));
    if (!area.child("color")) return doc.Error(area, "<area> has no <color>");
    desc->kind = LightDesc::Kind::kArea;
    PTLAB_RETURN_IF_ERROR(doc.Color(area.child("color"), &desc->color));
    return CheckRadiance(doc, area.child("color"), desc->color);
  }
  const std::string_view type = kind.name();
  // CS184 reads the attenuation factors but its lights do not use them; neither does ptlab.
  const bool attenuated = type == "point" || type == "spot";
  PTLAB_RETURN_IF_ERROR(doc.CheckChildren(
      kind,
      type == "spot"
          ? std::initializer_list<std::string_view>{"color", "constant_attenuation",
                                                    "linear_attenuation", "quadratic_attenuation",
                                                    "falloff_angle", "falloff_exponent"}
      : attenuated
          ? std::initializer_list<std::string_view>{"color", "constant_attenuation",
                                                    "linear_attenuation", "quadratic_attenuation"}
          : std::initializer_list<std::string_view>{"color"}));
  if (!kind.child("color")) return doc.Error(kind, std::string("<") + std::string(type) + "> has no <color>");
  desc->kind = type == "point"         ? LightDesc::Kind::kPoint
               : type == "spot"        ? LightDesc::Kind::kSpot
               : type == "directional" ? LightDesc::Kind::kDirectional
                                       : LightDesc::Kind::kAmbient;
  PTLAB_RETURN_IF_ERROR(doc.Color(kind.child("color"), &desc->color));
  if (desc->kind == LightDesc::Kind::kSpot) PTLAB_RETURN_IF_ERROR(ReadSpotFalloff(doc, kind, desc));
  return CheckRadiance(doc, kind.child("color"), desc->color);
}

Status ReadCamera(const Document& doc, const pugi::xml_node& camera, CameraDesc* desc) {
  PTLAB_RETURN_IF_ERROR(doc.CheckChildren(camera, {"optics", "asset"}, true));
  const pugi::xml_node optics = camera.child("optics");
  if (!optics) return doc.Error(camera, "<camera> has no <optics>");
  PTLAB_RETURN_IF_ERROR(doc.CheckChildren(optics, {"technique_common"}, true));
  const pugi::xml_node common = optics.child("technique_common");
  if (!common) return doc.Error(optics, "<optics> has no <technique_common>");
  PTLAB_RETURN_IF_ERROR(doc.CheckChildren(common, {"perspective"}));
  const pugi::xml_node p = common.child("perspective");
  if (!p) return doc.Error(common, "<technique_common> has no <perspective>");
  PTLAB_RETURN_IF_ERROR(
      doc.CheckChildren(p, {"xfov", "yfov", "aspect_ratio", "znear", "zfar"}));
  float xfov = 0, yfov = 0, aspect = 0, znear = 0.001f, zfar = 1000.0f;
  PTLAB_RETURN_IF_ERROR(doc.OptionalFloat(p, "xfov", &xfov));
  PTLAB_RETURN_IF_ERROR(doc.OptionalFloat(p, "yfov", &yfov));
  PTLAB_RETURN_IF_ERROR(doc.OptionalFloat(p, "aspect_ratio", &aspect));
  PTLAB_RETURN_IF_ERROR(doc.OptionalFloat(p, "znear", &znear));
  PTLAB_RETURN_IF_ERROR(doc.OptionalFloat(p, "zfar", &zfar));
  for (const char* name : {"xfov", "yfov"})
    if (p.child(name)) {
      const float v = std::string_view(name) == "xfov" ? xfov : yfov;
      if (!(v > 0 && v < 180))
        return doc.Error(p.child(name), std::string(name) + " is out of range; expected "
                                                             "degrees in (0, 180)");
    }
  if (p.child("aspect_ratio") && !(aspect > 0))
    return doc.Error(p.child("aspect_ratio"), "aspect_ratio must be > 0");
  const auto tan_half = [](float deg) { return std::tan(deg * kPi / 360.0f); };
  const bool has_x = p.child("xfov"), has_y = p.child("yfov"), has_a = p.child("aspect_ratio");
  if (has_x && has_y) aspect = tan_half(xfov) / tan_half(yfov);
  else if (has_y && has_a) xfov = 2.0f * std::atan(tan_half(yfov) * aspect) * 180.0f / kPi;
  else if (!(has_x && has_a))
    return doc.Error(p, "<perspective> needs xfov or yfov with aspect_ratio, or both "
                         "xfov and yfov");
  if (!(znear > 0) || !(zfar > znear))
    return doc.Error(p, "expected 0 < znear < zfar");
  desc->fov_deg = xfov;
  desc->width = kDefaultFilmWidth;
  desc->height = std::max(1, int(std::lround(kDefaultFilmWidth / aspect)));
  if (const std::string size = FilmSizeError(desc->width, desc->height); !size.empty())
    return doc.Error(p, "aspect_ratio gives a film of " + size);
  desc->near_clip = znear;
  desc->far_clip = zfar;
  desc->keep_vertical_fov = true;
  return Status::Ok();
}

Status PlaceLight(const Document& doc, const pugi::xml_node& instance, const pugi::xml_node& light,
                  const LightDesc& desc, const Matrix4& world, Scene* scene) {
  switch (desc.kind) {
  case LightDesc::Kind::kPoint: {
    // CS184's point light has radiant intensity `color` (W/sr); ptlab stores the power.
    PointLightTable& t = scene->point_lights;
    scene->emitters.push_back(EmitterRef::Make(EmitterTag::kPoint, uint32_t(t.size())));
    t.position.push_back(ApplyPoint(world, {0, 0, 0}));
    t.power.push_back(desc.color * (4.0f * kPi));
    return Status::Ok();
  }
  case LightDesc::Kind::kDirectional: {
    // COLLADA lights shine down their local -z.
    Vec3f dir;
    PTLAB_RETURN_IF_ERROR(LightAxis(doc, instance, world, &dir));
    DirectionalLightTable& t = scene->directional_lights;
    scene->emitters.push_back(EmitterRef::Make(EmitterTag::kDirectional, uint32_t(t.size())));
    t.direction.push_back(dir);
    t.radiance.push_back(desc.color);
    return Status::Ok();
  }
  case LightDesc::Kind::kSpot: {
    Vec3f axis;
    PTLAB_RETURN_IF_ERROR(LightAxis(doc, instance, world, &axis));
    SpotLightTable& t = scene->spot_lights;
    scene->emitters.push_back(EmitterRef::Make(EmitterTag::kSpot, uint32_t(t.size())));
    t.position.push_back(ApplyPoint(world, {0, 0, 0}));
    t.axis.push_back(axis);
    t.intensity.push_back(desc.color);
    // cos(angle/2) = sin(90° - angle/2): exactly 0 for the default 180°.
    t.cos_half_angle.push_back(
        float(std::sin((180.0 - double(desc.falloff_angle)) * std::numbers::pi / 360.0)));
    t.exponent.push_back(desc.falloff_exponent);
    // No linear ramp: full intensity (times cos^exponent) up to the cone's edge.
    t.cos_beam.push_back(t.cos_half_angle.back());
    t.cutoff.push_back(float(double(desc.falloff_angle) * std::numbers::pi / 360.0));
    t.inv_transition.push_back(0.0f);
    return Status::Ok();
  }
  case LightDesc::Kind::kAmbient: {
    // CS184's InfiniteHemisphereLight: constant radiance over the upper hemisphere (+y).
    if (IsBlack(desc.color)) return Status::Ok();
    StatusOr<uint32_t> row = AddDistantDisk(desc.color, 90.0f, Frame(Vec3f{0, 1, 0}),
                                            doc.at.At(light), &scene->distant_disks);
    if (!row.ok()) return row.status();
    scene->emitters.push_back(EmitterRef::Make(EmitterTag::kDistantDisk, *row));
    return Status::Ok();
  }
    case LightDesc::Kind::kArea:
      break;
  }
  return doc.Error(instance, "an area light is a mesh, not a placed light (internal)");
}

}  // namespace ptlab::collada
