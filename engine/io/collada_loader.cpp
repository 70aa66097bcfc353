// COLLADA scene assembly: the visual scene's node tree instancing geometry, lights and a camera.
#include "engine/io/collada_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <pugixml.hpp>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/core/memory_budget.h"
#include "engine/core/parse_number.h"
#include "engine/io/collada_document.h"
#include "engine/io/collada_effect.h"
#include "engine/io/collada_mesh.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/light/distant_disk.h"
#include "engine/io/mesh_builder.h"
#include "engine/scene/scene_limits.h"
#include "engine/io/shapes.h"
#include "engine/io/text_parsing.h"
#include "engine/io/xml_locator.h"

namespace ptlab {
namespace {

using collada::Document;

// CS184's pathtracer defaults (its AppConfig): 1 sample per pixel, max ray depth 1, 1 sample
// per area light; the film CS184 students render at is 480 pixels wide.
constexpr int kDefaultFilmWidth = 480;
constexpr float kCs184FocalDistance = 4.7f;  // pathtracer -d default
constexpr float kHuge = 3.0e38f;
// A spot's cos(θ)^e falls to 1/e at 1 - cos θ ≈ 1/e: beyond this exponent that is under
// ~1,000 float steps of cos θ below 1, a beam float cannot render faithfully.
constexpr float kMaxFalloffExponent = 1.0e4f;

// A light of <library_lights> as CS184 reads it (directional and spot lights as COLLADA
// defines them: CS184 reads no spot light).
struct LightDesc {
  enum class Kind { kPoint, kAmbient, kArea, kDirectional, kSpot };
  Kind kind = Kind::kPoint;
  Color3f color;
  float falloff_angle = 180.0f;   // spot: the full cone angle, degrees (COLLADA's default)
  float falloff_exponent = 0.0f;  // spot: the cos θ exponent (COLLADA's default)
};

std::string Name(const pugi::xml_node& node) {
  if (const char* id = node.attribute("id").value(); *id) return id;
  return node.attribute("name").value();
}

Vec3f ApplyPoint(const Matrix4& m, const Vec3f& p) {
  return {m.m[0][0] * p.x + m.m[0][1] * p.y + m.m[0][2] * p.z + m.m[0][3],
          m.m[1][0] * p.x + m.m[1][1] * p.y + m.m[1][2] * p.z + m.m[1][3],
          m.m[2][0] * p.x + m.m[2][1] * p.y + m.m[2][2] * p.z + m.m[2][3]};
}
Vec3f ApplyVector(const Matrix4& m, const Vec3f& v) {
  return ApplyPoint(m, v) - ApplyPoint(m, {0, 0, 0});
}

// True when the upper 3x3 of m is a rotation (or reflection) times one scale factor > 0, which
// it stores in *scale: its columns are orthogonal and of one length, to float precision.
bool UniformScale(const Matrix4& m, float* scale) {
  const Vec3f c[3] = {{m.m[0][0], m.m[1][0], m.m[2][0]},
                      {m.m[0][1], m.m[1][1], m.m[2][1]},
                      {m.m[0][2], m.m[1][2], m.m[2][2]}};
  const float l = Length(c[0]);
  if (!(l > 0) || !std::isfinite(l)) return false;
  constexpr float kTolerance = 1e-5f;
  for (int i = 0; i < 3; ++i) {
    if (!(std::fabs(Length(c[i]) - l) <= kTolerance * l)) return false;
    if (!(std::fabs(Dot(c[i], c[(i + 1) % 3])) <= kTolerance * l * l)) return false;
  }
  *scale = l;
  return true;
}

Matrix4 Columns(const Vec3f& x, const Vec3f& y, const Vec3f& z, const Vec3f& p) {
  Matrix4 m;
  const Vec3f c[4] = {x, y, z, p};
  for (int j = 0; j < 4; ++j) m.m[0][j] = c[j].x, m.m[1][j] = c[j].y, m.m[2][j] = c[j].z;
  return m;
}

// Deepest nesting of nodes read (through <node> children and <instance_node>s): the node
// reader recurses once a level, and ~10,000 levels overflowed its stack.
constexpr size_t kMaxNodeDepth = 256;

class ColladaReader {
 public:
  // `input_bytes`: the file's size, which bounds what its instances may expand into by default.
  ColladaReader(const Document& doc, uint64_t input_bytes)
      : doc_(doc), input_bytes_(input_bytes) {}

  Status Read(const pugi::xml_node& root) {
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(
        root,
        {"asset", "library_cameras", "library_lights", "library_images", "library_effects",
         "library_materials", "library_geometries", "library_controllers", "library_nodes",
         "library_visual_scenes", "scene"},
        /*extras=*/true));
    const std::string_view version = root.attribute("version").value();
    if (version != "1.4.1" && version != "1.4.0")
      return doc_.NotSupported(root, std::string("COLLADA version \"") + std::string(version) +
                                         "\"; expected 1.4.1");
    PTLAB_RETURN_IF_ERROR(ReadAsset(root.child("asset")));
    for (const char* empty : {"library_images", "library_controllers"})
      for (const pugi::xml_node lib : root.children(empty))
        PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(lib, {}, /*extras=*/true));
    PTLAB_RETURN_IF_ERROR(ReadLibraries(root));

    const pugi::xml_node scene = root.child("scene");
    if (!scene) return doc_.Error(root, "no <scene>; expected <scene><instance_visual_scene>");
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(scene, {"instance_visual_scene"}, true));
    const pugi::xml_node instance = scene.child("instance_visual_scene");
    if (!instance) return doc_.Error(scene, "<scene> has no <instance_visual_scene>");
    pugi::xml_node visual;
    PTLAB_RETURN_IF_ERROR(doc_.Resolve(instance, "url", "visual_scene", &visual));
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(visual, {"node", "asset"}, true));
    // Count what the node tree instances before expanding any of it: a few kilobytes of
    // <instance_node>s can multiply into billions of triangles.
    uint64_t primitives = 0;
    for (const pugi::xml_node node : visual.children("node")) {
      uint64_t n = 0;
      PTLAB_RETURN_IF_ERROR(CountInstances(node, 0, &n));
      primitives = SaturatingAdd(primitives, n);
    }
    const std::string over = OverExpansionBudget(
        double(primitives) * double(kSceneBytesPerTriangle), input_bytes_,
        "the visual scene instances " + std::to_string(primitives) +
            (primitives == kCountSaturated ? "+" : "") +
            " triangles and spheres (through its <instance_node>s), which");
    if (!over.empty()) return doc_.Error(visual, over);
    std::vector<pugi::xml_node> path;
    for (const pugi::xml_node node : visual.children("node"))
      PTLAB_RETURN_IF_ERROR(ReadNode(node, global_, &path));
    if (!camera_)
      return doc_.Error(visual, "the visual scene instances no camera; expected one "
                                "<instance_camera>");
    PTLAB_RETURN_IF_ERROR(PlaceCamera(visual));
    FinalizeAreaLights(&scene_);
    return Status::Ok();
  }

  Scene TakeScene() { return std::move(scene_); }

 private:
  // CS184 keeps only the direction of the file's camera: its Application::load aims it at the
  // centre of the bounding box of the scene's objects (lights excluded) from 1.5 times the
  // box's diagonal, with world +y up (the view direction's tilt is kept; the up vector of the
  // file is used only when the view is vertical).
  Status PlaceCamera(const pugi::xml_node& visual) {
    if (!(bounds_max_.x >= bounds_min_.x))
      return doc_.Error(visual, "the visual scene has no geometry to aim the camera at");
    const Vec3f target = (bounds_min_ + bounds_max_) * 0.5f;
    const float distance = 1.5f * Length(bounds_max_ - bounds_min_);
    const Vec3f f = view_dir_;
    Vec3f left = Cross(Vec3f{0, 1, 0}, f);
    if (!(Length(left) > 1e-6f)) left = Cross(view_up_, f);
    if (!(Length(left) > 1e-6f))
      return doc_.Error(camera_, "the camera looks straight up or down and its node gives no "
                                 "up direction");
    left = Normalize(left);
    const Vec3f origin = target - f * distance;
    const Matrix4 m = Columns(left, Cross(f, left), f, origin);
    Matrix4 inv;
    if (!Inverse(m, &inv)) return doc_.Error(camera_, "the camera frame is singular");
    scene_.camera.camera_to_world = Transform(m, inv);
    scene_.camera.focus_distance = kCs184FocalDistance;
    return Status::Ok();
  }

  void ExpandBounds(uint32_t first_triangle) {
    const TriangleTable& tri = scene_.triangles;
    for (uint32_t t = first_triangle; t < tri.size(); ++t)
      for (const Vec3f& v : {tri.V0(t), tri.V1(t), tri.V2(t)}) ExpandBoundsTo(v);
  }
  void ExpandBoundsTo(const Vec3f& v) {
    bounds_min_ = {std::min(bounds_min_.x, v.x), std::min(bounds_min_.y, v.y),
                   std::min(bounds_min_.z, v.z)};
    bounds_max_ = {std::max(bounds_max_.x, v.x), std::max(bounds_max_.y, v.y),
                   std::max(bounds_max_.z, v.z)};
  }

  // <unit meter> and <up_axis>: world = rotate(up axis to +y) · scale(meter).
  Status ReadAsset(const pugi::xml_node& asset) {
    if (!asset) return Status::Ok();
    float meter = 1;
    if (const pugi::xml_node unit = asset.child("unit")) {
      if (const pugi::xml_attribute m = unit.attribute("meter")) {
        if (!ParseFloat(m.value(), &meter) || !(meter > 0))
          return doc_.Error(unit, std::string("<unit> meter=\"") + std::string(m.value()) +
                                      "\" is not a number > 0");
      }
    }
    Matrix4 up;
    if (const pugi::xml_node axis = asset.child("up_axis")) {
      const std::string_view text = axis.child_value();
      // COLLADA 1.4.1 §5 <up_axis>: X_UP has right = -y, up = +x; Z_UP has up = +z, in = -y.
      if (text == "X_UP") {
        up.m[0][0] = 0, up.m[0][1] = -1, up.m[1][0] = 1, up.m[1][1] = 0;
      } else if (text == "Z_UP") {
        up.m[1][1] = 0, up.m[1][2] = 1, up.m[2][1] = -1, up.m[2][2] = 0;
      } else if (text != "Y_UP") {
        return doc_.Error(axis, std::string("<up_axis> \"") + std::string(text) +
                                    "\"; expected X_UP, Y_UP or Z_UP");
      }
    }
    global_ = up * Transform::Scale({meter, meter, meter}).matrix();
    return Status::Ok();
  }

  // Every effect, material, geometry, light and camera is read (and checked) up front, used
  // or not, so that nothing in a file is silently skipped.
  Status ReadLibraries(const pugi::xml_node& root) {
    for (const pugi::xml_node lib : root.children("library_effects")) {
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(lib, {"effect", "asset"}, true));
      for (const pugi::xml_node effect : lib.children("effect")) {
        StatusOr<collada::Effect> e = collada::ReadEffect(doc_, effect);
        if (!e.ok()) return e.status();
        effects_.emplace(effect.offset_debug(), std::move(*e));
      }
    }
    for (const pugi::xml_node lib : root.children("library_materials")) {
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(lib, {"material", "asset"}, true));
      for (const pugi::xml_node material : lib.children("material")) {
        PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(material, {"instance_effect", "asset"}, true));
        const pugi::xml_node instance = material.child("instance_effect");
        if (!instance) return doc_.Error(material, "<material> has no <instance_effect>");
        PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(instance, {}, true));
        pugi::xml_node effect;
        PTLAB_RETURN_IF_ERROR(doc_.Resolve(instance, "url", "effect", &effect));
        effect_of_material_[material.offset_debug()] = effect.offset_debug();
      }
    }
    for (const pugi::xml_node lib : root.children("library_geometries")) {
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(lib, {"geometry", "asset"}, true));
      for (const pugi::xml_node geometry : lib.children("geometry")) {
        StatusOr<collada::Geometry> g = collada::ReadGeometry(doc_, geometry);
        if (!g.ok()) return g.status();
        geometries_.emplace(geometry.offset_debug(), std::move(*g));
      }
    }
    for (const pugi::xml_node lib : root.children("library_lights")) {
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(lib, {"light", "asset"}, true));
      for (const pugi::xml_node light : lib.children("light")) {
        LightDesc desc;
        PTLAB_RETURN_IF_ERROR(ReadLight(light, &desc));
        lights_.emplace(light.offset_debug(), desc);
      }
    }
    for (const pugi::xml_node lib : root.children("library_cameras")) {
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(lib, {"camera", "asset"}, true));
      for (const pugi::xml_node camera : lib.children("camera")) {
        CameraDesc desc;
        PTLAB_RETURN_IF_ERROR(ReadCamera(camera, &desc));
        cameras_.emplace(camera.offset_debug(), desc);
      }
    }
    for (const pugi::xml_node lib : root.children("library_nodes"))
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(lib, {"node", "asset"}, true));
    return Status::Ok();
  }

  Status ReadLight(const pugi::xml_node& light, LightDesc* desc) {
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(light, {"technique_common", "asset"}, true));
    const pugi::xml_node common = light.child("technique_common");
    if (!common) return doc_.Error(light, "<light> has no <technique_common>");
    PTLAB_RETURN_IF_ERROR(
        doc_.CheckChildren(common, {"ambient", "directional", "point", "spot"}));
    pugi::xml_node kind;
    for (const pugi::xml_node child : common.children())
      if (child.type() == pugi::node_element) {
        if (kind) return doc_.Error(child, "a second light type in <technique_common>");
        kind = child;
      }
    if (!kind) return doc_.Error(common, "<technique_common> names no light type");
    // The CGL <area> extra makes the light a CS184 area light, whatever the common type.
    if (const pugi::xml_node cgl = doc_.CglTechnique(light)) {
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(cgl, {"area"}));
      const pugi::xml_node area = cgl.child("area");
      if (!area) return doc_.Error(cgl, "the CGL technique of a light has no <area>");
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(area, {"color"}));
      if (!area.child("color")) return doc_.Error(area, "<area> has no <color>");
      desc->kind = LightDesc::Kind::kArea;
      PTLAB_RETURN_IF_ERROR(doc_.Color(area.child("color"), &desc->color));
      return CheckRadiance(area.child("color"), desc->color);
    }
    const std::string_view type = kind.name();
    // CS184 reads the attenuation factors but its lights do not use them; neither does ptlab.
    const bool attenuated = type == "point" || type == "spot";
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(
        kind,
        type == "spot"
            ? std::initializer_list<std::string_view>{"color", "constant_attenuation",
                                                      "linear_attenuation", "quadratic_attenuation",
                                                      "falloff_angle", "falloff_exponent"}
        : attenuated
            ? std::initializer_list<std::string_view>{"color", "constant_attenuation",
                                                      "linear_attenuation", "quadratic_attenuation"}
            : std::initializer_list<std::string_view>{"color"}));
    if (!kind.child("color")) return doc_.Error(kind, std::string("<") + std::string(type) + "> has no <color>");
    desc->kind = type == "point"         ? LightDesc::Kind::kPoint
                 : type == "spot"        ? LightDesc::Kind::kSpot
                 : type == "directional" ? LightDesc::Kind::kDirectional
                                         : LightDesc::Kind::kAmbient;
    PTLAB_RETURN_IF_ERROR(doc_.Color(kind.child("color"), &desc->color));
    if (desc->kind == LightDesc::Kind::kSpot) PTLAB_RETURN_IF_ERROR(ReadSpotFalloff(kind, desc));
    return CheckRadiance(kind.child("color"), desc->color);
  }

  Status ReadSpotFalloff(const pugi::xml_node& spot, LightDesc* desc) const {
    PTLAB_RETURN_IF_ERROR(doc_.OptionalFloat(spot, "falloff_angle", &desc->falloff_angle));
    PTLAB_RETURN_IF_ERROR(doc_.OptionalFloat(spot, "falloff_exponent", &desc->falloff_exponent));
    if (!(desc->falloff_angle > 0 && desc->falloff_angle <= 180))
      return doc_.Error(spot.child("falloff_angle"),
                        "falloff_angle is out of range; expected the full cone angle in degrees, "
                        "in (0, 180]");
    if (!(desc->falloff_exponent >= 0 && desc->falloff_exponent <= kMaxFalloffExponent))
      return doc_.Error(spot.child("falloff_exponent"),
                        "falloff_exponent is out of range; expected a number in [0, " +
                            std::to_string(int(kMaxFalloffExponent)) + "]");
    return Status::Ok();
  }

  Status CheckRadiance(const pugi::xml_node& node, const Color3f& c) const {
    if (!(MaxComponent(c) <= kMaxRadiance))
      return doc_.Error(node, "a light color above " + std::to_string(kMaxRadiance));
    return Status::Ok();
  }

  Status ReadCamera(const pugi::xml_node& camera, CameraDesc* desc) {
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(camera, {"optics", "asset"}, true));
    const pugi::xml_node optics = camera.child("optics");
    if (!optics) return doc_.Error(camera, "<camera> has no <optics>");
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(optics, {"technique_common"}, true));
    const pugi::xml_node common = optics.child("technique_common");
    if (!common) return doc_.Error(optics, "<optics> has no <technique_common>");
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(common, {"perspective"}));
    const pugi::xml_node p = common.child("perspective");
    if (!p) return doc_.Error(common, "<technique_common> has no <perspective>");
    PTLAB_RETURN_IF_ERROR(
        doc_.CheckChildren(p, {"xfov", "yfov", "aspect_ratio", "znear", "zfar"}));
    float xfov = 0, yfov = 0, aspect = 0, znear = 0.001f, zfar = 1000.0f;
    PTLAB_RETURN_IF_ERROR(doc_.OptionalFloat(p, "xfov", &xfov));
    PTLAB_RETURN_IF_ERROR(doc_.OptionalFloat(p, "yfov", &yfov));
    PTLAB_RETURN_IF_ERROR(doc_.OptionalFloat(p, "aspect_ratio", &aspect));
    PTLAB_RETURN_IF_ERROR(doc_.OptionalFloat(p, "znear", &znear));
    PTLAB_RETURN_IF_ERROR(doc_.OptionalFloat(p, "zfar", &zfar));
    for (const char* name : {"xfov", "yfov"})
      if (p.child(name)) {
        const float v = std::string_view(name) == "xfov" ? xfov : yfov;
        if (!(v > 0 && v < 180))
          return doc_.Error(p.child(name), std::string(name) + " is out of range; expected "
                                                               "degrees in (0, 180)");
      }
    if (p.child("aspect_ratio") && !(aspect > 0))
      return doc_.Error(p.child("aspect_ratio"), "aspect_ratio must be > 0");
    const auto tan_half = [](float deg) { return std::tan(deg * kPi / 360.0f); };
    const bool has_x = p.child("xfov"), has_y = p.child("yfov"), has_a = p.child("aspect_ratio");
    if (has_x && has_y) aspect = tan_half(xfov) / tan_half(yfov);
    else if (has_y && has_a) xfov = 2.0f * std::atan(tan_half(yfov) * aspect) * 180.0f / kPi;
    else if (!(has_x && has_a))
      return doc_.Error(p, "<perspective> needs xfov or yfov with aspect_ratio, or both "
                           "xfov and yfov");
    if (!(znear > 0) || !(zfar > znear))
      return doc_.Error(p, "expected 0 < znear < zfar");
    desc->fov_deg = xfov;
    desc->width = kDefaultFilmWidth;
    desc->height = std::max(1, int(std::lround(kDefaultFilmWidth / aspect)));
    if (const std::string size = FilmSizeError(desc->width, desc->height); !size.empty())
      return doc_.Error(p, "aspect_ratio gives a film of " + size);
    desc->near_clip = znear;
    desc->far_clip = zfar;
    desc->keep_vertical_fov = true;
    return Status::Ok();
  }

  // The node's own transform: its matrix/translate/rotate/scale children in document order.
  Status LocalTransform(const pugi::xml_node& node, Matrix4* local) {
    *local = Matrix4::Identity();
    // A node holding only a camera instance (its transform reaches nothing else).
    bool camera_only = bool(node.child("instance_camera"));
    for (const char* other : {"node", "instance_node", "instance_geometry", "instance_light"})
      camera_only = camera_only && !node.child(other);
    for (const pugi::xml_node child : node.children()) {
      if (child.type() != pugi::node_element) continue;
      const std::string_view name = child.name();
      Matrix4 t;
      if (name == "matrix") {
        std::vector<float> v;
        PTLAB_RETURN_IF_ERROR(doc_.Floats(child, &v));
        if (v.size() < 16 && v.size() >= 12 && camera_only) {
          // CBgems.dae's camera matrix lacks a number. CS184 reads the missing ones as 0 and
          // keeps only the camera's view direction (the upper 3x3), so ptlab does the same.
          scene_.load_warnings.push_back(
              doc_.at.At(child) + ": <matrix> holds " + std::to_string(v.size()) +
              " numbers; expected 16. Read as CS184 does: the missing ones are 0 and only the "
              "camera's view direction is used");
          v.resize(16, 0.0f);
          v[15] = 1.0f;
          v[12] = v[13] = v[14] = 0.0f;
        }
        if (v.size() != 16)
          return doc_.Error(child, "<matrix> holds " + std::to_string(v.size()) +
                                       " numbers; expected 16");
        for (int i = 0; i < 16; ++i) t.m[i / 4][i % 4] = v[i];
        if (t.m[3][0] != 0 || t.m[3][1] != 0 || t.m[3][2] != 0 || t.m[3][3] != 1)
          return doc_.NotSupported(child, "a projective matrix; expected the last row 0 0 0 1");
      } else if (name == "translate") {
        float v[3];
        PTLAB_RETURN_IF_ERROR(doc_.FixedFloats(child, 3, v));
        t = Transform::Translate({v[0], v[1], v[2]}).matrix();
      } else if (name == "rotate") {
        float v[4];
        PTLAB_RETURN_IF_ERROR(doc_.FixedFloats(child, 4, v));
        if (v[0] == 0 && v[1] == 0 && v[2] == 0)
          return doc_.Error(child, "<rotate> has a zero axis");
        t = Transform::Rotate({v[0], v[1], v[2]}, v[3]).matrix();
      } else if (name == "scale") {
        float v[3];
        PTLAB_RETURN_IF_ERROR(doc_.FixedFloats(child, 3, v));
        // The matrix itself, not Transform::Scale (which inverts it): a zero factor is legal
        // here and an error only where a singular transform matters (meshes, light axes).
        t.m[0][0] = v[0], t.m[1][1] = v[1], t.m[2][2] = v[2];
      } else {
        continue;
      }
      *local = *local * t;
    }
    return Status::Ok();
  }

  static constexpr uint64_t kCountSaturated = UINT64_MAX - 1;
  static constexpr uint64_t kCounting = UINT64_MAX;  // a node whose count is under way
  static uint64_t SaturatingAdd(uint64_t a, uint64_t b) {
    return a > kCountSaturated - b ? kCountSaturated : a + b;
  }

  Status TooDeep(const pugi::xml_node& node) const {
    return doc_.Error(node, "<node>s nested deeper than " + std::to_string(kMaxNodeDepth) +
                                " levels (through <node> and <instance_node>); expected at "
                                "most " + std::to_string(kMaxNodeDepth));
  }

  // The triangles and spheres `node` instances, its subtree and the nodes it instances
  // included; memoised per node, so shared subtrees are counted once however often they are
  // instanced. Cycles and depth are refused here as ReadNode would.
  Status CountInstances(const pugi::xml_node& node, size_t depth, uint64_t* count) {
    if (depth >= kMaxNodeDepth) return TooDeep(node);
    const auto [it, inserted] = counts_.emplace(node.offset_debug(), kCounting);
    if (!inserted) {
      if (it->second == kCounting)
        return doc_.Error(node, "node '" + Name(node) + "' instances itself (a cycle of "
                                "<instance_node>s); expected a tree");
      *count = it->second;
      return Status::Ok();
    }
    uint64_t sum = 0;
    for (const pugi::xml_node child : node.children()) {
      const std::string_view name = child.name();
      uint64_t n = 0;
      if (name == "node") {
        PTLAB_RETURN_IF_ERROR(CountInstances(child, depth + 1, &n));
      } else if (name == "instance_node") {
        pugi::xml_node target;
        PTLAB_RETURN_IF_ERROR(doc_.Resolve(child, "url", "node", &target));
        PTLAB_RETURN_IF_ERROR(CountInstances(target, depth + 1, &n));
      } else if (name == "instance_geometry" || name == "instance_light") {
        n = 1;  // a sphere or a light (an area light: two triangles)
        pugi::xml_node geometry;
        if (name == "instance_geometry" &&
            doc_.Resolve(child, "url", "geometry", &geometry).ok()) {
          const auto g = geometries_.find(geometry.offset_debug());
          if (g != geometries_.end() && !g->second.is_sphere) {
            n = 0;
            for (const collada::MeshPart& part : g->second.parts)
              n = SaturatingAdd(n, part.mesh.triangle_count());
          }
        }
      }
      sum = SaturatingAdd(sum, n);
    }
    counts_[node.offset_debug()] = sum;
    *count = sum;
    return Status::Ok();
  }

  // `path` holds the nodes being read (for cycles through instance_node).
  Status ReadNode(const pugi::xml_node& node, const Matrix4& parent,
                  std::vector<pugi::xml_node>* path) {
    if (path->size() >= kMaxNodeDepth) return TooDeep(node);
    for (const pugi::xml_node& open : *path)
      if (open == node)
        return doc_.Error(node, "node '" + Name(node) + "' instances itself (a cycle of "
                                "<instance_node>s); expected a tree");
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(
        node,
        {"matrix", "translate", "rotate", "scale", "node", "instance_geometry", "instance_light",
         "instance_camera", "instance_node", "asset"},
        /*extras=*/true));
    Matrix4 local;
    PTLAB_RETURN_IF_ERROR(LocalTransform(node, &local));
    const Matrix4 world = parent * local;
    path->push_back(node);
    for (const pugi::xml_node child : node.children()) {
      const std::string_view name = child.name();
      if (name == "node") {
        PTLAB_RETURN_IF_ERROR(ReadNode(child, world, path));
      } else if (name == "instance_node") {
        pugi::xml_node target;
        PTLAB_RETURN_IF_ERROR(doc_.Resolve(child, "url", "node", &target));
        PTLAB_RETURN_IF_ERROR(ReadNode(target, world, path));
      } else if (name == "instance_geometry") {
        PTLAB_RETURN_IF_ERROR(InstanceGeometry(child, world));
      } else if (name == "instance_light") {
        PTLAB_RETURN_IF_ERROR(InstanceLight(child, world));
      } else if (name == "instance_camera") {
        PTLAB_RETURN_IF_ERROR(InstanceCamera(child, world));
      }
    }
    path->pop_back();
    return Status::Ok();
  }

  Status InstanceCamera(const pugi::xml_node& instance, const Matrix4& world) {
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(instance, {}, true));
    if (camera_)
      return doc_.Error(instance, "a second <instance_camera> (first at " + doc_.at.At(camera_) +
                                      "); expected one camera");
    pugi::xml_node camera;
    PTLAB_RETURN_IF_ERROR(doc_.Resolve(instance, "url", "camera", &camera));
    camera_ = instance;
    CameraDesc desc = cameras_.at(camera.offset_debug());
    // COLLADA cameras look down their local -z with +y up; ptlab's camera space looks along +z
    // with +x to the image's left. Scale is dropped: the frame is made orthonormal.
    const Vec3f forward = ApplyVector(world, {0, 0, -1}), up = ApplyVector(world, {0, 1, 0});
    if (!(Length(forward) > 0) || !std::isfinite(Length(forward)) ||
        !std::isfinite(Length(up)))
      return doc_.Error(instance, "the camera's node transform has no view direction");
    view_dir_ = Normalize(forward);
    view_up_ = Length(up) > 0 ? Normalize(up) : Vec3f{0, 0, 0};
    scene_.camera = desc;
    return Status::Ok();
  }

  Status InstanceLight(const pugi::xml_node& instance, const Matrix4& world) {
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(instance, {}, true));
    pugi::xml_node light;
    PTLAB_RETURN_IF_ERROR(doc_.Resolve(instance, "url", "light", &light));
    const LightDesc& desc = lights_.at(light.offset_debug());
    switch (desc.kind) {
      case LightDesc::Kind::kPoint: {
        // CS184's point light has radiant intensity `color` (W/sr); ptlab stores the power.
        PointLightTable& t = scene_.point_lights;
        scene_.emitters.push_back(EmitterRef::Make(EmitterTag::kPoint, uint32_t(t.size())));
        t.position.push_back(ApplyPoint(world, {0, 0, 0}));
        t.power.push_back(desc.color * (4.0f * kPi));
        return Status::Ok();
      }
      case LightDesc::Kind::kDirectional: {
        // COLLADA lights shine down their local -z.
        Vec3f dir;
        PTLAB_RETURN_IF_ERROR(LightAxis(instance, world, &dir));
        DirectionalLightTable& t = scene_.directional_lights;
        scene_.emitters.push_back(EmitterRef::Make(EmitterTag::kDirectional, uint32_t(t.size())));
        t.direction.push_back(dir);
        t.radiance.push_back(desc.color);
        return Status::Ok();
      }
      case LightDesc::Kind::kSpot: {
        Vec3f axis;
        PTLAB_RETURN_IF_ERROR(LightAxis(instance, world, &axis));
        SpotLightTable& t = scene_.spot_lights;
        scene_.emitters.push_back(EmitterRef::Make(EmitterTag::kSpot, uint32_t(t.size())));
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
                                                doc_.at.At(light), &scene_.distant_disks);
        if (!row.ok()) return row.status();
        scene_.emitters.push_back(EmitterRef::Make(EmitterTag::kDistantDisk, *row));
        return Status::Ok();
      }
      case LightDesc::Kind::kArea: {
        // CS184's area light: the unit square [-1/2, 1/2]² of the light's local xy plane,
        // emitting towards local -z (both triangles and normals face -z).
        MeshData quad;
        quad.positions = {{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {-0.5f, 0.5f, 0}};
        quad.normals.assign(4, Vec3f{0, 0, -1});
        quad.indices = {0, 2, 1, 0, 3, 2};
        const MaterialRef black = scene_.materials.AddDiffuse({0, 0, 0});
        uint32_t row = 0;
        PTLAB_RETURN_IF_ERROR(AddWorldMesh(instance, quad, world, black, "area light " +
                                           Name(light), &row));
        AddAreaEmitter(row, desc.color);
        return Status::Ok();
      }
    }
    return Status::Ok();
  }

  // The world direction of a light node's local -z (unit); an error when the node's transform
  // collapses it.
  Status LightAxis(const pugi::xml_node& instance, const Matrix4& world, Vec3f* axis) const {
    const Vec3f d = ApplyVector(world, {0, 0, -1});
    const float length = Length(d);
    if (!(length > 0) || !std::isfinite(length))
      return doc_.Error(instance, "the light's node transform has no direction (local -z)");
    *axis = d / length;
    return Status::Ok();
  }

  void AddAreaEmitter(uint32_t mesh_row, const Color3f& radiance) {
    AttachAreaLight(&scene_, mesh_row, radiance);
  }

  // A CGL sphere of world centre c and radius r as a SphereTable row.
  Status AddAnalyticSphere(const pugi::xml_node& instance, const Vec3f& c, float r,
                           MaterialRef material) {
    if (!(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && r > 0 &&
          std::isfinite(r)))
      return doc_.Error(instance,
                        "the sphere's node transform gives no finite centre and radius > 0");
    // The sphere itself must lie within the scene's coordinates (a radius of 1e20 was only
    // noticed later, as a camera the scene's bounds could not place).
    const float reach = std::max({std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)}) + r;
    if (!(reach <= kMaxWorldCoordinate))
      return doc_.Error(instance, "the sphere (world radius " + FormatLimit(r) + ", centre " +
                                      FormatLimit(c.x) + ", " + FormatLimit(c.y) + ", " +
                                      FormatLimit(c.z) + ") reaches beyond the scene's "
                                      "coordinates [-1e12, 1e12]; expected a smaller radius");
    if (scene_.spheres.size() + 1 >= kMaxSpheres)
      return doc_.Error(instance, "too many spheres; at most " + std::to_string(kMaxSpheres - 1));
    scene_.spheres.Append(c, r, material);
    ExpandBoundsTo(c - Vec3f{r, r, r});
    ExpandBoundsTo(c + Vec3f{r, r, r});
    return Status::Ok();
  }

  // Appends `mesh` through `world` (which must be invertible) and checks its coordinates.
  Status AddWorldMesh(const pugi::xml_node& instance, const MeshData& mesh, const Matrix4& world,
                      MaterialRef material, const std::string& name, uint32_t* row) {
    Matrix4 inv;
    if (!Inverse(world, &inv))
      return doc_.Error(instance, "the node transform of '" + name + "' is singular");
    const uint32_t first = uint32_t(scene_.triangles.size());
    *row = AddMesh(&scene_, mesh, Transform(world, inv), material, name);
    const TriangleTable& tri = scene_.triangles;
    for (uint32_t t = first; t < tri.size(); ++t)
      for (const Vec3f& v : {tri.V0(t), tri.V1(t), tri.V2(t)})
        if (!(std::abs(v.x) <= kMaxWorldCoordinate && std::abs(v.y) <= kMaxWorldCoordinate &&
              std::abs(v.z) <= kMaxWorldCoordinate))
          return doc_.Error(instance, "a world-space vertex of '" + name +
                                          "' lies beyond +-1e12; expected coordinates and "
                                          "transforms that keep it finite and within range");
    return Status::Ok();
  }

  // The ptlab row of a <material> (one per material element) and its emitted radiance.
  Status MaterialOf(const pugi::xml_node& material, MaterialRef* ref, Color3f* radiance) {
    const ptrdiff_t key = material.offset_debug();
    auto it = material_rows_.find(key);
    if (it == material_rows_.end()) {
      const collada::Effect& effect = effects_.at(effect_of_material_.at(key));
      StatusOr<MaterialRef> row = collada::AddEffectMaterial(doc_, effect, &scene_.materials);
      if (!row.ok()) return row.status();
      const Color3f emitted =
          effect.model == collada::Effect::Model::kEmission ? effect.radiance : Color3f{};
      it = material_rows_.emplace(key, std::make_pair(*row, emitted)).first;
    }
    *ref = it->second.first;
    *radiance = it->second.second;
    return Status::Ok();
  }

  Status InstanceGeometry(const pugi::xml_node& instance, const Matrix4& world) {
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(instance, {"bind_material"}, true));
    pugi::xml_node geometry;
    PTLAB_RETURN_IF_ERROR(doc_.Resolve(instance, "url", "geometry", &geometry));
    // bind_material: symbol -> <material>, in order.
    std::vector<std::pair<std::string, pugi::xml_node>> bound;
    const pugi::xml_node bind = instance.child("bind_material");
    if (bind) {
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(bind, {"technique_common"}, true));
      const pugi::xml_node common = bind.child("technique_common");
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(common, {"instance_material"}));
      for (const pugi::xml_node im : common.children("instance_material")) {
        PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(im, {}, true));
        pugi::xml_node material;
        PTLAB_RETURN_IF_ERROR(doc_.Resolve(im, "target", "material", &material));
        bound.emplace_back(im.attribute("symbol").value(), material);
      }
    }
    const collada::Geometry& g = geometries_.at(geometry.offset_debug());
    const std::string name = Name(geometry);
    // CS184 gives a sphere the first bound material; a mesh part the one bound to its symbol.
    const auto material_for = [&](const std::string& symbol, const pugi::xml_node& user,
                                  MaterialRef* ref, Color3f* radiance) -> Status {
      *radiance = {};
      pugi::xml_node material;
      if (g.is_sphere) {
        if (!bound.empty()) material = bound.front().second;
      } else {
        for (const auto& [s, m] : bound)
          if (s == symbol) material = m;
        if (!material && !symbol.empty() && bind)
          return doc_.Error(user, "material symbol '" + symbol + "' is not bound by the "
                                  "<instance_geometry> at " + doc_.at.At(instance));
      }
      if (!material) {
        *ref = scene_.materials.AddDiffuse({0.5f, 0.5f, 0.5f});
        return Status::Ok();
      }
      return MaterialOf(material, ref, radiance);
    };
    const auto add_mesh = [&](const MeshData& mesh, MaterialRef ref,
                              const Color3f& radiance) -> Status {
      uint32_t row = 0;
      const uint32_t first = uint32_t(scene_.triangles.size());
      PTLAB_RETURN_IF_ERROR(AddWorldMesh(instance, mesh, world, ref, name, &row));
      ExpandBounds(first);
      if (!IsBlack(radiance)) AddAreaEmitter(row, radiance);
      return Status::Ok();
    };
    const auto add = [&](const MeshData& mesh, const std::string& symbol,
                         const pugi::xml_node& user) -> Status {
      if (mesh.indices.empty()) return Status::Ok();
      MaterialRef ref;
      Color3f radiance;
      PTLAB_RETURN_IF_ERROR(material_for(symbol, user, &ref, &radiance));
      return add_mesh(mesh, ref, radiance);
    };
    if (g.is_sphere) {
      MaterialRef ref;
      Color3f radiance;
      PTLAB_RETURN_IF_ERROR(material_for("", geometry, &ref, &radiance));
      // An analytic sphere where it stays one: not emissive (area lights sample triangles) and
      // under a similarity transform (a non-uniform scale makes an ellipsoid).
      float scale = 0;
      if (IsBlack(radiance) && UniformScale(world, &scale))
        return AddAnalyticSphere(instance, ApplyPoint(world, {0, 0, 0}), g.sphere_radius * scale,
                                 ref);
      return add_mesh(MakeSphere({0, 0, 0}, g.sphere_radius), ref, radiance);
    }
    for (const collada::MeshPart& part : g.parts)
      PTLAB_RETURN_IF_ERROR(add(part.mesh, part.material_symbol, part.node));
    return Status::Ok();
  }

  const Document& doc_;
  Scene scene_;
  Matrix4 global_;
  pugi::xml_node camera_;  // the <instance_camera> read
  Vec3f view_dir_, view_up_;  // its world view direction and up vector (unit)
  Vec3f bounds_min_{kHuge, kHuge, kHuge}, bounds_max_{-kHuge, -kHuge, -kHuge};
  std::map<ptrdiff_t, collada::Effect> effects_;
  std::map<ptrdiff_t, ptrdiff_t> effect_of_material_;
  std::map<ptrdiff_t, collada::Geometry> geometries_;
  std::map<ptrdiff_t, uint64_t> counts_;  // CountInstances' memo
  uint64_t input_bytes_ = 0;
  std::map<ptrdiff_t, LightDesc> lights_;
  std::map<ptrdiff_t, CameraDesc> cameras_;
  std::map<ptrdiff_t, std::pair<MaterialRef, Color3f>> material_rows_;
};

}  // namespace

StatusOr<Scene> LoadColladaSceneFromString(const std::string& text,
                                           const std::string& display_name) {
  const internal::XmlLocator at(text, display_name);
  pugi::xml_document xml;
  const pugi::xml_parse_result result =
      xml.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
  if (result.status == pugi::status_no_document_element)
    return Status::Error(at.AtOffset(0) + ": no root element; expected a <COLLADA> element");
  if (!result)
    return Status::Error(at.AtOffset(result.offset) + ": XML syntax error: " +
                         result.description());
  pugi::xml_node root;
  PTLAB_RETURN_IF_ERROR(at.FindSingleRoot(xml, "COLLADA", &root));
  if (std::string_view(root.name()) != "COLLADA")
    return at.Error(root, std::string("root element <") + std::string(root.name()) +
                              ">; expected <COLLADA>");
  Document doc(at);
  PTLAB_RETURN_IF_ERROR(doc.IndexIds(root));
  ColladaReader reader(doc, text.size());
  PTLAB_RETURN_IF_ERROR(reader.Read(root));
  Scene scene = reader.TakeScene();
  scene.source_path = display_name;
  // CS184's defaults; its pixel samples are uniform over the pixel square: a box filter.
  scene.sampler.sample_count = 1;
  scene.integrator.type = IntegratorDesc::Type::kPathEms;
  scene.integrator.max_depth = 1;
  scene.integrator.light_samples = 1;
  scene.filter.type = FilterDesc::Type::kBox;
  scene.filter.radius = 0.5f;
  return scene;
}

StatusOr<Scene> LoadColladaScene(const std::string& path) {
  std::string text;
  PTLAB_RETURN_IF_ERROR(ReadTextFile(path, "scene file", &text));
  StatusOr<Scene> scene = LoadColladaSceneFromString(text, path);
  if (scene.ok()) scene->input_files.insert(scene->input_files.begin(), path);
  return scene;
}

}  // namespace ptlab
