// Positions in XML text for error messages ("file:line:col"), shared by the XML loaders.
#pragma once

#include <algorithm>
#include <cstddef>
#include <pugixml.hpp>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/status.h"
#include "engine/io/xml_loader.h"

namespace ptlab::internal {

/// Maps pugixml byte offsets to "file:line:col" (1-based; col counts bytes), and carries the
/// load options to the parsing functions.
class XmlLocator {
 public:
  XmlLocator(const std::string& text, std::string file, const LoadOptions& options = {})
      : file_(std::move(file)), options_(options) {
    line_starts_.push_back(0);
    for (size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') line_starts_.push_back(i + 1);
  }

  std::string AtOffset(ptrdiff_t offset) const {
    if (offset < 0) return file_;
    const size_t line = LineAt(offset);
    const size_t col = size_t(offset) - line_starts_[line - 1] + 1;
    return file_ + ":" + std::to_string(line) + ":" + std::to_string(col);
  }
  /// pugixml gives the offset of an element's name; report its '<' instead.
  std::string At(const pugi::xml_node& node) const { return AtOffset(Offset(node)); }
  size_t Line(const pugi::xml_node& node) const {
    const ptrdiff_t offset = Offset(node);
    return offset < 0 ? 0 : LineAt(offset);
  }
  Status Error(const pugi::xml_node& node, const std::string& message) const {
    return Status::Error(At(node) + ": " + message);
  }
  const std::string& file() const { return file_; }
  const LoadOptions& options() const { return options_; }

  /// The single root element of `doc` in *root; an error for text outside it, a second root
  /// element, or none (`tag` names the expected root, e.g. "scene").
  Status FindSingleRoot(const pugi::xml_document& doc, const std::string& tag,
                        pugi::xml_node* root) const {
    *root = pugi::xml_node();
    for (const pugi::xml_node node : doc.children()) {
      if (node.type() == pugi::node_pcdata || node.type() == pugi::node_cdata)
        return Error(node, "unexpected text outside the root element");
      if (node.type() != pugi::node_element) continue;
      if (*root)
        return Error(node, "a second root element <" + std::string(node.name()) +
                               ">; expected exactly one <" + tag + ">");
      *root = node;
    }
    if (!*root)
      return Status::Error(AtOffset(0) + ": no root element; expected a <" + tag + "> element");
    return Status::Ok();
  }

 private:
  static ptrdiff_t Offset(const pugi::xml_node& node) {
    const ptrdiff_t offset = node.offset_debug();
    return node.type() == pugi::node_element && offset > 0 ? offset - 1 : offset;
  }
  size_t LineAt(ptrdiff_t offset) const {
    return size_t(std::upper_bound(line_starts_.begin(), line_starts_.end(), size_t(offset)) -
                  line_starts_.begin());
  }

  std::string file_;
  LoadOptions options_;
  std::vector<size_t> line_starts_;
};

}  // namespace ptlab::internal
