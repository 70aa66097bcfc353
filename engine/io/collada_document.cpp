// Ids, strict child lists and number parsing for the COLLADA readers.
#include "engine/io/collada_document.h"

#include <algorithm>
#include <cstdint>
#include <string>

#include "engine/scene/scene_limits.h"
#include "engine/io/text_parsing.h"

namespace ptlab::collada {
namespace {

// Whitespace-separated tokens of `text` (COLLADA lists use whitespace only).
template <typename F>
bool ForEachToken(std::string_view text, F&& f) {
  size_t i = 0;
  const size_t n = text.size();
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (i < n) {
    while (i < n && space(text[i])) ++i;
    const size_t start = i;
    while (i < n && !space(text[i])) ++i;
    if (i > start && !f(text.substr(start, i - start))) return false;
  }
  return true;
}

}  // namespace

Status Document::IndexIds(const pugi::xml_node& root) {
  std::vector<pugi::xml_node> stack = {root};
  while (!stack.empty()) {
    const pugi::xml_node node = stack.back();
    stack.pop_back();
    if (const pugi::xml_attribute id = node.attribute("id")) {
      const auto [it, inserted] = ids.emplace(id.value(), node);
      if (!inserted)
        return Error(node, std::string("duplicate id '") + std::string(id.value()) + "' (first at " +
                               at.At(it->second) + ")");
    }
    for (const pugi::xml_node child : node.children())
      if (child.type() == pugi::node_element) stack.push_back(child);
  }
  return Status::Ok();
}

Status Document::NotSupported(const pugi::xml_node& node, const std::string& what) const {
  return Status::Error(std::string("not supported yet: <") + std::string(node.name()) + ">" +
                       (what.empty() ? "" : " (" + what + ")") + " at " + at.At(node));
}

Status Document::Resolve(const pugi::xml_node& node, const char* attribute, std::string_view tag,
                         pugi::xml_node* target) const {
  const pugi::xml_attribute a = node.attribute(attribute);
  if (!a)
    return Error(node, std::string("<") + std::string(node.name()) + "> has no '" + attribute +
                           std::string("' attribute; expected a reference \"#id\" to a <") + std::string(tag) +
                           ">");
  const std::string_view value = a.value();
  if (value.size() < 2 || value[0] != '#')
    return Error(node, std::string(attribute) + std::string("=\"") + std::string(value) +
                           "\" is not a local reference; expected \"#id\" of a <" +
                           std::string(tag) + "> (external documents are not supported yet)");
  const auto it = ids.find(std::string(value.substr(1)));
  if (it == ids.end())
    return Error(node, std::string(attribute) + std::string("=\"") + std::string(value) +
                           "\" names no element of this file; expected the id of a <" +
                           std::string(tag) + ">");
  if (tag != it->second.name())
    return Error(node, std::string(attribute) + std::string("=\"") + std::string(value) + "\" names a <" +
                           it->second.name() + "> (at " + at.At(it->second) + "); expected a <" +
                           std::string(tag) + ">");
  *target = it->second;
  return Status::Ok();
}

Status Document::CheckChildren(const pugi::xml_node& node,
                               std::initializer_list<std::string_view> allowed,
                               bool extras) const {
  for (const pugi::xml_node child : node.children()) {
    if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) {
      if (std::string_view(child.value()).find_first_not_of(" \t\r\n") != std::string_view::npos)
        return Error(child, std::string("unexpected text inside <") + std::string(node.name()) + ">");
      continue;
    }
    if (child.type() != pugi::node_element) continue;
    const std::string_view name = child.name();
    if (extras && name == "extra") continue;
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
      return NotSupported(child, std::string("inside <") + std::string(node.name()) + ">");
  }
  return Status::Ok();
}

Status Document::Floats(const pugi::xml_node& node, std::vector<float>* values) const {
  values->clear();
  std::string error;
  const bool ok = ForEachToken(node.child_value(), [&](std::string_view token) {
    float v = 0;
    if (ParseNumberQuietly<float>(token, -kMaxRadiance, kMaxRadiance, &v) != NumberError::kOk) {
      error = ParseNumber<float>(token, -kMaxRadiance, kMaxRadiance, &v);
      return false;
    }
    values->push_back(v);
    return true;
  });
  if (!ok)
    return Error(node, "in <" + std::string(node.name()) + ">: " + error +
                           " (COLLADA numbers are finite decimals)");
  return Status::Ok();
}

Status Document::Indices(const pugi::xml_node& node, std::vector<uint32_t>* values) const {
  values->clear();
  std::string bad;
  const bool ok = ForEachToken(node.child_value(), [&](std::string_view token) {
    int v = 0;
    if (!ParseInt(token, &v) || v < 0) {
      bad = std::string(token);
      return false;
    }
    values->push_back(uint32_t(v));
    return true;
  });
  if (!ok)
    return Error(node, "'" + bad + std::string("' in <") + std::string(node.name()) +
                           "> is not an index; expected integers >= 0");
  return Status::Ok();
}

Status Document::FixedFloats(const pugi::xml_node& node, size_t count, float* values) const {
  std::vector<float> v;
  PTLAB_RETURN_IF_ERROR(Floats(node, &v));
  if (v.size() != count)
    return Error(node, std::string("<") + std::string(node.name()) + "> holds " + std::to_string(v.size()) +
                           " numbers; expected " + std::to_string(count));
  std::copy(v.begin(), v.end(), values);
  return Status::Ok();
}

Status Document::Color(const pugi::xml_node& node, Color3f* color) const {
  std::vector<float> v;
  PTLAB_RETURN_IF_ERROR(Floats(node, &v));
  if (v.size() != 3 && v.size() != 4)
    return Error(node, std::string("<") + std::string(node.name()) + "> holds " + std::to_string(v.size()) +
                           " numbers; expected an RGB color (3 numbers, or 4 with alpha)");
  if (v[0] < 0 || v[1] < 0 || v[2] < 0)
    return Error(node, std::string("<") + std::string(node.name()) + "> has a negative component; expected "
                                                          "values >= 0");
  *color = {v[0], v[1], v[2]};
  return Status::Ok();
}

Status Document::OptionalFloat(const pugi::xml_node& node, const char* name, float* value) const {
  const pugi::xml_node child = node.child(name);
  if (!child) return Status::Ok();
  return FixedFloats(child, 1, value);
}

pugi::xml_node Document::CglTechnique(const pugi::xml_node& node) const {
  for (const pugi::xml_node extra : node.children("extra"))
    for (const pugi::xml_node technique : extra.children("technique"))
      if (std::string_view(technique.attribute("profile").value()) == "CGL") return technique;
  return pugi::xml_node();
}

}  // namespace ptlab::collada
