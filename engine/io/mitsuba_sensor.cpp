// Mitsuba scenes: the sensor (camera and film) and the reconstruction filter.
#include "engine/io/mitsuba_scene_builder.h"

#include <cmath>

#include "engine/io/mitsuba_document.h"
#include "engine/io/mitsuba_spectrum.h"
#include "engine/io/text_parsing.h"
#include "engine/io/xml_properties.h"
#include "engine/scene/scene_limits.h"

namespace ptlab::internal {
namespace {

constexpr double kPiD = 3.141592653589793238463;

// Mitsuba 3's scalar variants, which render its reference images, splat with the filter as a
// staircase of this many steps over [0, radius] (ReconstructionFilter::eval_discretized,
// MI_FILTER_RESOLUTION); its JIT variants evaluate it exactly. The difference is visible on
// hard edges: on the projector scenes the border pixels differ by 0.8 % (docs/mitsuba.md).
constexpr uint16_t kMitsubaFilterSteps = 31;

// Mitsuba's film aspect rule for `fov_axis` (and `focal_length`, a 35 mm film diagonal):
// the horizontal field of view in degrees.
double HorizontalFov(double fov, const std::string& axis, double aspect) {
  const auto from_half_tan = [](double t) { return 2.0 * std::atan(t) * 180.0 / kPiD; };
  const double half_tan = std::tan(0.5 * fov * kPiD / 180.0);
  if (axis == "y") return from_half_tan(half_tan * aspect);
  if (axis == "diagonal") return from_half_tan(half_tan / std::sqrt(1.0 + 1.0 / (aspect * aspect)));
  return fov;  // "x"
}

}  // namespace

Status MitsubaHorizontalFov(const MitsubaObject& obj, double aspect, float* horizontal_fov) {
  float fov = 0;
  std::string axis = "x";
  if (obj.Has("fov") && obj.Has("focal_length"))
    return obj.Error("focal_length", "give either 'fov' or 'focal_length', not both");
  if (obj.Has("focal_length")) {
    std::string text;
    PTLAB_RETURN_IF_ERROR(obj.String("focal_length", &text));
    if (text.size() > 2 && text.substr(text.size() - 2) == "mm") text.resize(text.size() - 2);
    float mm = 0;
    if (!ParseFloat(text, &mm) || !(mm > 0))
      return obj.Error("focal_length", "malformed focal_length; expected e.g. 50mm (> 0)");
    fov = float(2.0 * std::atan(std::sqrt(36.0 * 36 + 24 * 24) / (2.0 * mm)) * 180.0 / kPiD);
    axis = "diagonal";
  } else {
    fov = float(2.0 * std::atan(std::sqrt(36.0 * 36 + 24 * 24) / 100.0) * 180.0 / kPiD);
    axis = "diagonal";  // Mitsuba's default: a 50 mm lens
    if (obj.Has("fov")) {
      axis = "x";
      PTLAB_RETURN_IF_ERROR(obj.Float("fov", &fov));
      PTLAB_RETURN_IF_ERROR(obj.String("fov_axis", &axis));
      for (char& c : axis) c = char(std::tolower(static_cast<unsigned char>(c)));
      if (axis == "smaller") axis = aspect > 1 ? "y" : "x";
      if (axis == "larger") axis = aspect > 1 ? "x" : "y";
      if (axis != "x" && axis != "y" && axis != "diagonal")
        return obj.Error("fov_axis", "unknown fov_axis '" + axis +
                                         "'; expected x, y, diagonal, smaller or larger");
    }
  }
  if (!(fov > 0 && fov < 180))
    return obj.Error("fov", "fov = " + FormatNumber(fov) + " is out of range; expected (0, 180)");
  *horizontal_fov = float(HorizontalFov(fov, axis, aspect));
  if (!(*horizontal_fov > 0 && *horizontal_fov < 180))
    return obj.Error("fov", "the horizontal field of view " + FormatNumber(*horizontal_fov) +
                                " is out of range; expected (0, 180)");
  return Status::Ok();
}

Status MitsubaSceneBuilder::Sensor(const MitsubaNode& node) {
  StatusOr<MitsubaObject> obj = Read(node);
  if (!obj.ok()) return obj.status();
  const std::string& type = obj->type();
  CameraDesc camera;
  if (type == "perspective") {
    PTLAB_RETURN_IF_ERROR(obj->Expect(
        {"fov", "fov_axis", "focal_length", "near_clip", "far_clip", "focus_distance", "to_world",
         "shutter_open", "shutter_close", "principal_point_offset_x", "principal_point_offset_y"}));
  } else if (type == "thinlens") {
    PTLAB_RETURN_IF_ERROR(
        obj->Expect({"fov", "fov_axis", "focal_length", "near_clip", "far_clip", "focus_distance",
                     "aperture_radius", "to_world", "shutter_open", "shutter_close"}));
    PTLAB_RETURN_IF_ERROR(obj->Require("aperture_radius"));
  } else if (type == "orthographic") {
    PTLAB_RETURN_IF_ERROR(
        obj->Expect({"near_clip", "far_clip", "to_world", "shutter_open", "shutter_close"}));
    camera.projection = CameraDesc::Projection::kOrthographic;
  } else if (type == "radiancemeter" || type == "irradiancemeter" || type == "batch" ||
             type == "distant") {
    return Unsupported(node);
  } else {
    return node.Error("unknown sensor type '" + type +
                      "'; expected perspective, thinlens or orthographic");
  }
  const bool orthographic = camera.projection == CameraDesc::Projection::kOrthographic;
  const MitsubaNode *film = nullptr, *sampler = nullptr, *filter = nullptr;
  for (const MitsubaNode* child : obj->children()) {
    const MitsubaNode** slot = child->tag == "film"      ? &film
                               : child->tag == "sampler" ? &sampler
                                                         : nullptr;
    if (!slot) {
      if (child->tag == "medium") return Unsupported(*child);
      return child->Error("<" + child->tag +
                          "> is not allowed inside <sensor>; expected film "
                          "or sampler");
    }
    if (*slot) return child->Error("a second <" + child->tag + "> in the sensor");
    *slot = child;
  }
  // Mitsuba's defaults: hdrfilm 768 x 576 with a gaussian filter, independent sampler, 4 spp.
  camera.width = 768, camera.height = 576;
  scene_.filter = FilterDesc{};  // gaussian, stddev 0.5, radius 2 (= 4 stddev, Mitsuba's)
  scene_.filter.steps = kMitsubaFilterSteps;
  scene_.sampler.type = SamplerType::kIndependent;
  scene_.sampler.sample_count = 4;
  if (film) {
    StatusOr<MitsubaObject> f = Read(*film);
    if (!f.ok()) return f.status();
    if (f->type() != "hdrfilm") return Unsupported(*film);
    PTLAB_RETURN_IF_ERROR(
        f->Expect({"width", "height", "pixel_format", "component_format", "file_format",
                   "crop_offset_x", "crop_offset_y", "crop_width", "crop_height", "sample_border",
                   "banner", "high_quality_edges", "attach_log"}));
    PTLAB_RETURN_IF_ERROR(f->OnlyDefault("sample_border", false));
    PTLAB_RETURN_IF_ERROR(f->OnlyDefault("high_quality_edges", false));
    for (const char* crop : {"crop_offset_x", "crop_offset_y", "crop_width", "crop_height"})
      if (f->Has(crop))
        return f->Error(crop, "unsupported: film \"hdrfilm\" property " + std::string(crop) +
                                  " (crop windows)");
    PTLAB_RETURN_IF_ERROR(f->Integer("width", &camera.width));
    PTLAB_RETURN_IF_ERROR(f->Integer("height", &camera.height));
    if (const std::string size = FilmSizeError(camera.width, camera.height); !size.empty())
      return f->Error("width", size);
    for (const char* name : {"pixel_format", "component_format", "file_format"}) {
      std::string ignored;
      PTLAB_RETURN_IF_ERROR(f->String(name, &ignored));
    }
    for (const MitsubaNode* child : f->children()) {
      if (child->tag != "rfilter")
        return child->Error("<" + child->tag + "> is not allowed inside <film>; expected rfilter");
      if (filter) return child->Error("a second <rfilter> in the film");
      filter = child;
    }
  }
  if (filter) PTLAB_RETURN_IF_ERROR(Filter(*filter));
  if (sampler) PTLAB_RETURN_IF_ERROR(Sampler(*sampler));

  const double aspect = double(camera.width) / camera.height;
  if (!orthographic) PTLAB_RETURN_IF_ERROR(MitsubaHorizontalFov(*obj, aspect, &camera.fov_deg));
  camera.near_clip = 1e-2f, camera.far_clip = 1e4f;  // Mitsuba's defaults
  PTLAB_RETURN_IF_ERROR(obj->Float("near_clip", &camera.near_clip));
  PTLAB_RETURN_IF_ERROR(obj->Float("far_clip", &camera.far_clip));
  if (!(camera.near_clip > 0)) return obj->Error("near_clip", "near_clip must be > 0");
  if (!(camera.far_clip > camera.near_clip))
    return obj->Error("far_clip", "far_clip must be > near_clip");
  camera.focus_distance = camera.far_clip;
  PTLAB_RETURN_IF_ERROR(obj->Float("focus_distance", &camera.focus_distance));
  if (type == "thinlens") {
    PTLAB_RETURN_IF_ERROR(obj->Float("aperture_radius", &camera.aperture_radius));
    if (!(camera.aperture_radius >= 0))
      return obj->Error("aperture_radius", "aperture_radius must be >= 0");
    if (!(camera.focus_distance > 0))
      return obj->Error("focus_distance", "focus_distance must be > 0");
  }
  for (const char* name : {"principal_point_offset_x", "principal_point_offset_y"}) {
    float offset = 0;
    PTLAB_RETURN_IF_ERROR(obj->Float(name, &offset));
    if (offset != 0)
      return obj->Error(name, "unsupported: sensor \"" + type + "\" with " + name + " != 0");
  }
  float open = 0, close = 0;
  PTLAB_RETURN_IF_ERROR(obj->Float("shutter_open", &open));
  PTLAB_RETURN_IF_ERROR(obj->Float("shutter_close", &close));
  if (close != open)
    return obj->Error("shutter_close", "unsupported: sensor \"" + type +
                                           "\" motion blur (shutter_close != "
                                           "shutter_open)");
  PTLAB_RETURN_IF_ERROR(obj->TransformProperty("to_world", &camera.camera_to_world));
  const Matrix4& m = camera.camera_to_world.matrix();
  if (orthographic) {
    // The scale sets the view's extent (Mitsuba's [-1, 1]² film rectangle in camera space);
    // it must not collapse an axis.
    const float det = m.m[0][0] * (m.m[1][1] * m.m[2][2] - m.m[1][2] * m.m[2][1]) -
                      m.m[0][1] * (m.m[1][0] * m.m[2][2] - m.m[1][2] * m.m[2][0]) +
                      m.m[0][2] * (m.m[1][0] * m.m[2][1] - m.m[1][1] * m.m[2][0]);
    if (!(std::fabs(det) > 0 && std::isfinite(det)))
      return obj->Error("to_world",
                        "the orthographic sensor's to_world is singular; expected an "
                        "invertible transform (its scale sets the view's extent)");
    scene_.camera = camera;
    return Status::Ok();
  }
  // Mitsuba refuses scale in a perspective camera's to_world: its upper 3x3 must be orthonormal.
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const float dot = m.m[0][i] * m.m[0][j] + m.m[1][i] * m.m[1][j] + m.m[2][i] * m.m[2][j];
      if (!(std::fabs(dot - (i == j ? 1.0f : 0.0f)) <= 1e-4f))
        return obj->Error("to_world",
                          "the sensor's to_world scales or shears; expected a "
                          "rotation and translation (lookat, rotate, translate)");
    }
  scene_.camera = camera;
  return Status::Ok();
}

Status MitsubaSceneBuilder::Filter(const MitsubaNode& node) {
  StatusOr<MitsubaObject> obj = Read(node);
  if (!obj.ok()) return obj.status();
  const std::string& type = obj->type();
  FilterDesc filter;
  filter.steps = kMitsubaFilterSteps;  // Mitsuba's box is exact (its film skips the filter)
  if (type == "box") {
    PTLAB_RETURN_IF_ERROR(obj->Expect({}));
    filter.type = FilterDesc::Type::kBox;
    filter.radius = 0.5f;
    filter.steps = 0;
  } else if (type == "tent") {
    PTLAB_RETURN_IF_ERROR(obj->Expect({"radius"}));
    filter.type = FilterDesc::Type::kTent;
    filter.radius = 1.0f;
    PTLAB_RETURN_IF_ERROR(obj->Float("radius", &filter.radius));
  } else if (type == "gaussian") {
    PTLAB_RETURN_IF_ERROR(obj->Expect({"stddev"}));
    filter.type = FilterDesc::Type::kGaussian;
    PTLAB_RETURN_IF_ERROR(obj->Float("stddev", &filter.stddev));
    if (!(filter.stddev > 0)) return obj->Error("stddev", "stddev must be > 0");
    filter.radius = 4 * filter.stddev;  // Mitsuba's truncation
  } else if (type == "mitchell" || type == "catmullrom" || type == "lanczos") {
    return Unsupported(node);
  } else {
    return node.Error("unknown rfilter type '" + type + "'; expected box, tent or gaussian");
  }
  if (!(filter.radius > 0 && filter.radius <= kMaxFilterRadius))
    return obj->Error(type == "gaussian" ? "stddev" : "radius",
                      "filter radius " + FormatNumber(filter.radius) +
                          " is out of range; expected (0, " + FormatNumber(kMaxFilterRadius) +
                          "] pixels");
  scene_.filter = filter;
  return Status::Ok();
}

}  // namespace ptlab::internal
