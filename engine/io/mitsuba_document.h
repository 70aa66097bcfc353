// A Mitsuba scene file read into one element tree: <include>s spliced in, <default>s and `-D`
// parameters substituted for `$name`, <path>s collected as search paths.
#pragma once

#include <cstddef>
#include <cstdint>
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
  /// Bytes of the main file and of every included file (once each): what the scene's
  /// expansion budget (ExpansionBudgetBytes) is measured against.
  uint64_t input_bytes = 0;
};

/// Maximum depth of nested <include>s (the main file is depth 0).
inline constexpr int kMaxMitsubaIncludeDepth = 16;
/// Maximum nesting of elements inside one top-level element (30,000 levels overflowed the
/// stack of the recursive copy).
inline constexpr int kMaxMitsubaElementDepth = 256;
/// Budgets of what a small file can expand into: an attribute value after `$name`
/// substitution, all bytes that substitutions insert over the document (a parameter doubled
/// 34 times in <default>s grew to 256 GiB), and the XML read again when a file is included
/// more than once, and how many includes are read (10 includes of a file that includes 10 ...,
/// 7 levels deep, hung).
inline constexpr size_t kMaxMitsubaValueBytes = size_t(1) << 20;
inline constexpr size_t kMaxMitsubaSubstitutedBytes = size_t(32) << 20;
inline constexpr size_t kMaxMitsubaRepeatedIncludeBytes = size_t(32) << 20;
/// Most <include>s read in one document (each file opened again counts).
inline constexpr size_t kMaxMitsubaIncludes = 65536;

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
