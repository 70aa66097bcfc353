// Nori XML building blocks: attribute and leaf checks, numbers, transforms, property lists.
#include "engine/io/xml_properties.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>

#include "engine/io/lookat_range.h"
#include "engine/io/text_parsing.h"

namespace ptlab::internal {

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
      if (const std::string range = LookatRangeError(origin, target, up); !range.empty())
        return at.Error(step, range);
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
            // Appended rather than "<" + std::string(tag): GCC 12 warns (-Wrestrict) on that
            // insert at the front, a known false positive.
            return at.Error(step, std::string("<").append(tag) +
                                      "> makes the transform (or its inverse) overflow; expected "
                                      "matrix entries of magnitude <= 1e30");
  }
  *result = t;
  return Status::Ok();
}

bool PropertyTypeOf(std::string_view tag, PropertyType* type) {
  for (int i = 0; i < 8; ++i)
    if (tag == kPropertyTags[i]) {
      *type = PropertyType(i);
      return true;
    }
  return false;
}

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

}  // namespace ptlab::internal
