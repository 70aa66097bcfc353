// Mitsuba property values: numbers, vectors, colours, spectra, transforms, references.
#include "engine/io/mitsuba_properties.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include "engine/io/text_parsing.h"

namespace ptlab::internal {
namespace {

constexpr const char* kObjectTags[] = {"bsdf",    "emitter", "shape",   "sensor",     "film",
                                       "sampler", "rfilter", "texture", "integrator", "medium",
                                       "phase",   "volume",  "scene"};

std::string Join(const std::vector<const char*>& names) {
  std::string s;
  for (const char* n : names) s += (s.empty() ? "" : ", ") + std::string(n);
  return s.empty() ? "none" : s;
}

// "toWorld" -> "to_world", "intIOR" -> "int_ior": an underscore where an upper-case letter
// follows a lower-case letter or a digit.
std::string CamelToSnake(const std::string& name) {
  std::string out;
  for (size_t i = 0; i < name.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    if (std::isupper(c) && i > 0 &&
        (std::islower(static_cast<unsigned char>(name[i - 1])) ||
         std::isdigit(static_cast<unsigned char>(name[i - 1]))))
      out.push_back('_');
    out.push_back(char(std::tolower(c)));
  }
  return out;
}

// Checks that the node's attributes are among `allowed`, each of `required` present.
Status CheckAttributes(const MitsubaNode& node, const std::vector<const char*>& allowed,
                       const std::vector<const char*>& required) {
  for (const auto& attribute : node.attributes) {
    const std::string& name = attribute.first;  // a plain name: lambdas capture it (clang 14)
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return name == a; }))
      return node.Error("unknown attribute '" + name + "' on <" + node.tag + ">; expected " +
                        Join(allowed));
  }
  for (const char* r : required)
    if (!node.Attribute(r))
      return node.Error("<" + node.tag + "> is missing the attribute '" + r + "'");
  return Status::Ok();
}

Status Leaf(const MitsubaNode& node) {
  if (!node.children.empty())
    return node.children[0].Error("unexpected <" + node.children[0].tag + "> inside <" + node.tag +
                                  ">; expected no child elements");
  return Status::Ok();
}

Status Numbers(const MitsubaNode& node, const char* attribute, std::vector<double>* out) {
  const std::string& text = *node.Attribute(attribute);
  std::vector<std::string_view> items;
  out->clear();
  if (!SplitList(text, &items))
    return node.Error("malformed list '" + text + "' in attribute '" + attribute + "'");
  for (const std::string_view item : items) {
    float v = 0;
    if (!ParseFloat(item, &v))
      return node.Error("malformed number '" + std::string(item) + "' in attribute '" + attribute +
                        "'; expected finite decimal numbers");
    out->push_back(v);
  }
  return Status::Ok();
}

// A vector given as value="a, b, c" (or one number, repeated when `splat`) or as x, y, z
// attributes, each defaulting to `fallback`.
Status XyzVector(const MitsubaNode& node, float fallback, bool splat, Vec3f* v) {
  *v = {fallback, fallback, fallback};
  if (node.Attribute("value")) {
    if (node.Attribute("x") || node.Attribute("y") || node.Attribute("z"))
      return node.Error("give either 'value' or 'x', 'y', 'z' on <" + node.tag + ">, not both");
    std::vector<double> n;
    PTLAB_RETURN_IF_ERROR(Numbers(node, "value", &n));
    if (n.size() == 1 && splat) n.assign(3, n[0]);
    if (n.size() != 3)
      return node.Error("wrong number of components in '" + *node.Attribute("value") +
                        "': expected 3" + (splat ? " (or 1)" : ""));
    *v = {float(n[0]), float(n[1]), float(n[2])};
    return Status::Ok();
  }
  const char* names[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    const std::string* text = node.Attribute(names[i]);
    if (!text) continue;
    float c = 0;
    if (!ParseFloat(*text, &c))
      return node.Error("malformed number '" + *text + "' in attribute '" + names[i] +
                        "'; expected a finite decimal number");
    (*v)[i] = c;
  }
  return Status::Ok();
}

Status ParseVec3Attribute(const MitsubaNode& node, const char* attribute, Vec3f* v) {
  std::vector<double> n;
  PTLAB_RETURN_IF_ERROR(Numbers(node, attribute, &n));
  if (n.size() != 3)
    return node.Error("wrong number of components in '" + *node.Attribute(attribute) +
                      "' (attribute '" + attribute + "'): expected 3");
  *v = {float(n[0]), float(n[1]), float(n[2])};
  return Status::Ok();
}

float SrgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

Status ParseColor(const MitsubaNode& node, bool srgb, Color3f* c) {
  const std::string& text = *node.Attribute("value");
  std::vector<double> n;
  if (srgb && !text.empty() && text[0] == '#') {
    if (text.size() != 7 || !std::all_of(text.begin() + 1, text.end(), [](char ch) {
          return std::isxdigit(static_cast<unsigned char>(ch));
        }))
      return node.Error("malformed colour '" + text + "'; expected #rrggbb");
    for (int i = 0; i < 3; ++i)
      n.push_back(std::stoi(text.substr(1 + 2 * i, 2), nullptr, 16) / 255.0);
  } else {
    PTLAB_RETURN_IF_ERROR(Numbers(node, "value", &n));
  }
  if (n.size() == 1) n.assign(3, n[0]);
  if (n.size() != 3)
    return node.Error("wrong number of components in '" + text + "': expected 3 (or 1)");
  *c = {float(n[0]), float(n[1]), float(n[2])};
  if (srgb) *c = {SrgbToLinear(c->r), SrgbToLinear(c->g), SrgbToLinear(c->b)};
  return Status::Ok();
}

Status ParseSpectrum(const MitsubaNode& node, MitsubaProperty* p) {
  if (node.Attribute("filename"))
    return Unsupported(node, "<spectrum filename=...> (spectra from files)");
  const std::string& text = *node.Attribute("value");
  std::vector<std::string_view> items;
  if (!SplitList(text, &items) || items.empty())
    return node.Error("malformed spectrum '" + text +
                      "'; expected a number or "
                      "'wavelength:value, ...' pairs");
  if (items.size() == 1 && items[0].find(':') == std::string_view::npos) {
    float v = 0;
    if (!ParseFloat(items[0], &v))
      return node.Error("malformed number '" + text + "' in attribute 'value'");
    p->number = v;
    return Status::Ok();
  }
  for (const std::string_view item : items) {
    const size_t colon = item.find(':');
    float w = 0, v = 0;
    if (colon == std::string_view::npos || !ParseFloat(item.substr(0, colon), &w) ||
        !ParseFloat(item.substr(colon + 1), &v))
      return node.Error("malformed spectrum entry '" + std::string(item) +
                        "'; expected wavelength:value (nm:number)");
    if (!p->wavelengths.empty() && !(w > p->wavelengths.back()))
      return node.Error("spectrum wavelengths must increase ('" + std::string(item) + "')");
    p->wavelengths.push_back(w);
    p->values.push_back(v);
  }
  if (p->wavelengths.size() < 2)
    return node.Error("a spectrum list needs at least two wavelength:value pairs");
  return Status::Ok();
}

const char* TypeTag(MitsubaProperty::Type t) {
  using T = MitsubaProperty::Type;
  switch (t) {
    case T::kBoolean:
      return "boolean";
    case T::kInteger:
      return "integer";
    case T::kFloat:
      return "float";
    case T::kString:
      return "string";
    case T::kPoint:
      return "point";
    case T::kVector:
      return "vector";
    case T::kRgb:
      return "rgb";
    case T::kSpectrum:
      return "spectrum";
    case T::kTransform:
      return "transform";
    case T::kObject:
      return "texture (or other object)";
  }
  return "?";
}

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

Status ParseMitsubaTransform(const MitsubaNode& node, Transform* result) {
  Transform t;
  for (const MitsubaNode& step : node.children) {
    PTLAB_RETURN_IF_ERROR(Leaf(step));
    Transform s;
    if (step.tag == "translate") {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(step, {"x", "y", "z", "value"}, {}));
      Vec3f v;
      PTLAB_RETURN_IF_ERROR(XyzVector(step, 0.0f, true, &v));
      s = Transform::Translate(v);
    } else if (step.tag == "scale") {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(step, {"x", "y", "z", "value"}, {}));
      Vec3f v;
      PTLAB_RETURN_IF_ERROR(XyzVector(step, 1.0f, true, &v));
      if (v.x == 0 || v.y == 0 || v.z == 0)
        return step.Error("singular <scale>; expected non-zero scale factors");
      s = Transform::Scale(v);
    } else if (step.tag == "rotate") {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(step, {"x", "y", "z", "value", "angle"}, {"angle"}));
      Vec3f axis;
      PTLAB_RETURN_IF_ERROR(XyzVector(step, 0.0f, false, &axis));
      float angle = 0;
      if (!ParseFloat(*step.Attribute("angle"), &angle))
        return step.Error("malformed angle '" + *step.Attribute("angle") +
                          "'; expected degrees as a finite decimal number");
      if (!(Length(axis) > 0)) return step.Error("zero <rotate> axis; expected a non-zero axis");
      s = Transform::Rotate(axis, angle);
    } else if (step.tag == "matrix") {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(step, {"value"}, {"value"}));
      std::vector<double> n;
      PTLAB_RETURN_IF_ERROR(Numbers(step, "value", &n));
      if (n.size() != 16 && n.size() != 9)
        return step.Error("<matrix> has " + std::to_string(n.size()) +
                          " numbers; expected 16 (4x4) or 9 (3x3), row-major");
      const int dim = n.size() == 16 ? 4 : 3;
      Matrix4 m, inv;
      for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j) m.m[i][j] = float(n[size_t(dim * i + j)]);
      if (!Inverse(m, &inv)) return step.Error("singular <matrix>; expected an invertible matrix");
      s = Transform(m, inv);
    } else if (step.tag == "lookat") {
      PTLAB_RETURN_IF_ERROR(
          CheckAttributes(step, {"origin", "target", "up"}, {"origin", "target"}));
      Vec3f origin, target, up{0, 0, 0};
      PTLAB_RETURN_IF_ERROR(ParseVec3Attribute(step, "origin", &origin));
      PTLAB_RETURN_IF_ERROR(ParseVec3Attribute(step, "target", &target));
      if (step.Attribute("up")) PTLAB_RETURN_IF_ERROR(ParseVec3Attribute(step, "up", &up));
      if (!(Length(target - origin) > 0))
        return step.Error("degenerate <lookat>: expected target != origin");
      const Vec3f dir = Normalize(target - origin);
      if (!(Length(up) > 0)) {
        // Mitsuba picks some up vector perpendicular to dir.
        up =
            std::fabs(dir.x) > std::fabs(dir.y) ? Vec3f{-dir.z, 0, dir.x} : Vec3f{0, dir.z, -dir.y};
      }
      const Vec3f left_raw = Cross(Normalize(up), dir);
      if (!(Length(left_raw) > 1e-6f))
        return step.Error("degenerate <lookat>: expected 'up' not parallel to target - origin");
      const Vec3f left = Normalize(left_raw), new_up = Normalize(Cross(dir, left));
      Matrix4 m, inv;
      const Vec3f columns[4] = {left, new_up, dir, origin};
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) m.m[r][c] = columns[c][r];
      if (!Inverse(m, &inv)) return step.Error("degenerate <lookat>");
      s = Transform(m, inv);
    } else {
      return step.Error("unknown transform step <" + step.tag +
                        ">; expected translate, scale, rotate, matrix or lookat");
    }
    t = s * t;
    for (const Matrix4* m : {&t.matrix(), &t.inverse_matrix()})
      for (const auto& row : m->m)
        for (const float x : row)
          if (!(std::fabs(x) <= 1e30f))
            return step.Error("<" + step.tag +
                              "> makes the transform (or its inverse) overflow; expected "
                              "matrix entries of magnitude <= 1e30");
  }
  *result = t;
  return Status::Ok();
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

Status MitsubaObject::Expect(const std::vector<const char*>& names) const {
  for (const MitsubaProperty& p : props_)
    if (std::none_of(names.begin(), names.end(), [&](const char* n) { return p.name == n; }))
      return p.node->Error(
          "unknown property '" + p.name + "' for " + DescribeMitsuba(*node_) + "; expected " +
          (names.empty() ? std::string("no properties") : "one of: " + Join(names)));
  return Status::Ok();
}

const MitsubaProperty* MitsubaObject::Get(const char* name) const {
  for (const MitsubaProperty& p : props_)
    if (p.name == name) return &p;
  return nullptr;
}

Status MitsubaObject::Find(const char* name, std::initializer_list<MitsubaProperty::Type> types,
                           const char* expected, const MitsubaProperty** found) const {
  *found = Get(name);
  if (*found && std::find(types.begin(), types.end(), (*found)->type) == types.end()) {
    if ((*found)->type == MitsubaProperty::Type::kObject)
      return Unsupported(*(*found)->object,
                         std::string("as property '") + name + "' of " + DescribeMitsuba(*node_));
    return (*found)->node->Error(std::string("property '") + name + "' of " +
                                 DescribeMitsuba(*node_) + " has the wrong type <" +
                                 TypeTag((*found)->type) + ">; expected " + expected);
  }
  return Status::Ok();
}

Status MitsubaObject::Boolean(const char* name, bool* v) const {
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(Find(name, {MitsubaProperty::Type::kBoolean}, "<boolean>", &p));
  if (p) *v = p->boolean;
  return Status::Ok();
}

Status MitsubaObject::Integer(const char* name, int* v) const {
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(Find(name, {MitsubaProperty::Type::kInteger}, "<integer>", &p));
  if (p) *v = int(p->integer);
  return Status::Ok();
}

Status MitsubaObject::Float(const char* name, float* v) const {
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(
      Find(name, {MitsubaProperty::Type::kFloat, MitsubaProperty::Type::kInteger}, "<float>", &p));
  if (p) *v = p->type == MitsubaProperty::Type::kFloat ? float(p->number) : float(p->integer);
  return Status::Ok();
}

Status MitsubaObject::String(const char* name, std::string* v) const {
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(Find(name, {MitsubaProperty::Type::kString}, "<string>", &p));
  if (p) *v = p->text;
  return Status::Ok();
}

Status MitsubaObject::Point(const char* name, Vec3f* v) const {
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(
      Find(name, {MitsubaProperty::Type::kPoint, MitsubaProperty::Type::kVector}, "<point>", &p));
  if (p) *v = p->vec;
  return Status::Ok();
}

Status MitsubaObject::Vector(const char* name, Vec3f* v) const {
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(
      Find(name, {MitsubaProperty::Type::kVector, MitsubaProperty::Type::kPoint}, "<vector>", &p));
  if (p) *v = p->vec;
  return Status::Ok();
}

Status MitsubaObject::TransformProperty(const char* name, Transform* v) const {
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(Find(name, {MitsubaProperty::Type::kTransform}, "<transform>", &p));
  if (p) *v = p->transform;
  return Status::Ok();
}

Status MitsubaObject::Color(const char* name, SpectrumUse use, Color3f* v) const {
  using T = MitsubaProperty::Type;
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(Find(name, {T::kRgb, T::kSpectrum, T::kFloat, T::kInteger},
                             "<rgb>, <spectrum> or <float>", &p));
  if (!p) return Status::Ok();
  switch (p->type) {
    case T::kRgb:
      *v = p->rgb;
      break;
    case T::kFloat:
    case T::kInteger: {
      const float x = p->type == T::kFloat ? float(p->number) : float(p->integer);
      *v = {x, x, x};
      break;
    }
    case T::kSpectrum:
      if (!p->wavelengths.empty()) {
        *v = SpectrumToRgb(p->wavelengths, p->values, use);
      } else if (use == SpectrumUse::kEmission) {
        // Mitsuba's rgb variants turn a uniform emission spectrum into the sRGB of an
        // equal-energy spectrum: value · xyz_to_srgb(1, 1, 1) (not grey: sRGB's white is D65).
        const float x = float(p->number);
        *v = {x * (3.240479f - 1.537150f - 0.498535f), x * (-0.969256f + 1.875991f + 0.041556f),
              x * (0.055648f - 0.204043f + 1.057311f)};
      } else {
        const float x = float(p->number);
        *v = {x, x, x};
      }
      break;
    default:
      break;
  }
  return Status::Ok();
}

Status MitsubaObject::OnlyDefault(const char* name, bool fallback) const {
  bool value = fallback;
  PTLAB_RETURN_IF_ERROR(Boolean(name, &value));
  if (value == fallback) return Status::Ok();
  return Error(name, "unsupported: " + node_->tag + " \"" + type_ + "\" with " + name + " = " +
                         (value ? "true" : "false"));
}

Status MitsubaObject::SamplingWeight() const {
  float weight = 1;
  PTLAB_RETURN_IF_ERROR(Float("sampling_weight", &weight));
  if (!(weight > 0)) return Error("sampling_weight", "sampling_weight must be > 0");
  return Status::Ok();
}

Status MitsubaObject::Error(const char* name, const std::string& message) const {
  const MitsubaProperty* p = Get(name);
  return (p ? *p->node : *node_).Error(message);
}

Status MitsubaObject::Require(const char* name) const {
  if (Has(name)) return Status::Ok();
  return node_->Error(DescribeMitsuba(*node_) + " is missing the required property '" + name + "'");
}

}  // namespace ptlab::internal
