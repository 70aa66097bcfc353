// Mitsuba <emitter>s at a point that light a region of directions: spot and projector.
#include <cmath>
#include <numbers>

#include "engine/io/mitsuba_scene_builder.h"
#include "engine/io/xml_properties.h"
#include "engine/texture/texture_mean.h"

namespace ptlab::internal {

// Mitsuba 3's spot (src/emitters/spot.cpp): intensity I along its local +z, full up to
// beam_width, falling linearly in angle to 0 at cutoff_angle (degrees; beam_width defaults to
// 3/4 of cutoff_angle, cutoff_angle to 20), times its projected `texture` if it has one.
Status MitsubaSceneBuilder::SpotEmitter(const MitsubaObject& obj) {
  PTLAB_RETURN_IF_ERROR(obj.Expect(
      {"intensity", "cutoff_angle", "beam_width", "texture", "to_world", "sampling_weight"}));
  PTLAB_RETURN_IF_ERROR(obj.SamplingWeight());
  uint32_t texture = kNoTexture;
  if (const MitsubaProperty* p = obj.Get("texture")) {
    if (p->type != MitsubaProperty::Type::kObject)
      return obj.Error("texture", "the texture of a spot must be a spatially varying <texture> "
                                  "(bitmap or checkerboard), as in Mitsuba 3");
    StatusOr<uint32_t> row = EmitterTexture(*p, "as the texture of a spot emitter");
    if (!row.ok()) return row.status();
    texture = *row;
  }
  Color3f intensity{1, 1, 1};
  PTLAB_RETURN_IF_ERROR(obj.Color("intensity", SpectrumUse::kEmission, &intensity));
  PTLAB_RETURN_IF_ERROR(CheckEmission(obj, "intensity", intensity));
  float cutoff_deg = 20.0f;
  PTLAB_RETURN_IF_ERROR(obj.Float("cutoff_angle", &cutoff_deg));
  if (!(cutoff_deg > 0 && cutoff_deg <= 180))
    return obj.Error("cutoff_angle", "cutoff_angle = " + FormatNumber(cutoff_deg) +
                                         " is out of range; expected (0, 180] degrees");
  float beam_deg = cutoff_deg * 3.0f / 4.0f;
  PTLAB_RETURN_IF_ERROR(obj.Float("beam_width", &beam_deg));
  if (!(beam_deg >= 0 && beam_deg <= cutoff_deg))
    return obj.Error("beam_width", "beam_width = " + FormatNumber(beam_deg) +
                                       " is out of range; expected [0, cutoff_angle = " +
                                       FormatNumber(cutoff_deg) + "] degrees");
  Transform to_world;
  PTLAB_RETURN_IF_ERROR(obj.TransformProperty("to_world", &to_world));
  Frame frame;
  PTLAB_RETURN_IF_ERROR(Rotation(obj, to_world, &frame));
  const double deg = std::numbers::pi / 180.0;
  const float cutoff = float(double(cutoff_deg) * deg), beam = float(double(beam_deg) * deg);
  SpotLightTable& t = scene_.spot_lights;
  scene_.emitters.push_back(EmitterRef::Make(EmitterTag::kSpot, uint32_t(t.size())));
  t.position.push_back(to_world.ApplyPoint({0, 0, 0}));
  t.axis.push_back(frame.n);
  t.intensity.push_back(intensity);
  t.cos_half_angle.push_back(std::cos(cutoff));
  t.exponent.push_back(0.0f);
  // beam_width = cutoff_angle: no ramp (Mitsuba's 1 / 0 is never used either).
  const bool ramp = beam < cutoff;
  t.cos_beam.push_back(ramp ? std::cos(beam) : t.cos_half_angle.back());
  t.cutoff.push_back(cutoff);
  t.inv_transition.push_back(ramp ? 1.0f / (cutoff - beam) : 0.0f);
  // The texture columns exist once a spot has a texture (SpotLightTable).
  if (texture != kNoTexture || !t.texture.empty()) {
    t.texture.resize(t.size(), kNoTexture);
    t.texture_frame.resize(t.size());
    t.texture.back() = texture;
    t.texture_frame.back() = frame;
  }
  return Status::Ok();
}

// Mitsuba 3's projector (src/emitters/projector.cpp): a pinhole at to_world's origin looking
// along its +z, its frustum the perspective camera's for the image's aspect (fov, fov_axis or
// focal_length as a sensor's), projecting the irradiance image times `scale`. The image is a
// constant colour (aspect 1, as Mitsuba's constant texture has resolution 1 × 1) or a
// bitmap / checkerboard texture (aspect = the bitmap's width / height; ProjectorIrradiance).
Status MitsubaSceneBuilder::ProjectorEmitter(const MitsubaObject& obj) {
  PTLAB_RETURN_IF_ERROR(obj.Expect(
      {"irradiance", "scale", "to_world", "fov", "fov_axis", "focal_length", "sampling_weight"}));
  PTLAB_RETURN_IF_ERROR(obj.SamplingWeight());
  PTLAB_RETURN_IF_ERROR(obj.Require("irradiance"));
  Color3f irradiance;
  uint32_t texture = kNoTexture;
  double aspect = 1.0;  // a constant image: 1 × 1 pixels, as Mitsuba's constant texture
  if (const MitsubaProperty* p = obj.Get("irradiance");
      p->type == MitsubaProperty::Type::kObject && p->object->tag == "texture") {
    StatusOr<uint32_t> row = EmitterTexture(*p, "as property 'irradiance' of a projector");
    if (!row.ok()) return row.status();
    texture = *row;
    // The image's mean: the selection power (ProjectorTable::irradiance).
    irradiance = TextureMean(scene_.textures, texture);
    aspect = double(scene_.textures.width[texture]) / double(scene_.textures.height[texture]);
  } else {
    PTLAB_RETURN_IF_ERROR(obj.Color("irradiance", SpectrumUse::kEmission, &irradiance));
    PTLAB_RETURN_IF_ERROR(CheckEmission(obj, "irradiance", irradiance));
  }
  float scale = 1.0f;
  PTLAB_RETURN_IF_ERROR(obj.Float("scale", &scale));
  if (!(scale >= 0 && scale <= 1e20f))
    return obj.Error("scale",
                     "scale = " + FormatNumber(scale) + " is out of range; expected [0, 1e20]");
  float fov_x = 0;
  PTLAB_RETURN_IF_ERROR(MitsubaHorizontalFov(obj, aspect, &fov_x));
  Transform to_world;
  PTLAB_RETURN_IF_ERROR(obj.TransformProperty("to_world", &to_world));
  Frame frame;
  PTLAB_RETURN_IF_ERROR(Rotation(obj, to_world, &frame));
  const double tan_x = std::tan(double(fov_x) * std::numbers::pi / 360.0);
  ProjectorTable& t = scene_.projectors;
  scene_.emitters.push_back(EmitterRef::Make(EmitterTag::kProjector, uint32_t(t.size())));
  t.position.push_back(to_world.ApplyPoint({0, 0, 0}));
  t.to_world.push_back(frame);
  t.tan_half_x.push_back(float(tan_x));
  t.tan_half_y.push_back(float(tan_x / aspect));
  t.scale.push_back(scale);
  t.irradiance.push_back(irradiance);
  if (texture != kNoTexture || !t.texture.empty()) {
    t.texture.resize(t.size(), kNoTexture);
    t.texture.back() = texture;
  }
  return Status::Ok();
}

}  // namespace ptlab::internal
