// Nori XML scene parser: strict property lists, transforms, and one builder per object type.
#include "engine/io/xml_loader.h"
#include "engine/io/xml_locator.h"

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
#include "engine/io/obj_loader.h"
#include "engine/scene/scene_limits.h"
#include "engine/io/shapes.h"
#include "engine/io/text_parsing.h"
#include "engine/io/xml_loader_internal.h"
#include "engine/io/xml_scene_parser.h"

namespace ptlab {
namespace internal {

Status SceneParser::ParseRoot(const pugi::xml_document& doc) {
  pugi::xml_node root;
  PTLAB_RETURN_IF_ERROR(at_.FindSingleRoot(doc, "scene", &root));
  const std::string_view tag = root.name();
  if (tag == "test")
    return at_.Error(root,
                     "<test> roots (Nori t-test / chi-square test files) are not supported "
                     "yet as scenes; run the file with `ptlab test FILE.xml`; expected a "
                     "<scene> root");
  if (tag != "scene")
    return at_.Error(root, "root element <" + std::string(tag) + ">; expected <scene>");
  return ParseScene(root);
}

Status SceneParser::Collect(const pugi::xml_node& node, const std::vector<const char*>& allowed,
                            PropertyList* props, std::vector<pugi::xml_node>* children) {
  for (const pugi::xml_node child : node.children()) {
    if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata)
      return at_.Error(node,
                       "unexpected text inside " + Describe(node) + "; expected only elements");
    if (child.type() != pugi::node_element) continue;
    const std::string_view tag = child.name();
    PropertyType type;
    if (PropertyTypeOf(tag, &type)) {
      PTLAB_RETURN_IF_ERROR(props->Add(child));
    } else if (std::any_of(allowed.begin(), allowed.end(),
                           [&](const char* a) { return tag == a; })) {
      children->push_back(child);
    } else {
      const std::string expected =
          "expected a property (boolean, integer, float, string, point, vector, color, "
          "transform)" +
          (allowed.empty() ? std::string() : " or one of the elements " + JoinNames(allowed));
      if (tag == "test")
        return at_.Error(child,
                         "<test> elements (Nori t-tests and chi-square tests) are not "
                         "supported yet");
      if (IsObjectTag(tag))
        return at_.Error(child, "<" + std::string(tag) + "> is not allowed inside " +
                                    Describe(node) + "; " + expected);
      return at_.Error(child, "unknown tag <" + std::string(tag) + ">; " + expected);
    }
  }
  return Status::Ok();
}

Status SceneParser::CollectLeafObject(const pugi::xml_node& node, PropertyList* props) {
  PTLAB_RETURN_IF_ERROR(CheckAttributes(at_, node, {"type"}));
  std::vector<pugi::xml_node> none;
  return Collect(node, {}, props, &none);
}

Status SceneParser::TakeSingleton(const pugi::xml_node& node, pugi::xml_node* slot) {
  if (*slot)
    return at_.Error(node, "a second <" + std::string(node.name()) +
                               ">; expected at most one (the first is at line " +
                               std::to_string(at_.Line(*slot)) + ")");
  *slot = node;
  return Status::Ok();
}

Status SceneParser::ParseScene(const pugi::xml_node& node) {
  PTLAB_RETURN_IF_ERROR(CheckAttributes(at_, node, {}));
  PropertyList props(&at_, node);
  std::vector<pugi::xml_node> children;
  PTLAB_RETURN_IF_ERROR(
      Collect(node, {"mesh", "shape", "camera", "sampler", "integrator", "emitter", "rfilter"},
              &props, &children));
  PTLAB_RETURN_IF_ERROR(props.Expect({}));
  pugi::xml_node sampler;
  for (const pugi::xml_node child : children) {
    const std::string_view tag = child.name();
    if (tag == "mesh" || tag == "shape") {
      PTLAB_RETURN_IF_ERROR(ParseShape(child));
    } else if (tag == "camera") {
      PTLAB_RETURN_IF_ERROR(TakeSingleton(child, &camera_));
      PTLAB_RETURN_IF_ERROR(ParseCamera(child));
    } else if (tag == "sampler") {
      PTLAB_RETURN_IF_ERROR(TakeSingleton(child, &sampler));
      PTLAB_RETURN_IF_ERROR(ParseSampler(child));
    } else if (tag == "integrator") {
      PTLAB_RETURN_IF_ERROR(TakeSingleton(child, &integrator_));
      PTLAB_RETURN_IF_ERROR(ParseIntegrator(child));
    } else if (tag == "rfilter") {
      PTLAB_RETURN_IF_ERROR(ParseFilter(child));
    } else {
      PTLAB_RETURN_IF_ERROR(ParseSceneEmitter(child));
    }
  }
  if (!camera_) return at_.Error(node, "no <camera> in the scene; expected one");
  if (!integrator_) return at_.Error(node, "no <integrator> in the scene; expected one");
  return Status::Ok();
}

std::string SceneParser::Resolve(const std::string& filename) const {
  const std::filesystem::path p(filename);
  if (p.is_absolute() || base_dir_.empty()) return p.lexically_normal().string();
  return (std::filesystem::path(base_dir_) / p).lexically_normal().string();
}

Status SceneParser::CheckColor(PropertyList& props, const char* name, const Color3f& c, Range range) {
  const float max = range == Range::kUnit ? 1.0f : kMaxRadiance;
  if (c.r >= 0 && c.g >= 0 && c.b >= 0 && c.r <= max && c.g <= max && c.b <= max)
    return Status::Ok();
  return props.Error(name, std::string("'") + name + "' = (" + FormatColor(c) +
                               ") is out of range; expected components " +
                               (range == Range::kUnit ? "in [0, 1]" : "in [0, 1e20]"));
}

Status SceneParser::CheckPositive(PropertyList& props, const char* name, float v) {
  if (v > 0) return Status::Ok();
  return props.Error(name, std::string("'") + name + "' = " + FormatNumber(v) +
                               " is out of range; expected a value > 0");
}

Status SceneParser::ParseCamera(const pugi::xml_node& node) {
  PTLAB_RETURN_IF_ERROR(CheckAttributes(at_, node, {"type"}));
  PropertyList props(&at_, node);
  std::vector<pugi::xml_node> children;
  PTLAB_RETURN_IF_ERROR(Collect(node, {"rfilter"}, &props, &children));
  const std::string type = node.attribute("type").value();
  CameraDesc camera;
  if (type == "perspective") {
    PTLAB_RETURN_IF_ERROR(
        props.Expect({"fov", "width", "height", "nearClip", "farClip", "toWorld"}));
  } else if (type == "thinlens") {
    PTLAB_RETURN_IF_ERROR(props.Expect({"fov", "width", "height", "nearClip", "farClip",
                                        "toWorld", "apertureRadius", "focusDistance"}));
    PTLAB_RETURN_IF_ERROR(props.Require("apertureRadius", "float"));
    PTLAB_RETURN_IF_ERROR(props.Require("focusDistance", "float"));
    PTLAB_RETURN_IF_ERROR(props.Float("apertureRadius", &camera.aperture_radius));
    PTLAB_RETURN_IF_ERROR(props.Float("focusDistance", &camera.focus_distance));
    if (!(camera.aperture_radius >= 0))  // 0 is a pinhole
      return props.Error("apertureRadius", "'apertureRadius' = " +
                                               FormatNumber(camera.aperture_radius) +
                                               " is out of range; expected a value >= 0");
    PTLAB_RETURN_IF_ERROR(CheckPositive(props, "focusDistance", camera.focus_distance));
  } else {
    return at_.Error(node,
                     "unknown camera type '" + type + "'; expected perspective or thinlens");
  }
  PTLAB_RETURN_IF_ERROR(props.Float("fov", &camera.fov_deg));
  PTLAB_RETURN_IF_ERROR(props.Integer("width", &camera.width));
  PTLAB_RETURN_IF_ERROR(props.Integer("height", &camera.height));
  PTLAB_RETURN_IF_ERROR(props.Float("nearClip", &camera.near_clip));
  PTLAB_RETURN_IF_ERROR(props.Float("farClip", &camera.far_clip));
  PTLAB_RETURN_IF_ERROR(props.TransformProperty("toWorld", &camera.camera_to_world));
  if (!(camera.fov_deg > 0 && camera.fov_deg < 180))
    return props.Error("fov", "fov = " + FormatNumber(camera.fov_deg) +
                                  " is out of range; expected degrees in (0, 180)");
  if (camera.width < 1) return props.Error("width", "width must be >= 1 pixel");
  if (camera.height < 1) return props.Error("height", "height must be >= 1 pixel");
  if (const std::string size = FilmSizeError(camera.width, camera.height); !size.empty())
    return props.Error(camera.width > kMaxFilmSide || camera.height <= kMaxFilmSide ? "width"
                                                                                      : "height",
                       size);
  PTLAB_RETURN_IF_ERROR(CheckPositive(props, "nearClip", camera.near_clip));
  if (!(camera.far_clip > camera.near_clip))
    return props.Error("farClip", "farClip must be > nearClip");
  scene_.camera = camera;
  for (const pugi::xml_node child : children) PTLAB_RETURN_IF_ERROR(ParseFilter(child));
  return Status::Ok();
}

Status SceneParser::ParseFilter(const pugi::xml_node& node) {
  PTLAB_RETURN_IF_ERROR(TakeSingleton(node, &filter_));
  PropertyList props(&at_, node);
  PTLAB_RETURN_IF_ERROR(CollectLeafObject(node, &props));
  const std::string type = node.attribute("type").value();
  FilterDesc filter;
  if (type == "gaussian") {
    PTLAB_RETURN_IF_ERROR(props.Expect({"radius", "stddev"}));
    filter.type = FilterDesc::Type::kGaussian;
    filter.radius = 2.0f;
    filter.stddev = 0.5f;
    PTLAB_RETURN_IF_ERROR(props.Float("stddev", &filter.stddev));
    PTLAB_RETURN_IF_ERROR(CheckPositive(props, "stddev", filter.stddev));
  } else if (type == "box" || type == "tent") {
    PTLAB_RETURN_IF_ERROR(props.Expect({"radius"}));
    filter.type = type == "box" ? FilterDesc::Type::kBox : FilterDesc::Type::kTent;
    filter.radius = type == "box" ? 0.5f : 1.0f;  // Nori's fixed radii
  } else {
    return at_.Error(node, "unknown rfilter type '" + type + "'; expected gaussian, box or tent");
  }
  PTLAB_RETURN_IF_ERROR(props.Float("radius", &filter.radius));
  PTLAB_RETURN_IF_ERROR(CheckPositive(props, "radius", filter.radius));
  if (!(filter.radius <= kMaxFilterRadius))
    return props.Error("radius", "radius = " + FormatNumber(filter.radius) +
                                     " is out of range; expected a filter radius in (0, " +
                                     FormatNumber(kMaxFilterRadius) + "] pixels");
  scene_.filter = filter;
  return Status::Ok();
}

Status SceneParser::ParseSampler(const pugi::xml_node& node) {
  PropertyList props(&at_, node);
  PTLAB_RETURN_IF_ERROR(CollectLeafObject(node, &props));
  const std::string type = node.attribute("type").value();
  if (!SamplerTypeFromName(type, &scene_.sampler.type))
    return at_.Error(node, "unknown sampler type '" + type + "'; expected independent or sobol");
  PTLAB_RETURN_IF_ERROR(props.Expect({"sampleCount"}));
  int count = 1;
  PTLAB_RETURN_IF_ERROR(props.Integer("sampleCount", &count));
  if (count < 1 || count > kMaxSampleCount)
    return props.Error("sampleCount", "sampleCount " + std::to_string(count) +
                                          " is out of range; expected 1.." +
                                          std::to_string(kMaxSampleCount) + " (as -s)");
  scene_.sampler.sample_count = uint32_t(count);
  return Status::Ok();
}

Status SceneParser::ParseIntegrator(const pugi::xml_node& node) {
  PropertyList props(&at_, node);
  PTLAB_RETURN_IF_ERROR(CollectLeafObject(node, &props));
  const std::string type = node.attribute("type").value();
  using Type = IntegratorDesc::Type;
  struct Kind {
    const char* name;
    Type type;
    bool depth, light_samples, heuristic;
  };
  static constexpr Kind kKinds[] = {
      {"normals", Type::kNormals, false, false, false},
      {"direct_ems", Type::kDirectEms, false, true, false},
      {"direct_mats", Type::kDirectMats, false, false, false},
      {"direct_mis", Type::kDirectMis, false, true, true},
      {"whitted", Type::kWhitted, true, false, false},
      {"path_mats", Type::kPathMats, true, false, false},
      {"path_ems", Type::kPathEms, true, true, false},
      {"path_mis", Type::kPathMis, true, true, true},
      {"bdpt", Type::kBdpt, true, false, true},
      {"ptracer", Type::kPtracer, true, false, false},
  };
  const Kind* kind = nullptr;
  for (const Kind& k : kKinds)
    if (type == k.name) kind = &k;
  if (!kind)
    return at_.Error(node, "unknown integrator type '" + type +
                               "'; expected normals, direct_ems, direct_mats, direct_mis, "
                               "whitted, path_mats, path_ems, path_mis, bdpt or ptracer");
  std::vector<const char*> names;
  if (kind->depth) names.push_back("maxDepth");
  if (kind->light_samples) {
    names.push_back("lightSamples");
    names.push_back("lightSelection");
    names.push_back("triangleSampling");
  }
  if (kind->heuristic) names.push_back("heuristic");
  PTLAB_RETURN_IF_ERROR(props.Expect(std::move(names)));
  IntegratorDesc desc;
  desc.type = kind->type;
  if (kind->depth) {
    PTLAB_RETURN_IF_ERROR(props.Integer("maxDepth", &desc.max_depth));
    if (desc.max_depth < -1)
      return props.Error("maxDepth", "maxDepth must be >= 0, or -1 for unbounded");
  }
  if (kind->light_samples) {
    PTLAB_RETURN_IF_ERROR(props.Integer("lightSamples", &desc.light_samples));
    if (desc.light_samples < 1) return props.Error("lightSamples", "lightSamples must be >= 1");
    std::string selection = "power", triangles = "area";
    PTLAB_RETURN_IF_ERROR(props.String("lightSelection", &selection));
    if (selection != "uniform" && selection != "power")
      return props.Error("lightSelection", "unknown light selection '" + selection +
                                               "'; expected uniform or power");
    desc.light_selection =
        selection == "power" ? LightSelection::kPower : LightSelection::kUniform;
    PTLAB_RETURN_IF_ERROR(props.String("triangleSampling", &triangles));
    if (triangles != "area" && triangles != "solidAngle")
      return props.Error("triangleSampling", "unknown triangle sampling '" + triangles +
                                                 "'; expected area or solidAngle");
    desc.triangle_sampling =
        triangles == "area" ? TriangleSampling::kArea : TriangleSampling::kSolidAngle;
  }
  if (kind->heuristic) {
    // bdpt combines many strategies, where the power heuristic is Veach's recommendation.
    std::string heuristic = kind->type == Type::kBdpt ? "power" : "balance";
    PTLAB_RETURN_IF_ERROR(props.String("heuristic", &heuristic));
    if (heuristic != "balance" && heuristic != "power")
      return props.Error("heuristic",
                         "unknown heuristic '" + heuristic + "'; expected balance or power");
    desc.power_heuristic = heuristic == "power";
  }
  scene_.integrator = desc;
  return Status::Ok();
}

}  // namespace internal

using internal::Locator;
using internal::SceneParser;


StatusOr<Scene> LoadSceneFromString(const std::string& xml, const std::string& base_dir,
                                    const std::string& display_name,
                                    const LoadOptions& options) {
  const Locator at(xml, display_name, options);
  pugi::xml_document doc;
  const pugi::xml_parse_result result =
      doc.load_buffer(xml.data(), xml.size(), pugi::parse_default, pugi::encoding_utf8);
  if (result.status == pugi::status_no_document_element)
    return Status::Error(at.AtOffset(0) + ": no root element; expected a <scene> element");
  if (!result)
    return Status::Error(at.AtOffset(result.offset) +
                         ": XML syntax error: " + result.description());
  SceneParser parser(&at, base_dir);
  parser.set_input_bytes(xml.size());
  PTLAB_RETURN_IF_ERROR(parser.ParseRoot(doc));
  Scene scene = parser.TakeScene();
  scene.source_path = display_name;
  FinalizeAreaLights(&scene);
  return scene;
}

StatusOr<Scene> LoadScene(const std::string& path, const LoadOptions& options) {
  std::string xml;
  PTLAB_RETURN_IF_ERROR(ReadTextFile(path, "scene file", &xml));
  StatusOr<Scene> scene = LoadSceneFromString(
      xml, std::filesystem::path(path).parent_path().string(), path, options);
  if (scene.ok()) scene->input_files.insert(scene->input_files.begin(), path);
  return scene;
}

namespace internal {

StatusOr<Scene> ParseSceneElement(const std::string& xml, const pugi::xml_node& node,
                                  const std::string& base_dir, const std::string& display_name,
                                  const LoadOptions& options) {
  const Locator at(xml, display_name, options);
  SceneParser parser(&at, base_dir);
  parser.set_input_bytes(xml.size());
  PTLAB_RETURN_IF_ERROR(parser.ParseSceneElement(node));
  Scene scene = parser.TakeScene();
  scene.source_path = display_name;
  FinalizeAreaLights(&scene);
  return scene;
}

StatusOr<ParsedBsdfs> ParseBsdfElements(const std::string& xml,
                                        const std::vector<pugi::xml_node>& nodes,
                                        const std::string& display_name) {
  const Locator at(xml, display_name, LoadOptions{});
  SceneParser parser(&at, "");
  ParsedBsdfs parsed;
  for (const pugi::xml_node& node : nodes) {
    StatusOr<MaterialRef> ref = parser.ParseBsdfElement(node);
    if (!ref.ok()) return ref.status();
    parsed.refs.push_back(*ref);
  }
  parsed.materials = std::move(parser.TakeScene().materials);
  return parsed;
}

}  // namespace internal
}  // namespace ptlab
