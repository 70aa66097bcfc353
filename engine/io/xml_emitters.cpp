// Nori XML <emitter>: area (inside shapes), envmap, distantdisk, constant and point.

#include "engine/bsdf/conductor_presets.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <pugixml.hpp>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/image/image_io.h"
#include "engine/light/distant_disk.h"
#include "engine/light/environment_map.h"
#include "engine/io/mesh_builder.h"
#include "engine/io/rotation_frame.h"
#include "engine/io/obj_loader.h"
#include "engine/scene/scene_limits.h"
#include "engine/io/shapes.h"
#include "engine/io/text_parsing.h"
#include "engine/io/xml_loader_internal.h"
#include "engine/io/xml_scene_parser.h"

namespace ptlab::internal {

bool SceneParser::IsUnsupportedEmitter(const std::string& type) {
  return type == "spot" || type == "directional";
}

bool SceneParser::IsSceneEmitter(const std::string& type) {
  return type == "envmap" || type == "distantdisk" || type == "point" || type == "constant";
}

Status SceneParser::ParseAreaEmitter(const pugi::xml_node& node, Color3f* radiance) {
  PropertyList props(&at_, node);
  PTLAB_RETURN_IF_ERROR(CollectLeafObject(node, &props));
  const std::string type = node.attribute("type").value();
  if (IsUnsupportedEmitter(type))
    return at_.Error(node, "emitter type '" + type + "' is not supported yet");
  if (IsSceneEmitter(type))
    return at_.Error(node, "an emitter of type '" + type +
                               "' cannot be attached to a shape; expected it directly inside "
                               "<scene>");
  if (type != "area")
    return at_.Error(node, "unknown emitter type '" + type + "' inside a shape; expected area");
  PTLAB_RETURN_IF_ERROR(props.Expect({"radiance"}));
  PTLAB_RETURN_IF_ERROR(props.Require("radiance", "color"));
  PTLAB_RETURN_IF_ERROR(props.Color("radiance", radiance));
  return CheckColor(props, "radiance", *radiance, Range::kNonNegative);
}

Status SceneParser::ParseSceneEmitter(const pugi::xml_node& node) {
  PTLAB_RETURN_IF_ERROR(CheckAttributes(at_, node, {"type"}));
  const std::string type = node.attribute("type").value();
  if (IsUnsupportedEmitter(type))
    return at_.Error(node, "emitter type '" + type + "' is not supported yet");
  if (type == "area")
    return at_.Error(node, "an area emitter must be inside a <mesh> or <shape>");
  if (type == "envmap") return ParseEnvironmentEmitter(node);
  if (type == "distantdisk") return ParseDistantDiskEmitter(node);
  if (type == "point") return ParsePointEmitter(node);
  if (type == "constant") return ParseConstantEmitter(node);
  return at_.Error(node, "unknown emitter type '" + type +
                             "'; expected envmap, distantdisk, constant or point (area goes "
                             "inside a shape)");
}

Status SceneParser::ParseConstantEmitter(const pugi::xml_node& node) {
  PropertyList props(&at_, node);
  PTLAB_RETURN_IF_ERROR(CollectLeafObject(node, &props));
  PTLAB_RETURN_IF_ERROR(props.Expect({"radiance"}));
  PTLAB_RETURN_IF_ERROR(props.Require("radiance", "color"));
  Color3f radiance;
  PTLAB_RETURN_IF_ERROR(props.Color("radiance", &radiance));
  PTLAB_RETURN_IF_ERROR(CheckColor(props, "radiance", radiance, Range::kNonNegative));
  StatusOr<uint32_t> row =
      AddDistantDisk(radiance, 180.0f, Frame(), at_.At(node), &scene_.distant_disks);
  if (!row.ok()) return row.status();
  scene_.emitters.push_back(EmitterRef::Make(EmitterTag::kDistantDisk, *row));
  return Status::Ok();
}

Status SceneParser::ParsePointEmitter(const pugi::xml_node& node) {
  PropertyList props(&at_, node);
  PTLAB_RETURN_IF_ERROR(CollectLeafObject(node, &props));
  PTLAB_RETURN_IF_ERROR(props.Expect({"position", "power"}));
  PTLAB_RETURN_IF_ERROR(props.Require("position", "point"));
  PTLAB_RETURN_IF_ERROR(props.Require("power", "color"));
  Vec3f position;
  Color3f power;
  PTLAB_RETURN_IF_ERROR(props.Point("position", &position));
  PTLAB_RETURN_IF_ERROR(props.Color("power", &power));
  PTLAB_RETURN_IF_ERROR(CheckColor(props, "power", power, Range::kNonNegative));
  PointLightTable& lights = scene_.point_lights;
  scene_.emitters.push_back(EmitterRef::Make(EmitterTag::kPoint, uint32_t(lights.size())));
  lights.position.push_back(position);
  lights.power.push_back(power);
  return Status::Ok();
}

Status SceneParser::RotationOf(const pugi::xml_node& node, PropertyList& props, const Transform& to_world,
                               Frame* frame) {
  if (!RotationFrameOf(to_world, frame))
    return props.Error("toWorld", "toWorld of " + Describe(node) +
                                      " is not a rotation; expected an orthonormal upper 3x3 "
                                      "(rotate, lookat; no scale or shear)");
  return Status::Ok();
}

Status SceneParser::ParseEnvironmentEmitter(const pugi::xml_node& node) {
  PropertyList props(&at_, node);
  PTLAB_RETURN_IF_ERROR(CollectLeafObject(node, &props));
  PTLAB_RETURN_IF_ERROR(props.Expect({"filename", "scale", "toWorld", "sampling"}));
  PTLAB_RETURN_IF_ERROR(props.Require("filename", "string"));
  std::string filename, sampling = "importance";
  EnvironmentMapDesc desc;
  Transform to_world;
  PTLAB_RETURN_IF_ERROR(props.String("filename", &filename));
  PTLAB_RETURN_IF_ERROR(props.Float("scale", &desc.scale));
  PTLAB_RETURN_IF_ERROR(props.String("sampling", &sampling));
  PTLAB_RETURN_IF_ERROR(props.TransformProperty("toWorld", &to_world));
  if (!(desc.scale >= 0))
    return props.Error("scale", "scale = " + FormatNumber(desc.scale) +
                                    " is out of range; expected a value >= 0");
  if (sampling != "importance" && sampling != "uniform")
    return props.Error("sampling",
                       "unknown sampling '" + sampling + "'; expected importance or uniform");
  desc.sampling =
      sampling == "uniform" ? EnvironmentSampling::kUniform : EnvironmentSampling::kImportance;
  PTLAB_RETURN_IF_ERROR(RotationOf(node, props, to_world, &desc.to_world));
  const std::string path = Resolve(filename);
  StatusOr<Image> image = ReadImage(path);
  if (!image.ok())
    return at_.Error(
        node, "cannot load the image of " + Describe(node) + ": " + image.status().message());
  scene_.input_files.push_back(path);
  StatusOr<uint32_t> row = AddEnvironmentMap(*image, desc, path, &scene_.environment_maps);
  if (!row.ok()) return at_.Error(node, row.status().message());
  scene_.emitters.push_back(EmitterRef::Make(EmitterTag::kEnvironment, *row));
  return Status::Ok();
}

Status SceneParser::ParseDistantDiskEmitter(const pugi::xml_node& node) {
  PropertyList props(&at_, node);
  PTLAB_RETURN_IF_ERROR(CollectLeafObject(node, &props));
  PTLAB_RETURN_IF_ERROR(props.Expect({"radiance", "thetaA", "toWorld"}));
  PTLAB_RETURN_IF_ERROR(props.Require("radiance", "color"));
  PTLAB_RETURN_IF_ERROR(props.Require("thetaA", "float"));
  Color3f radiance;
  float theta_a = 0;
  Transform to_world;
  Frame frame;
  PTLAB_RETURN_IF_ERROR(props.Color("radiance", &radiance));
  PTLAB_RETURN_IF_ERROR(props.Float("thetaA", &theta_a));
  PTLAB_RETURN_IF_ERROR(props.TransformProperty("toWorld", &to_world));
  PTLAB_RETURN_IF_ERROR(CheckColor(props, "radiance", radiance, Range::kNonNegative));
  if (!(theta_a > 0 && theta_a <= 180))
    return props.Error("thetaA", "thetaA = " + FormatNumber(theta_a) +
                                     " is out of range; expected degrees in (0, 180]");
  PTLAB_RETURN_IF_ERROR(RotationOf(node, props, to_world, &frame));
  StatusOr<uint32_t> row =
      AddDistantDisk(radiance, theta_a, frame, at_.At(node), &scene_.distant_disks);
  if (!row.ok()) return row.status();
  scene_.emitters.push_back(EmitterRef::Make(EmitterTag::kDistantDisk, *row));
  return Status::Ok();
}

}  // namespace ptlab::internal
