// Mitsuba objects: the object tags, ids, and reading an element's typed properties.
#include "engine/io/mitsuba_properties.h"

#include <algorithm>
#include <cctype>

#include "engine/io/mitsuba_values.h"
#include "engine/io/text_parsing.h"

namespace ptlab::internal {

using mitsuba_values::CamelToSnake;
using mitsuba_values::CheckAttributes;
using mitsuba_values::Leaf;
using mitsuba_values::XyzVector;
using mitsuba_values::ParseColor;
using mitsuba_values::ParseSpectrum;

namespace {

constexpr const char* kObjectTags[] = {"bsdf",    "emitter", "shape",   "sensor",     "film",
                                       "sampler", "rfilter", "texture", "integrator", "medium",
                                       "phase",   "volume",  "scene"};

}  // namespace

bool IsMitsubaObjectTag(const std::string& tag) {
  return std::any_of(std::begin(kObjectTags), std::end(kObjectTags),
                     [&](const char* t) { return tag == t; });
}

std::string DescribeMitsuba(const MitsubaNode& node) {
  std::string s = "<" + node.tag;
  if (const std::string* type = node.Attribute("type")) s += " type=\"" + *type + "\"";
  return s + ">";
}

Status Unsupported(const MitsubaNode& node, const std::string& note) {
  const std::string* type = node.Attribute("type");
  std::string what = node.tag;
  if (type) what += " \"" + *type + "\"";
  return node.Error("unsupported: " + what + (note.empty() ? "" : " (" + note + ")"));
}

Status CollectMitsubaIds(const MitsubaNode& root, std::map<std::string, const MitsubaNode*>* ids) {
  for (const MitsubaNode& child : root.children) {
    if (child.tag != "ref" && IsMitsubaObjectTag(child.tag))
      if (const std::string* id = child.Attribute("id")) {
        const auto [it, inserted] = ids->emplace(*id, &child);
        if (!inserted)
          return child.Error("duplicate id '" + *id + "' (first given at " + it->second->where +
                             ")");
      }
    PTLAB_RETURN_IF_ERROR(CollectMitsubaIds(child, ids));
  }
  return Status::Ok();
}

StatusOr<MitsubaObject> MitsubaObject::Read(const MitsubaNode& node,
                                            const std::map<std::string, const MitsubaNode*>& ids,
                                            bool legacy) {
  MitsubaObject obj;
  obj.node_ = &node;
  for (const auto& [name, value] : node.attributes)
    if (name != "type" && name != "id" && name != "name")
      return node.Error("unknown attribute '" + name + "' on <" + node.tag +
                        ">; expected type, id (and name when it is a property)");
  if (const std::string* type = node.Attribute("type")) obj.type_ = *type;
  using T = MitsubaProperty::Type;
  for (const MitsubaNode& child : node.children) {
    const std::string& tag = child.tag;
    MitsubaProperty p;
    p.node = &child;
    const std::string* name = child.Attribute("name");
    if (tag == "ref") {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(child, {"id", "name"}, {"id"}));
      PTLAB_RETURN_IF_ERROR(Leaf(child));
      const auto it = ids.find(*child.Attribute("id"));
      if (it == ids.end())
        return child.Error("<ref id=\"" + *child.Attribute("id") +
                           "\"> names no object; expected the id of an object in the scene");
      if (!name) {
        obj.children_.push_back(it->second);
        continue;
      }
      p.type = T::kObject;
      p.object = it->second;
    } else if (IsMitsubaObjectTag(tag)) {
      if (tag == "scene") return child.Error("<scene> is only allowed as the root element");
      if (!name) {
        obj.children_.push_back(&child);
        continue;
      }
      p.type = T::kObject;
      p.object = &child;
    } else if (tag == "transform") {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(child, {"name"}, {"name"}));
      p.type = T::kTransform;
      PTLAB_RETURN_IF_ERROR(ParseMitsubaTransform(child, &p.transform));
    } else {
      PTLAB_RETURN_IF_ERROR(Leaf(child));
      if (tag == "point" || tag == "vector") {
        PTLAB_RETURN_IF_ERROR(CheckAttributes(child, {"name", "value", "x", "y", "z"}, {"name"}));
        p.type = tag == "point" ? T::kPoint : T::kVector;
        PTLAB_RETURN_IF_ERROR(XyzVector(child, 0.0f, false, &p.vec));
      } else if (tag == "spectrum") {
        PTLAB_RETURN_IF_ERROR(CheckAttributes(child, {"name", "value", "filename"}, {"name"}));
        if (!child.Attribute("value") && !child.Attribute("filename"))
          return child.Error("<spectrum> needs a 'value' attribute");
        p.type = T::kSpectrum;
        PTLAB_RETURN_IF_ERROR(ParseSpectrum(child, &p));
      } else if (tag == "boolean" || tag == "integer" || tag == "float" || tag == "string" ||
                 tag == "rgb" || tag == "srgb" || tag == "color") {
        PTLAB_RETURN_IF_ERROR(CheckAttributes(child, {"name", "value"}, {"name", "value"}));
        const std::string& value = *child.Attribute("value");
        if (tag == "boolean") {
          std::string lower = value;
          for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
          if (lower != "true" && lower != "false")
            return child.Error("malformed boolean '" + value + "'; expected true or false");
          p.type = T::kBoolean;
          p.boolean = lower == "true";
        } else if (tag == "integer") {
          int v = 0;
          if (const std::string error = ParseNumber<int>(value, &v); !error.empty())
            return child.Error("integer " + error);
          p.type = T::kInteger;
          p.integer = v;
        } else if (tag == "float") {
          float v = 0;
          if (!ParseFloat(value, &v))
            return child.Error("malformed number '" + value +
                               "'; expected one finite decimal number");
          p.type = T::kFloat;
          p.number = v;
        } else if (tag == "string") {
          p.type = T::kString;
          p.text = value;
        } else {
          p.type = T::kRgb;
          PTLAB_RETURN_IF_ERROR(ParseColor(child, tag == "srgb", &p.rgb));
        }
      } else {
        return child.Error("unknown tag <" + tag + "> inside " + DescribeMitsuba(node) +
                           "; expected a property (boolean, integer, float, string, point, "
                           "vector, rgb, srgb, spectrum, transform), <ref> or an object");
      }
    }
    if (!name) return child.Error("<" + tag + "> is missing the attribute 'name'");
    p.name = legacy ? CamelToSnake(*name) : *name;
    for (const MitsubaProperty& q : obj.props_)
      if (q.name == p.name)
        return child.Error("duplicate property '" + p.name + "' (first given at " + q.node->where +
                           "); expected each property at most once");
    obj.props_.push_back(std::move(p));
  }
  return obj;
}

}  // namespace ptlab::internal
