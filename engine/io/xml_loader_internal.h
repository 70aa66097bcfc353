// Entry points into the Nori XML parser for loaders of other root elements (Nori test files).
#pragma once

#include <pugixml.hpp>
#include <string>
#include <vector>

#include "engine/core/status.h"
#include "engine/scene/material_tables.h"
#include "engine/scene/scene.h"
#include "engine/io/xml_loader.h"

namespace ptlab::internal {

/// Parses `node`, a <scene> element anywhere in a document loaded from the text `xml` (used for
/// the line:column of messages, which name `display_name`), exactly as LoadScene parses a root
/// <scene>: relative file names resolve against `base_dir`, area lights are finalized and
/// scene.source_path = display_name.
StatusOr<Scene> ParseSceneElement(const std::string& xml, const pugi::xml_node& node,
                                  const std::string& base_dir, const std::string& display_name,
                                  const LoadOptions& options);

/// BSDFs parsed outside a shape: their rows, and a reference per parsed element in order.
struct ParsedBsdfs {
  MaterialTables materials;
  std::vector<MaterialRef> refs;
};

/// Parses each <bsdf> element of `nodes` (from a document loaded from `xml`) as LoadScene
/// parses a shape's <bsdf>, with the same types, defaults, ranges and messages.
StatusOr<ParsedBsdfs> ParseBsdfElements(const std::string& xml,
                                        const std::vector<pugi::xml_node>& nodes,
                                        const std::string& display_name);

}  // namespace ptlab::internal
