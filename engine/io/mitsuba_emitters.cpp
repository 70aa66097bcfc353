// Mitsuba <emitter>s: area (inside shapes), point, directional, constant, envmap (spot and
// projector: mitsuba_delta_emitters.cpp).
#include <cmath>
#include <numbers>

#include "engine/image/image_io.h"
#include "engine/io/mitsuba_scene_builder.h"
#include "engine/io/rotation_frame.h"
#include "engine/light/distant_disk.h"
#include "engine/light/environment_map.h"
#include "engine/scene/scene_limits.h"
#include "engine/texture/texture_mean.h"

namespace ptlab::internal {

Status CheckEmission(const MitsubaObject& obj, const char* name, const Color3f& c) {
  if (c.r >= 0 && c.g >= 0 && c.b >= 0 && c.r <= kMaxRadiance && c.g <= kMaxRadiance &&
      c.b <= kMaxRadiance)
    return Status::Ok();
  return obj.Error(name,
                   std::string("'") + name + "' is out of range; expected components in [0, 1e20]");
}

namespace {

bool IsUnsupportedEmitter(const std::string& type) {
  return type == "sunsky" || type == "sky" || type == "sun" || type == "ptracer";
}

}  // namespace

Status MitsubaSceneBuilder::AreaEmitter(const MitsubaNode& node, Color3f* radiance,
                                        uint32_t* texture) {
  StatusOr<MitsubaObject> obj = Read(node);
  if (!obj.ok()) return obj.status();
  if (obj->type() != "area") {
    if (IsUnsupportedEmitter(obj->type())) return Unsupported(node);
    return node.Error("emitter type '" + obj->type() + "' inside a shape; expected area");
  }
  PTLAB_RETURN_IF_ERROR(obj->Expect({"radiance", "sampling_weight"}));
  PTLAB_RETURN_IF_ERROR(obj->SamplingWeight());
  PTLAB_RETURN_IF_ERROR(obj->Require("radiance"));
  *texture = kNoTexture;
  if (const MitsubaProperty* p = obj->Get("radiance");
      p->type == MitsubaProperty::Type::kObject && p->object->tag == "texture") {
    StatusOr<uint32_t> row = EmitterTexture(*p, "as property 'radiance' of an area emitter");
    if (!row.ok()) return row.status();
    *texture = *row;
    // The texture's mean: the selection power (AreaLightTable::radiance).
    *radiance = TextureMean(scene_.textures, *texture);
    return Status::Ok();
  }
  PTLAB_RETURN_IF_ERROR(obj->Color("radiance", SpectrumUse::kEmission, radiance));
  return CheckEmission(*obj, "radiance", *radiance);
}

Status MitsubaSceneBuilder::Rotation(const MitsubaObject& obj, const Transform& to_world,
                                     Frame* frame) const {
  if (!RotationFrameOf(to_world, frame))
    return obj.Error("to_world", "to_world of " + DescribeMitsuba(obj.node()) +
                                     " is not a rotation; expected an orthonormal upper 3x3");
  return Status::Ok();
}

Status MitsubaSceneBuilder::SceneEmitter(const MitsubaNode& node) {
  StatusOr<MitsubaObject> read = Read(node);
  if (!read.ok()) return read.status();
  const MitsubaObject& obj = *read;
  const std::string& type = obj.type();
  if (!obj.children().empty() && type != "envmap")
    return Unsupported(*obj.children()[0], "inside " + DescribeMitsuba(node));
  if (type == "point") {
    PTLAB_RETURN_IF_ERROR(obj.Expect({"intensity", "position", "to_world", "sampling_weight"}));
    PTLAB_RETURN_IF_ERROR(obj.SamplingWeight());
    Color3f intensity{1, 1, 1};
    PTLAB_RETURN_IF_ERROR(obj.Color("intensity", SpectrumUse::kEmission, &intensity));
    PTLAB_RETURN_IF_ERROR(CheckEmission(obj, "intensity", intensity));
    if (obj.Has("position") && obj.Has("to_world"))
      return obj.Error("to_world", "give either 'position' or 'to_world', not both");
    Vec3f position{0, 0, 0};
    PTLAB_RETURN_IF_ERROR(obj.Point("position", &position));
    Transform to_world;
    PTLAB_RETURN_IF_ERROR(obj.TransformProperty("to_world", &to_world));
    if (obj.Has("to_world")) position = to_world.ApplyPoint({0, 0, 0});
    // ptlab's point light takes the power Φ = 4π I.
    const float four_pi = 4.0f * std::numbers::pi_v<float>;
    scene_.emitters.push_back(
        EmitterRef::Make(EmitterTag::kPoint, uint32_t(scene_.point_lights.size())));
    scene_.point_lights.position.push_back(position);
    scene_.point_lights.power.push_back(intensity * four_pi);
    return Status::Ok();
  }
  if (type == "directional") {
    PTLAB_RETURN_IF_ERROR(obj.Expect({"irradiance", "direction", "to_world", "sampling_weight"}));
    PTLAB_RETURN_IF_ERROR(obj.SamplingWeight());
    Color3f irradiance{1, 1, 1};
    PTLAB_RETURN_IF_ERROR(obj.Color("irradiance", SpectrumUse::kEmission, &irradiance));
    PTLAB_RETURN_IF_ERROR(CheckEmission(obj, "irradiance", irradiance));
    if (obj.Has("direction") && obj.Has("to_world"))
      return obj.Error("to_world", "give either 'direction' or 'to_world', not both");
    Vec3f direction{0, 0, 1};
    PTLAB_RETURN_IF_ERROR(obj.Vector("direction", &direction));
    Transform to_world;
    PTLAB_RETURN_IF_ERROR(obj.TransformProperty("to_world", &to_world));
    if (obj.Has("to_world")) direction = to_world.ApplyVector({0, 0, 1});
    if (!(Length(direction) > 0))
      return obj.Error("direction", "the direction must be a non-zero vector");
    scene_.emitters.push_back(
        EmitterRef::Make(EmitterTag::kDirectional, uint32_t(scene_.directional_lights.size())));
    scene_.directional_lights.direction.push_back(Normalize(direction));
    scene_.directional_lights.radiance.push_back(irradiance);  // irradiance, per its table
    return Status::Ok();
  }
  if (type == "constant") {
    PTLAB_RETURN_IF_ERROR(obj.Expect({"radiance", "sampling_weight"}));
    PTLAB_RETURN_IF_ERROR(obj.SamplingWeight());
    Color3f radiance{1, 1, 1};
    PTLAB_RETURN_IF_ERROR(obj.Color("radiance", SpectrumUse::kEmission, &radiance));
    PTLAB_RETURN_IF_ERROR(CheckEmission(obj, "radiance", radiance));
    StatusOr<uint32_t> row =
        AddDistantDisk(radiance, 180.0f, Frame(), node.where, &scene_.distant_disks);
    if (!row.ok()) return row.status();
    scene_.emitters.push_back(EmitterRef::Make(EmitterTag::kDistantDisk, *row));
    return Status::Ok();
  }
  if (type == "envmap") {
    if (!obj.children().empty()) return Unsupported(*obj.children()[0], "inside an envmap");
    PTLAB_RETURN_IF_ERROR(obj.Expect(
        {"filename", "scale", "to_world", "mis_compensation", "sampling_weight", "gamma"}));
    PTLAB_RETURN_IF_ERROR(obj.SamplingWeight());
    if (obj.Has("gamma"))  // Mitsuba 0.6: a gamma for LDR maps
      return obj.Error("gamma", "unsupported: emitter \"envmap\" with gamma");
    PTLAB_RETURN_IF_ERROR(obj.Require("filename"));
    std::string filename;
    PTLAB_RETURN_IF_ERROR(obj.String("filename", &filename));
    EnvironmentMapDesc desc;
    // Mitsuba 3's envmap puts its first and last pixel rows on the poles; Mitsuba 0.6's (the
    // scenes of version < 2 were rendered with it) centres them in their bands, as ptlab does.
    desc.rows = legacy_ ? EnvironmentRows::kCentred : EnvironmentRows::kAtPoles;
    PTLAB_RETURN_IF_ERROR(obj.Float("scale", &desc.scale));
    if (!(desc.scale >= 0)) return obj.Error("scale", "scale must be >= 0");
    bool compensation = false;
    PTLAB_RETURN_IF_ERROR(obj.Boolean("mis_compensation", &compensation));
    if (compensation)
      return obj.Error("mis_compensation",
                       "unsupported: emitter \"envmap\" with "
                       "mis_compensation = true");
    Transform to_world;
    PTLAB_RETURN_IF_ERROR(obj.TransformProperty("to_world", &to_world));
    PTLAB_RETURN_IF_ERROR(Rotation(obj, to_world, &desc.to_world));
    StatusOr<std::string> path = Resolve(obj, "filename", filename);
    if (!path.ok()) return path.status();
    StatusOr<Image> image = ReadImage(*path);
    if (!image.ok())
      return obj.Error("filename", "cannot load the image of " + DescribeMitsuba(node) + ": " +
                                       image.status().message());
    scene_.input_files.push_back(*path);
    StatusOr<uint32_t> row = AddEnvironmentMap(*image, desc, *path, &scene_.environment_maps);
    if (!row.ok()) return node.Error(row.status().message());
    scene_.emitters.push_back(EmitterRef::Make(EmitterTag::kEnvironment, *row));
    return Status::Ok();
  }
  if (type == "area") return node.Error("an area emitter must be inside a <shape>");
  if (type == "spot") return SpotEmitter(obj);
  if (type == "projector") return ProjectorEmitter(obj);
  if (IsUnsupportedEmitter(type)) return Unsupported(node);
  return node.Error("unknown emitter type '" + type +
                    "'; expected point, directional, spot, projector, constant, envmap "
                    "(area inside a shape)");
}

}  // namespace ptlab::internal
