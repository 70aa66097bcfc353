// Nori XML scene parser: strict property lists, transforms, and one builder per object type.
#include "engine/scene/xml_loader.h"
#include "engine/scene/xml_locator.h"

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
#include "engine/scene/mesh_builder.h"
#include "engine/scene/obj_loader.h"
#include "engine/scene/scene_limits.h"
#include "engine/scene/shapes.h"
#include "engine/scene/text_parsing.h"
#include "engine/scene/xml_loader_internal.h"

namespace ptlab {
namespace {

// ---------------------------------------------------------------------------------------------
// Locations

using Locator = internal::XmlLocator;

// "<mesh type="obj">" for messages.
std::string Describe(const pugi::xml_node& node) {
  std::string s = std::string("<") + node.name();
  if (const pugi::xml_attribute type = node.attribute("type")) {
    s += " type=\"" + std::string(type.value()) + "\"";
  }
  return s + ">";
}

std::string JoinNames(const std::vector<const char*>& names) {
  std::string s;
  for (const char* n : names) s += (s.empty() ? "" : ", ") + std::string(n);
  return s.empty() ? "none" : s;
}

// Checks that `node` has exactly the `required` attributes, each once.
Status CheckAttributes(const Locator& at, const pugi::xml_node& node,
                       const std::vector<const char*>& required) {
  std::vector<std::string_view> seen;
  for (const pugi::xml_attribute a : node.attributes()) {
    const std::string_view name = a.name();
    const auto is = [&](const char* n) { return name == n; };
    if (std::none_of(required.begin(), required.end(), is))
      return at.Error(node, "unknown attribute '" + std::string(name) + "' on <" + node.name() +
                                ">; expected " +
                                (required.empty() ? "no attributes" : JoinNames(required)));
    if (std::find(seen.begin(), seen.end(), name) != seen.end())
      return at.Error(node,
                      "duplicate attribute '" + std::string(name) + "' on <" + node.name() + ">");
    seen.push_back(name);
  }
  for (const char* r : required)
    if (!node.attribute(r))
      return at.Error(node,
                      std::string("<") + node.name() + "> is missing the attribute '" + r + "'");
  return Status::Ok();
}

// Leaf elements (properties, transform steps) may hold neither elements nor text.
Status CheckLeaf(const Locator& at, const pugi::xml_node& node) {
  for (const pugi::xml_node child : node.children()) {
    if (child.type() == pugi::node_element)
      return at.Error(child, "unexpected <" + std::string(child.name()) + "> inside <" +
                                 node.name() + ">; expected no child elements");
    if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata)
      return at.Error(node, "unexpected text inside <" + std::string(node.name()) +
                                ">; the value goes in the 'value' attribute");
  }
  return Status::Ok();
}

// ---------------------------------------------------------------------------------------------
// Values

Status ParseFloatValue(const Locator& at, const pugi::xml_node& node, const char* attribute,
                       float* value) {
  const std::string_view text = node.attribute(attribute).value();
  std::vector<std::string_view> items;
  if (!SplitList(text, &items) || items.size() != 1 || !ParseFloat(items[0], value))
    return at.Error(node, "malformed number '" + std::string(text) + "' in attribute '" +
                              attribute + "'; expected one finite decimal number");
  return Status::Ok();
}

Status ParseFloatList(const Locator& at, const pugi::xml_node& node, const char* attribute,
                      size_t count, float* values) {
  const std::string_view text = node.attribute(attribute).value();
  std::vector<std::string_view> items;
  const std::string expected = "expected " + std::to_string(count) +
                               " finite decimal numbers separated by commas and/or whitespace";
  if (!SplitList(text, &items))
    return at.Error(node, "malformed list '" + std::string(text) + "' in attribute '" + attribute +
                              "' (empty item); " + expected);
  if (items.size() != count)
    return at.Error(node, "wrong number of components in '" + std::string(text) + "' (attribute '" +
                              attribute + "'): found " + std::to_string(items.size()) + ", " +
                              expected);
  for (size_t i = 0; i < count; ++i)
    if (!ParseFloat(items[i], &values[i]))
      return at.Error(node, "malformed number '" + std::string(items[i]) + "' in attribute '" +
                                attribute + "'; " + expected);
  return Status::Ok();
}

Status ParseVec3(const Locator& at, const pugi::xml_node& node, const char* attribute, Vec3f* v) {
  float xyz[3];
  PTLAB_RETURN_IF_ERROR(ParseFloatList(at, node, attribute, 3, xyz));
  *v = {xyz[0], xyz[1], xyz[2]};
  return Status::Ok();
}

// The <transform> element: steps applied in order, each multiplied from the left (Nori).
Status ParseTransform(const Locator& at, const pugi::xml_node& node, Transform* result) {
  Transform t;
  for (const pugi::xml_node step : node.children()) {
    if (step.type() == pugi::node_pcdata || step.type() == pugi::node_cdata)
      return at.Error(node,
                      "unexpected text inside <transform>; expected translate, scale, "
                      "rotate, matrix or lookat elements");
    if (step.type() != pugi::node_element) continue;
    const std::string_view tag = step.name();
    PTLAB_RETURN_IF_ERROR(CheckLeaf(at, step));
    Transform s;
    if (tag == "translate") {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(at, step, {"value"}));
      Vec3f v;
      PTLAB_RETURN_IF_ERROR(ParseVec3(at, step, "value", &v));
      s = Transform::Translate(v);
    } else if (tag == "scale") {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(at, step, {"value"}));
      Vec3f v;
      PTLAB_RETURN_IF_ERROR(ParseVec3(at, step, "value", &v));
      if (v.x == 0 || v.y == 0 || v.z == 0)
        return at.Error(step, "singular <scale>; expected non-zero scale factors");
      Matrix4 m, inv;
      m.m[0][0] = v.x, m.m[1][1] = v.y, m.m[2][2] = v.z;
      inv.m[0][0] = 1 / v.x, inv.m[1][1] = 1 / v.y, inv.m[2][2] = 1 / v.z;
      s = Transform(m, inv);
    } else if (tag == "rotate") {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(at, step, {"axis", "angle"}));
      Vec3f axis;
      float angle = 0;
      PTLAB_RETURN_IF_ERROR(ParseVec3(at, step, "axis", &axis));
      PTLAB_RETURN_IF_ERROR(ParseFloatValue(at, step, "angle", &angle));
      if (!(Length(axis) > 0))
        return at.Error(step, "zero <rotate> axis; expected a non-zero axis");
      s = Transform::Rotate(axis, angle);
    } else if (tag == "matrix") {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(at, step, {"value"}));
      float values[16];
      PTLAB_RETURN_IF_ERROR(ParseFloatList(at, step, "value", 16, values));
      Matrix4 m, inv;
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) m.m[i][j] = values[4 * i + j];
      if (!Inverse(m, &inv))
        return at.Error(step, "singular <matrix>; expected an invertible 4x4 matrix");
      s = Transform(m, inv);
    } else if (tag == "lookat") {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(at, step, {"origin", "target", "up"}));
      Vec3f origin, target, up;
      PTLAB_RETURN_IF_ERROR(ParseVec3(at, step, "origin", &origin));
      PTLAB_RETURN_IF_ERROR(ParseVec3(at, step, "target", &target));
      PTLAB_RETURN_IF_ERROR(ParseVec3(at, step, "up", &up));
      if (!(Length(target - origin) > 0))
        return at.Error(step, "degenerate <lookat>: expected target != origin");
      if (!(Length(up) > 0)) return at.Error(step, "degenerate <lookat>: expected a non-zero 'up'");
      const Vec3f dir = Normalize(target - origin);
      const Vec3f left_raw = Cross(Normalize(up), dir);
      if (!(Length(left_raw) > 1e-6f))
        return at.Error(step, "degenerate <lookat>: expected 'up' not parallel to target - origin");
      Vec3f left = Normalize(left_raw), new_up = Normalize(Cross(dir, left));
      if (at.options().lookat == LookatConvention::kNori2015) {
        left = Cross(dir, Normalize(up));
        new_up = Cross(left, dir);
      }
      Matrix4 m, inv;
      const Vec3f columns[4] = {left, new_up, dir, origin};
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) m.m[r][c] = columns[c][r];
      if (!Inverse(m, &inv)) return at.Error(step, "degenerate <lookat>");
      s = Transform(m, inv);
    } else {
      return at.Error(step, "unknown transform step <" + std::string(tag) +
                                ">; expected translate, scale, rotate, matrix or lookat");
    }
    t = s * t;
    // Products of extreme steps can overflow; keep every matrix and inverse entry finite and
    // within 1e30 so that transformed positions and normals stay finite.
    for (const Matrix4* m : {&t.matrix(), &t.inverse_matrix()})
      for (const auto& row : m->m)
        for (const float x : row)
          if (!(std::fabs(x) <= 1e30f))
            return at.Error(step, "<" + std::string(tag) +
                                      "> makes the transform (or its inverse) overflow; expected "
                                      "matrix entries of magnitude <= 1e30");
  }
  *result = t;
  return Status::Ok();
}

// ---------------------------------------------------------------------------------------------
// Property lists

enum class PropertyType : uint8_t {
  kBoolean,
  kInteger,
  kFloat,
  kString,
  kPoint,
  kVector,
  kColor,
  kTransform
};

constexpr const char* kPropertyTags[] = {"boolean", "integer", "float", "string",
                                         "point",   "vector",  "color", "transform"};

bool PropertyTypeOf(std::string_view tag, PropertyType* type) {
  for (int i = 0; i < 8; ++i)
    if (tag == kPropertyTags[i]) {
      *type = PropertyType(i);
      return true;
    }
  return false;
}

struct Property {
  std::string name;
  PropertyType type;
  pugi::xml_node node;
  bool boolean = false;
  int integer = 0;
  float number = 0;
  std::string text;
  Vec3f vec;
  Transform transform;
};

// The properties of one object. A builder first declares every name its type accepts
// (Expect), then reads them with typed getters that fall back to the given default.
class PropertyList {
 public:
  PropertyList(const Locator* at, pugi::xml_node owner) : at_(at), owner_(owner) {}

  Status Add(const pugi::xml_node& node) {
    PropertyType type;
    PTLAB_CHECK(PropertyTypeOf(node.name(), &type));
    Property p;
    p.type = type;
    p.node = node;
    if (type == PropertyType::kTransform) {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(*at_, node, {"name"}));
      PTLAB_RETURN_IF_ERROR(ParseTransform(*at_, node, &p.transform));
    } else {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(*at_, node, {"name", "value"}));
      PTLAB_RETURN_IF_ERROR(CheckLeaf(*at_, node));
      const std::string value = node.attribute("value").value();
      switch (type) {
        case PropertyType::kBoolean: {
          std::string lower = value;
          for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
          if (lower != "true" && lower != "false")
            return at_->Error(node, "malformed boolean '" + value + "'; expected true or false");
          p.boolean = lower == "true";
          break;
        }
        case PropertyType::kInteger:
          if (!ParseInt(value, &p.integer))
            return at_->Error(
                node, "malformed integer '" + value + "'; expected a decimal integer such as 42");
          break;
        case PropertyType::kFloat:
          PTLAB_RETURN_IF_ERROR(ParseFloatValue(*at_, node, "value", &p.number));
          break;
        case PropertyType::kString:
          p.text = value;
          break;
        default:
          PTLAB_RETURN_IF_ERROR(ParseVec3(*at_, node, "value", &p.vec));
          break;
      }
    }
    p.name = node.attribute("name").value();
    for (const Property& q : props_)
      if (q.name == p.name)
        return at_->Error(node, "duplicate property '" + p.name + "' (first given at line " +
                                    std::to_string(at_->Line(q.node)) +
                                    "); expected each property at most once");
    props_.push_back(std::move(p));
    return Status::Ok();
  }

  // Fails on the first property whose name is not in `names`.
  Status Expect(std::vector<const char*> names) {
    expected_ = std::move(names);
    for (const Property& p : props_) {
      if (std::none_of(expected_.begin(), expected_.end(),
                       [&](const char* n) { return p.name == n; }))
        return at_->Error(p.node, "unknown property '" + p.name + "' for " + Describe(owner_) +
                                      "; expected " +
                                      (expected_.empty() ? std::string("no properties")
                                                         : "one of: " + JoinNames(expected_)));
    }
    return Status::Ok();
  }

  Status Boolean(const char* name, bool* v) {
    const Property* p = nullptr;
    PTLAB_RETURN_IF_ERROR(Find(name, PropertyType::kBoolean, &p));
    if (p) *v = p->boolean;
    return Status::Ok();
  }
  Status Integer(const char* name, int* v) {
    const Property* p = nullptr;
    PTLAB_RETURN_IF_ERROR(Find(name, PropertyType::kInteger, &p));
    if (p) *v = p->integer;
    return Status::Ok();
  }
  Status Float(const char* name, float* v) {
    const Property* p = nullptr;
    PTLAB_RETURN_IF_ERROR(Find(name, PropertyType::kFloat, &p));
    if (p) *v = p->number;
    return Status::Ok();
  }
  Status String(const char* name, std::string* v) {
    const Property* p = nullptr;
    PTLAB_RETURN_IF_ERROR(Find(name, PropertyType::kString, &p));
    if (p) *v = p->text;
    return Status::Ok();
  }
  Status Point(const char* name, Vec3f* v) {
    const Property* p = nullptr;
    PTLAB_RETURN_IF_ERROR(Find(name, PropertyType::kPoint, &p));
    if (p) *v = p->vec;
    return Status::Ok();
  }
  Status Color(const char* name, Color3f* v) {
    const Property* p = nullptr;
    PTLAB_RETURN_IF_ERROR(Find(name, PropertyType::kColor, &p));
    if (p) *v = {p->vec.x, p->vec.y, p->vec.z};
    return Status::Ok();
  }
  Status TransformProperty(const char* name, Transform* v) {
    const Property* p = nullptr;
    PTLAB_RETURN_IF_ERROR(Find(name, PropertyType::kTransform, &p));
    if (p) *v = p->transform;
    return Status::Ok();
  }

  bool Has(const char* name) const { return Get(name) != nullptr; }

  // An error located at property `name` if given, else at the owning element.
  Status Error(const char* name, const std::string& message) const {
    const Property* p = Get(name);
    return at_->Error(p ? p->node : owner_, message);
  }
  Status Require(const char* name, const char* tag) const {
    if (Has(name)) return Status::Ok();
    return at_->Error(owner_, Describe(owner_) + " is missing the required property <" + tag +
                                  " name=\"" + name + "\">");
  }

 private:
  const Property* Get(const char* name) const {
    for (const Property& p : props_)
      if (p.name == name) return &p;
    return nullptr;
  }
  Status Find(const char* name, PropertyType type, const Property** found) const {
    // A getter for a name the builder did not Expect is a bug in this file.
    PTLAB_CHECK(std::any_of(expected_.begin(), expected_.end(),
                            [&](const char* n) { return std::string_view(n) == name; }));
    *found = Get(name);
    if (*found && (*found)->type != type)
      return at_->Error((*found)->node, "property '" + std::string(name) + "' of " +
                                            Describe(owner_) + " has the wrong type <" +
                                            kPropertyTags[int((*found)->type)] + ">; expected <" +
                                            kPropertyTags[int(type)] + ">");
    return Status::Ok();
  }

  const Locator* at_;
  pugi::xml_node owner_;
  std::vector<Property> props_;
  std::vector<const char*> expected_;
};

// ---------------------------------------------------------------------------------------------
// Objects

constexpr const char* kObjectTags[] = {"scene",  "mesh",    "shape",      "bsdf",    "emitter",
                                       "camera", "sampler", "integrator", "rfilter", "test"};

bool IsObjectTag(std::string_view tag) {
  return std::any_of(std::begin(kObjectTags), std::end(kObjectTags),
                     [&](const char* t) { return tag == t; });
}

std::string FormatNumber(float v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%g", double(v));
  return buffer;
}

std::string FormatColor(const Color3f& c) {
  return FormatNumber(c.r) + ", " + FormatNumber(c.g) + ", " + FormatNumber(c.b);
}

class SceneParser {
 public:
  SceneParser(const Locator* at, std::string base_dir) : at_(*at), base_dir_(std::move(base_dir)) {}

  Status ParseRoot(const pugi::xml_document& doc) {
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

  Scene TakeScene() { return std::move(scene_); }

  // One <scene> or <bsdf> element of a larger document (xml_loader_internal.h).
  Status ParseSceneElement(const pugi::xml_node& node) { return ParseScene(node); }
  StatusOr<MaterialRef> ParseBsdfElement(const pugi::xml_node& node) { return ParseBsdf(node); }

 private:
  // Splits `node`'s children into properties (parsed into `props`) and child objects, which
  // must be among `allowed`.
  Status Collect(const pugi::xml_node& node, const std::vector<const char*>& allowed,
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

  // Objects that take only properties.
  Status CollectLeafObject(const pugi::xml_node& node, PropertyList* props) {
    PTLAB_RETURN_IF_ERROR(CheckAttributes(at_, node, {"type"}));
    std::vector<pugi::xml_node> none;
    return Collect(node, {}, props, &none);
  }

  // Enforces "at most one" for `slot`, remembering where the first one was.
  Status TakeSingleton(const pugi::xml_node& node, pugi::xml_node* slot) {
    if (*slot)
      return at_.Error(node, "a second <" + std::string(node.name()) +
                                 ">; expected at most one (the first is at line " +
                                 std::to_string(at_.Line(*slot)) + ")");
    *slot = node;
    return Status::Ok();
  }

  Status ParseScene(const pugi::xml_node& node) {
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

  std::string Resolve(const std::string& filename) const {
    const std::filesystem::path p(filename);
    if (p.is_absolute() || base_dir_.empty()) return p.lexically_normal().string();
    return (std::filesystem::path(base_dir_) / p).lexically_normal().string();
  }

  Status ParseShape(const pugi::xml_node& node) {
    PTLAB_RETURN_IF_ERROR(CheckAttributes(at_, node, {"type"}));
    const std::string type = node.attribute("type").value();
    PropertyList props(&at_, node);
    std::vector<pugi::xml_node> children;
    PTLAB_RETURN_IF_ERROR(Collect(node, {"bsdf", "emitter"}, &props, &children));

    MeshData generated;
    const MeshData* mesh = &generated;
    std::string name = type;
    if (type == "obj") {
      PTLAB_RETURN_IF_ERROR(props.Expect({"filename", "toWorld"}));
      PTLAB_RETURN_IF_ERROR(props.Require("filename", "string"));
    } else if (type == "sphere") {
      PTLAB_RETURN_IF_ERROR(props.Expect({"center", "radius", "toWorld"}));
      Vec3f center;
      float radius = 1.0f;
      PTLAB_RETURN_IF_ERROR(props.Point("center", &center));
      PTLAB_RETURN_IF_ERROR(props.Float("radius", &radius));
      if (!(radius > 0)) return props.Error("radius", "sphere radius must be > 0");
      generated = MakeSphere(center, radius);
    } else if (type == "rectangle" || type == "cube" || type == "disk") {
      PTLAB_RETURN_IF_ERROR(props.Expect({"toWorld"}));
      generated =
          type == "rectangle" ? MakeRectangle() : (type == "cube" ? MakeCube() : MakeDisk());
    } else {
      return at_.Error(node, "unknown " + std::string(node.name()) + " type '" + type +
                                 "'; expected obj, sphere, rectangle, cube or disk");
    }
    Transform to_world;
    PTLAB_RETURN_IF_ERROR(props.TransformProperty("toWorld", &to_world));

    pugi::xml_node bsdf_node, emitter_node;
    for (const pugi::xml_node child : children)
      PTLAB_RETURN_IF_ERROR(TakeSingleton(
          child, std::string_view(child.name()) == "bsdf" ? &bsdf_node : &emitter_node));
    // Nori's default material for a mesh without a BSDF.
    MaterialRef material;
    if (bsdf_node) {
      StatusOr<MaterialRef> parsed = ParseBsdf(bsdf_node);
      if (!parsed.ok()) return parsed.status();
      material = *parsed;
    }
    Color3f radiance;
    if (emitter_node) PTLAB_RETURN_IF_ERROR(ParseAreaEmitter(emitter_node, &radiance));

    if (type == "obj") {
      std::string filename;
      PTLAB_RETURN_IF_ERROR(props.String("filename", &filename));
      const std::string path = Resolve(filename);
      auto it = obj_cache_.find(path);
      if (it == obj_cache_.end()) {
        StatusOr<MeshData> loaded = LoadObj(path);
        if (!loaded.ok())
          return at_.Error(node, "cannot load the OBJ file of " + Describe(node) + ": " +
                                     loaded.status().message());
        it = obj_cache_.emplace(path, std::move(*loaded)).first;
        scene_.input_files.push_back(path);
      }
      mesh = &it->second;
      name = filename;
    }
    if (!bsdf_node) material = scene_.materials.AddDiffuse({0.5f, 0.5f, 0.5f});
    const uint32_t first = uint32_t(scene_.triangles.size());
    const uint32_t row = AddMesh(&scene_, *mesh, to_world, material, name);
    const TriangleTable& tri = scene_.triangles;
    for (uint32_t t = first; t < tri.size(); ++t)
      for (const Vec3f& v : {tri.V0(t), tri.V1(t), tri.V2(t)})
        if (!(std::abs(v.x) <= kMaxWorldCoordinate && std::abs(v.y) <= kMaxWorldCoordinate &&
              std::abs(v.z) <= kMaxWorldCoordinate))
          return at_.Error(node, "triangle " + std::to_string(t - first) + " of " + Describe(node) +
                                     " has the world-space vertex (" + FormatNumber(v.x) + ", " +
                                     FormatNumber(v.y) + ", " + FormatNumber(v.z) +
                                     "); expected coordinates and toWorld that keep every "
                                     "coordinate finite and within +-" +
                                     FormatNumber(kMaxWorldCoordinate));
    if (emitter_node) {
      AreaLightTable& lights = scene_.area_lights;
      const EmitterRef ref = EmitterRef::Make(EmitterTag::kArea, uint32_t(lights.size()));
      lights.radiance.push_back(radiance);
      lights.mesh.push_back(row);
      scene_.meshes.emitter[row] = ref;
      scene_.emitters.push_back(ref);
    }
    return Status::Ok();
  }

  // Reflectances must lie in [0, 1]; radiance, power, eta and k in [0, kMaxRadiance].
  enum class Range { kUnit, kNonNegative };
  Status CheckColor(PropertyList& props, const char* name, const Color3f& c, Range range) {
    const float max = range == Range::kUnit ? 1.0f : kMaxRadiance;
    if (c.r >= 0 && c.g >= 0 && c.b >= 0 && c.r <= max && c.g <= max && c.b <= max)
      return Status::Ok();
    return props.Error(name, std::string("'") + name + "' = (" + FormatColor(c) +
                                 ") is out of range; expected components " +
                                 (range == Range::kUnit ? "in [0, 1]" : "in [0, 1e20]"));
  }
  Status CheckPositive(PropertyList& props, const char* name, float v) {
    if (v > 0) return Status::Ok();
    return props.Error(name, std::string("'") + name + "' = " + FormatNumber(v) +
                                 " is out of range; expected a value > 0");
  }

  StatusOr<MaterialRef> ParseBsdf(const pugi::xml_node& node) {
    PropertyList props(&at_, node);
    PTLAB_RETURN_IF_ERROR(CollectLeafObject(node, &props));
    const std::string type = node.attribute("type").value();
    MaterialTables& materials = scene_.materials;
    float int_ior = 1.5046f, ext_ior = 1.000277f, alpha = 0.1f;
    if (type == "diffuse") {
      PTLAB_RETURN_IF_ERROR(props.Expect({"albedo"}));
      Color3f albedo{0.5f, 0.5f, 0.5f};
      PTLAB_RETURN_IF_ERROR(props.Color("albedo", &albedo));
      PTLAB_RETURN_IF_ERROR(CheckColor(props, "albedo", albedo, Range::kUnit));
      return materials.AddDiffuse(albedo);
    }
    if (type == "mirror") {
      PTLAB_RETURN_IF_ERROR(props.Expect({}));
      return materials.AddMirror();
    }
    if (type == "dielectric") {
      PTLAB_RETURN_IF_ERROR(props.Expect({"intIOR", "extIOR", "schlick", "scaleRadiance"}));
      PTLAB_RETURN_IF_ERROR(props.Float("intIOR", &int_ior));
      PTLAB_RETURN_IF_ERROR(props.Float("extIOR", &ext_ior));
      PTLAB_RETURN_IF_ERROR(CheckPositive(props, "intIOR", int_ior));
      PTLAB_RETURN_IF_ERROR(CheckPositive(props, "extIOR", ext_ior));
      // ptlab extensions: Schlick's approximation (as CS184's glass) and the (η_o/η_i)²
      // radiance scaling on refraction; both off by default, as in Nori.
      bool schlick = false, scale_radiance = false;
      PTLAB_RETURN_IF_ERROR(props.Boolean("schlick", &schlick));
      PTLAB_RETURN_IF_ERROR(props.Boolean("scaleRadiance", &scale_radiance));
      const uint8_t flags = uint8_t((schlick ? kDielectricSchlick : 0) |
                                    (scale_radiance ? kDielectricScaleRadiance : 0));
      return materials.AddDielectric(int_ior, ext_ior, flags);
    }
    if (type == "microfacet") {
      PTLAB_RETURN_IF_ERROR(props.Expect({"alpha", "intIOR", "extIOR", "kd"}));
      Color3f kd{0.5f, 0.5f, 0.5f};
      PTLAB_RETURN_IF_ERROR(props.Float("alpha", &alpha));
      PTLAB_RETURN_IF_ERROR(props.Float("intIOR", &int_ior));
      PTLAB_RETURN_IF_ERROR(props.Float("extIOR", &ext_ior));
      PTLAB_RETURN_IF_ERROR(props.Color("kd", &kd));
      PTLAB_RETURN_IF_ERROR(CheckPositive(props, "alpha", alpha));
      PTLAB_RETURN_IF_ERROR(CheckPositive(props, "intIOR", int_ior));
      PTLAB_RETURN_IF_ERROR(CheckPositive(props, "extIOR", ext_ior));
      PTLAB_RETURN_IF_ERROR(CheckColor(props, "kd", kd, Range::kUnit));
      return materials.AddRoughPlastic(alpha, int_ior, ext_ior, kd);
    }
    if (type == "roughconductor") {
      PTLAB_RETURN_IF_ERROR(props.Expect({"alpha", "eta", "k", "material"}));
      // Mitsuba's roughconductor: a named `material` (default Cu) or explicit eta and k.
      Color3f eta, k;
      PTLAB_RETURN_IF_ERROR(props.Float("alpha", &alpha));
      if (props.Has("eta") || props.Has("k")) {
        if (props.Has("material"))
          return props.Error("material", "give either string 'material' or colors 'eta' and "
                                         "'k', not both");
        PTLAB_RETURN_IF_ERROR(props.Require("eta", "color"));
        PTLAB_RETURN_IF_ERROR(props.Require("k", "color"));
        PTLAB_RETURN_IF_ERROR(props.Color("eta", &eta));
        PTLAB_RETURN_IF_ERROR(props.Color("k", &k));
      } else {
        std::string name = "Cu";
        PTLAB_RETURN_IF_ERROR(props.String("material", &name));
        if (!LookupConductorPreset(name, &eta, &k)) {
          return props.Error("material", "unknown conductor '" + name + "'; expected one of " +
                                              std::string(ConductorPresetNames()));
        }
      }
      PTLAB_RETURN_IF_ERROR(CheckPositive(props, "alpha", alpha));
      PTLAB_RETURN_IF_ERROR(CheckColor(props, "eta", eta, Range::kNonNegative));
      PTLAB_RETURN_IF_ERROR(CheckColor(props, "k", k, Range::kNonNegative));
      return materials.AddConductor(alpha, eta, k);
    }
    return at_.Error(node, "unknown bsdf type '" + type +
                               "'; expected diffuse, mirror, dielectric, microfacet or "
                               "roughconductor");
  }

  // Mitsuba emitter types we recognise but do not render yet (a clear "not supported yet").
  static bool IsUnsupportedEmitter(const std::string& type) {
    return type == "spot" || type == "directional";
  }
  // Emitters that stand on their own, directly inside <scene>.
  static bool IsSceneEmitter(const std::string& type) {
    return type == "envmap" || type == "distantdisk" || type == "point" || type == "constant";
  }

  Status ParseAreaEmitter(const pugi::xml_node& node, Color3f* radiance) {
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

  Status ParseSceneEmitter(const pugi::xml_node& node) {
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

  // Mitsuba `constant`: uniform radiance from every direction (color radiance, required), a
  // distant disk of half-angle 180°: sampled uniformly over the sphere, with MIS as envmaps.
  Status ParseConstantEmitter(const pugi::xml_node& node) {
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

  // Nori's `point`: point position and color power (W), both required; power >= 0.
  Status ParsePointEmitter(const pugi::xml_node& node) {
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

  // The rotation of an infinite emitter's toWorld: its upper 3x3 must be orthonormal
  // (translation is ignored: the emitter is infinitely far away).
  Status RotationOf(const pugi::xml_node& node, PropertyList& props, const Transform& to_world,
                    Frame* frame) {
    const Matrix4& m = to_world.matrix();
    const Vec3f c[3] = {{m.m[0][0], m.m[1][0], m.m[2][0]},
                        {m.m[0][1], m.m[1][1], m.m[2][1]},
                        {m.m[0][2], m.m[1][2], m.m[2][2]}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (!(std::fabs(Dot(c[i], c[j]) - (i == j ? 1.0f : 0.0f)) <= 1e-4f))
          return props.Error("toWorld", "toWorld of " + Describe(node) +
                                            " is not a rotation; expected an orthonormal upper 3x3 "
                                            "(rotate, lookat; no scale or shear)");
    frame->s = Normalize(c[0]), frame->t = Normalize(c[1]), frame->n = Normalize(c[2]);
    return Status::Ok();
  }

  // Mitsuba `envmap`: string filename (EXR/HDR/PFM/PNG lat-long image, required), float scale
  // = 1, transform toWorld (rotation), string sampling = importance|uniform.
  Status ParseEnvironmentEmitter(const pugi::xml_node& node) {
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

  // Nori (ETH) `distantdisk`: color radiance and float thetaA (half-angle in degrees, (0, 180])
  // required, transform toWorld (rotation; the cone is around its local +z).
  Status ParseDistantDiskEmitter(const pugi::xml_node& node) {
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

  Status ParseCamera(const pugi::xml_node& node) {
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

  Status ParseFilter(const pugi::xml_node& node) {
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

  Status ParseSampler(const pugi::xml_node& node) {
    PropertyList props(&at_, node);
    PTLAB_RETURN_IF_ERROR(CollectLeafObject(node, &props));
    const std::string type = node.attribute("type").value();
    if (type != "independent")
      return at_.Error(node, "unknown sampler type '" + type + "'; expected independent");
    PTLAB_RETURN_IF_ERROR(props.Expect({"sampleCount"}));
    int count = 1;
    PTLAB_RETURN_IF_ERROR(props.Integer("sampleCount", &count));
    if (count < 1) return props.Error("sampleCount", "sampleCount must be >= 1");
    scene_.sampler.sample_count = uint32_t(count);
    return Status::Ok();
  }

  Status ParseIntegrator(const pugi::xml_node& node) {
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
    };
    const Kind* kind = nullptr;
    for (const Kind& k : kKinds)
      if (type == k.name) kind = &k;
    if (!kind)
      return at_.Error(node, "unknown integrator type '" + type +
                                 "'; expected normals, direct_ems, direct_mats, direct_mis, "
                                 "whitted, path_mats, path_ems or path_mis");
    std::vector<const char*> names;
    if (kind->depth) names.push_back("maxDepth");
    if (kind->light_samples) names.push_back("lightSamples");
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
    }
    if (kind->heuristic) {
      std::string heuristic = "balance";
      PTLAB_RETURN_IF_ERROR(props.String("heuristic", &heuristic));
      if (heuristic != "balance" && heuristic != "power")
        return props.Error("heuristic",
                           "unknown heuristic '" + heuristic + "'; expected balance or power");
      desc.power_heuristic = heuristic == "power";
    }
    scene_.integrator = desc;
    return Status::Ok();
  }

  const Locator& at_;
  std::string base_dir_;
  Scene scene_;
  pugi::xml_node camera_, integrator_, filter_;
  std::map<std::string, MeshData> obj_cache_;  // one OBJ used by several meshes loads once
};

}  // namespace

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
