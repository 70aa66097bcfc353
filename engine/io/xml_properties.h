// Nori XML building blocks shared by the XML readers: attribute and leaf checks, numbers,
// transforms, and the typed property list of one object.
#pragma once

#include <cstdint>
#include <pugixml.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/status.h"
#include "engine/core/transform.h"
#include "engine/core/vec.h"
#include "engine/io/text_parsing.h"
#include "engine/io/xml_locator.h"

namespace ptlab::internal {

// ---------------------------------------------------------------------------------------------
// Locations

using Locator = internal::XmlLocator;

// "<mesh type="obj">" for messages.
std::string Describe(const pugi::xml_node& node);

std::string JoinNames(const std::vector<const char*>& names);

// Checks that `node` has exactly the `required` attributes, each once.
Status CheckAttributes(const Locator& at, const pugi::xml_node& node,
                       const std::vector<const char*>& required);

// Leaf elements (properties, transform steps) may hold neither elements nor text.
Status CheckLeaf(const Locator& at, const pugi::xml_node& node);

// ---------------------------------------------------------------------------------------------
// Values

Status ParseFloatValue(const Locator& at, const pugi::xml_node& node, const char* attribute,
                       float* value);

Status ParseFloatList(const Locator& at, const pugi::xml_node& node, const char* attribute,
                      size_t count, float* values);

Status ParseVec3(const Locator& at, const pugi::xml_node& node, const char* attribute, Vec3f* v);

// The <transform> element: steps applied in order, each multiplied from the left (Nori).
Status ParseTransform(const Locator& at, const pugi::xml_node& node, Transform* result);

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

inline constexpr const char* kPropertyTags[] = {"boolean", "integer", "float", "string",
                                         "point",   "vector",  "color", "transform"};


bool PropertyTypeOf(std::string_view tag, PropertyType* type);

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
          if (const std::string error = ParseNumber<int>(value, &p.integer); !error.empty())
            return at_->Error(node, "integer " + error);
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


bool IsObjectTag(std::string_view tag);

std::string FormatNumber(float v);

std::string FormatColor(const Color3f& c);

}  // namespace ptlab::internal
