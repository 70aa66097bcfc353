// The parsed COLLADA document shared by the COLLADA readers: ids, locations, strict children.
#pragma once

#include <pugixml.hpp>
#include <initializer_list>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "engine/core/status.h"
#include "engine/core/vec.h"
#include "engine/io/xml_locator.h"

namespace ptlab::collada {

/// The document, its "file:line:col" locator and every element with an id.
struct Document {
  explicit Document(const internal::XmlLocator& locator) : at(locator) {}
  const internal::XmlLocator& at;
  std::unordered_map<std::string, pugi::xml_node> ids;

  /// Fills `ids`; an error for two elements with the same id.
  Status IndexIds(const pugi::xml_node& root);

  /// "not supported yet: <name> at file:line:col" (`what` adds a detail after the name).
  Status NotSupported(const pugi::xml_node& node, const std::string& what = "") const;
  Status Error(const pugi::xml_node& node, const std::string& message) const {
    return at.Error(node, message);
  }

  /// The element a "#id" reference in attribute `attribute` of `node` names; it must exist and
  /// be a <tag> element.
  Status Resolve(const pugi::xml_node& node, const char* attribute, std::string_view tag,
                 pugi::xml_node* target) const;

  /// Checks that every child element of `node` is one of `allowed`, that none of `single`
  /// appears twice and that there is no text; "extra" children are allowed when `extras` (their
  /// CGL techniques are read by the caller, other profiles are ignored).
  Status CheckChildren(const pugi::xml_node& node, std::initializer_list<std::string_view> allowed,
                       bool extras = false) const;

  /// The numbers of the text of `node` (whitespace separated, each a finite float).
  Status Floats(const pugi::xml_node& node, std::vector<float>* values) const;
  /// The numbers of the text of `node` as non-negative integers.
  Status Indices(const pugi::xml_node& node, std::vector<uint32_t>* values) const;
  /// Exactly `count` floats (count 1..16) from the text of `node`.
  Status FixedFloats(const pugi::xml_node& node, size_t count, float* values) const;
  /// A color: 3 floats, or 4 with the alpha ignored (COLLADA's <color>), finite and >= 0.
  Status Color(const pugi::xml_node& node, Color3f* color) const;
  /// A single float child `name` of `node` if present (else *value is unchanged).
  Status OptionalFloat(const pugi::xml_node& node, const char* name, float* value) const;
  /// The child <technique profile="CGL"> of `extra` elements under `node`, or a null node.
  pugi::xml_node CglTechnique(const pugi::xml_node& node) const;
};

}  // namespace ptlab::collada
