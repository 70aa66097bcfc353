// A Mitsuba scene file read into one element tree: <include>s spliced in, <default>s and `-D`
// parameters substituted for `$name`, <path>s collected as search paths.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "engine/core/status.h"
#include "engine/io/xml_loader.h"

namespace ptlab::internal {

/// One element after preprocessing. `where` is "file:line:col" of its '<' in the file it came
/// from (an included file names that file); attribute values have their `$name`s replaced.
struct MitsubaNode {
  std::string tag;
  std::vector<std::pair<std::string, std::string>> attributes;
  std::vector<MitsubaNode> children;
  std::string where;

  /// The attribute's value, or nullptr.
  const std::string* Attribute(const std::string& name) const {
    for (const auto& [key, value] : attributes)
      if (key == name) return &value;
    return nullptr;
  }
  Status Error(const std::string& message) const { return Status::Error(where + ": " + message); }
};

/// The preprocessed scene: root is the <scene> element with the children of every included
/// scene in place of its <include>; search_paths are where relative file names are looked up,
/// in order (the <path>s, last given first, then the main file's directory); files lists every
/// XML file read.
struct MitsubaDocument {
  MitsubaNode root;
  std::string version;  // the root's version attribute
  std::vector<std::string> search_paths;
  std::vector<std::string> files;
};

/// Maximum depth of nested <include>s (the main file is depth 0).
inline constexpr int kMaxMitsubaIncludeDepth = 16;

/// Reads the Mitsuba scene in the text `xml` (what messages call `display_name`, in the folder
/// `base_dir`). Parameters: options.defines ("name=value" each; they win over <default>), then
/// <default name value> in document order (a name already set keeps its value). `$name` in any
/// attribute value is replaced by the parameter's value (the longest name of letters, digits
/// and '_' after '$'); an unknown name is an error. <path value> (root level only) adds a
/// search path, resolved against the directory of its file; <include filename> (root level
/// only) is resolved against that file's directory, then the search paths, must hold a
/// <scene>, and may not include itself (directly or not) or nest deeper than
/// kMaxMitsubaIncludeDepth.
StatusOr<MitsubaDocument> ReadMitsubaDocument(const std::string& xml, const std::string& base_dir,
                                              const std::string& display_name,
                                              const LoadOptions& options);

/// The first of dir/name for dir in search_paths that exists (name itself when absolute); ""
/// when none does.
std::string ResolveMitsubaPath(const std::vector<std::string>& search_paths,
                               const std::string& name);

/// True when the root element of `xml` is a <scene> with a `version` attribute (a Mitsuba 2/3
/// or 0.6 scene) or with a Mitsuba-only child element (<sensor>, <default>, <include>, <path>),
/// looking at the first 64 KiB only.
bool LooksLikeMitsubaScene(const std::string& xml);

}  // namespace ptlab::internal
