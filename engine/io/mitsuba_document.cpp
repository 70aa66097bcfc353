// Mitsuba scene preprocessing: parameters, includes and search paths.
#include "engine/io/mitsuba_document.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <memory>
#include <pugixml.hpp>

#include "engine/io/text_parsing.h"
#include "engine/io/xml_locator.h"

namespace ptlab::internal {
namespace {

namespace fs = std::filesystem;

bool IsNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

class Preprocessor {
 public:
  explicit Preprocessor(const LoadOptions& options) : options_(options) {}

  Status SetDefines(const std::string& where) {
    for (const std::string& define : options_.defines) {
      const size_t eq = define.find('=');
      const std::string name = define.substr(0, eq == std::string::npos ? 0 : eq);
      if (eq == std::string::npos || name.empty() ||
          !std::all_of(name.begin(), name.end(), IsNameChar))
        return Status::Error(where + ": malformed parameter definition '" + define +
                             "' (-D); expected name=value with a name of letters, digits and _");
      params_[name] = define.substr(eq + 1);
    }
    return Status::Ok();
  }

  // Parses one file's text and appends its <scene>'s children (preprocessed) to `out`.
  Status ReadScene(const std::string& xml, const std::string& dir, const std::string& display,
                   int depth, MitsubaNode* out, std::string* version) {
    auto at = std::make_unique<XmlLocator>(xml, display, options_);
    pugi::xml_document doc;
    const pugi::xml_parse_result result =
        doc.load_buffer(xml.data(), xml.size(), pugi::parse_default, pugi::encoding_utf8);
    if (result.status == pugi::status_no_document_element)
      return Status::Error(at->AtOffset(0) + ": no root element; expected a <scene> element");
    if (!result)
      return Status::Error(at->AtOffset(result.offset) +
                           ": XML syntax error: " + result.description());
    pugi::xml_node root;
    PTLAB_RETURN_IF_ERROR(at->FindSingleRoot(doc, "scene", &root));
    if (std::string_view(root.name()) != "scene")
      return at->Error(root, "root element <" + std::string(root.name()) + ">; expected <scene>");
    for (const pugi::xml_attribute a : root.attributes()) {
      if (std::string_view(a.name()) != "version")
        return at->Error(
            root, "unknown attribute '" + std::string(a.name()) + "' on <scene>; expected version");
    }
    if (!root.attribute("version"))
      return at->Error(root, "<scene> is missing the attribute 'version' (a Mitsuba scene)");
    if (version) *version = root.attribute("version").value();
    if (out->where.empty()) {
      out->tag = "scene";
      out->where = at->At(root);
    }
    const XmlLocator* locator = at.get();
    locators_.push_back(std::move(at));
    for (const pugi::xml_node child : root.children())
      PTLAB_RETURN_IF_ERROR(SceneChild(*locator, child, dir, depth, out));
    return Status::Ok();
  }

  std::vector<std::string> search_paths;  // most recent first
  std::vector<std::string> files;
  std::vector<std::string> include_stack;  // canonical paths of the files being read
  uint64_t distinct_bytes = 0;             // bytes of the included files, each once

 private:
  Status SceneChild(const XmlLocator& at, const pugi::xml_node& node, const std::string& dir,
                    int depth, MitsubaNode* out) {
    if (node.type() == pugi::node_pcdata || node.type() == pugi::node_cdata)
      return at.Error(node.parent(), "unexpected text inside <scene>; expected only elements");
    if (node.type() != pugi::node_element) return Status::Ok();
    const std::string_view tag = node.name();
    if (tag == "default") {
      std::string name, value;
      PTLAB_RETURN_IF_ERROR(NameValue(at, node, &name, &value));
      if (!params_.count(name)) params_[name] = value;  // -D and earlier ones win
      return Status::Ok();
    }
    if (tag == "path") {
      std::string value;
      PTLAB_RETURN_IF_ERROR(OnlyAttribute(at, node, "value", &value));
      fs::path p(value);
      if (p.is_relative()) p = fs::path(dir) / p;
      std::error_code ec;
      if (!fs::is_directory(p, ec))
        return at.Error(node, "<path>: folder '" + p.lexically_normal().string() +
                                  "' not found; expected an existing directory");
      search_paths.insert(search_paths.begin(), p.lexically_normal().string());
      return Status::Ok();
    }
    if (tag == "include") {
      std::string filename;
      PTLAB_RETURN_IF_ERROR(OnlyAttribute(at, node, "filename", &filename));
      std::vector<std::string> paths = {dir};
      paths.insert(paths.end(), search_paths.begin(), search_paths.end());
      const std::string path = ResolveMitsubaPath(paths, filename);
      if (path.empty())
        return at.Error(node, "<include>: file '" + filename +
                                  "' not found in the including file's folder or the <path>s");
      std::error_code ec;
      const std::string canonical = fs::weakly_canonical(path, ec).string();
      for (const std::string& open : include_stack)
        if (open == canonical)
          return at.Error(node, "<include> cycle: '" + path +
                                    "' is already being read; expected no file to include itself");
      if (depth + 1 > kMaxMitsubaIncludeDepth)
        return at.Error(node, "<include> nesting deeper than " +
                                  std::to_string(kMaxMitsubaIncludeDepth) + " levels");
      if (++include_count_ > kMaxMitsubaIncludes)
        return at.Error(node, "<include>: more than " + std::to_string(kMaxMitsubaIncludes) +
                                  " includes read for one scene (files included more than once "
                                  "count each time); expected at most that");
      std::string text;
      Status read = ReadTextFile(path, "included scene", &text);
      if (!read.ok()) return at.Error(node, "<include>: " + read.message());
      if (std::find(files.begin(), files.end(), path) != files.end()) {
        repeated_include_bytes_ += text.size();
        if (repeated_include_bytes_ > kMaxMitsubaRepeatedIncludeBytes)
          return at.Error(node, "<include>: '" + path + "' is included again, and the files " +
                                    "included more than once now add up to " +
                                    std::to_string(repeated_include_bytes_) +
                                    " bytes; expected at most " +
                                    std::to_string(kMaxMitsubaRepeatedIncludeBytes));
      } else {
        files.push_back(path);
        distinct_bytes += text.size();
      }
      include_stack.push_back(canonical);
      Status s =
          ReadScene(text, fs::path(path).parent_path().string(), path, depth + 1, out, nullptr);
      include_stack.pop_back();
      return s;
    }
    MitsubaNode child;
    PTLAB_RETURN_IF_ERROR(Copy(at, node, 1, &child));
    out->children.push_back(std::move(child));
    return Status::Ok();
  }

  Status Copy(const XmlLocator& at, const pugi::xml_node& node, int depth, MitsubaNode* out) {
    if (depth > kMaxMitsubaElementDepth)
      return at.Error(node, "elements nested deeper than " +
                                std::to_string(kMaxMitsubaElementDepth) +
                                " levels; expected at most " +
                                std::to_string(kMaxMitsubaElementDepth));
    out->tag = node.name();
    out->where = at.At(node);
    const std::string_view tag = out->tag;
    if (tag == "default" || tag == "path" || tag == "include")
      return at.Error(node, "<" + out->tag + "> is only allowed directly inside <scene>");
    for (const pugi::xml_attribute a : node.attributes()) {
      std::string value;
      PTLAB_RETURN_IF_ERROR(Substitute(at, node, a.value(), &value));
      out->attributes.emplace_back(a.name(), std::move(value));
    }
    for (const pugi::xml_node child : node.children()) {
      if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata)
        return at.Error(node, "unexpected text inside <" + out->tag + ">; expected only elements");
      if (child.type() != pugi::node_element) continue;
      MitsubaNode c;
      PTLAB_RETURN_IF_ERROR(Copy(at, child, depth + 1, &c));
      out->children.push_back(std::move(c));
    }
    return Status::Ok();
  }

  Status Substitute(const XmlLocator& at, const pugi::xml_node& node, std::string_view text,
                    std::string* out) {
    out->clear();
    for (size_t i = 0; i < text.size();) {
      if (text[i] != '$') {
        out->push_back(text[i++]);
        continue;
      }
      size_t end = i + 1;
      while (end < text.size() && IsNameChar(text[end])) ++end;
      const std::string name(text.substr(i + 1, end - i - 1));
      const auto it = params_.find(name);
      if (name.empty() || it == params_.end())
        return at.Error(node, "unknown parameter '$" + name + "' in '" + std::string(text) +
                                  "'; expected a name set by <default name=\"" + name +
                                  "\" value=...> or -D " + name + "=...");
      if (out->size() + it->second.size() > kMaxMitsubaValueBytes)
        return at.Error(node, "the value with '$" + name + "' would grow past " +
                                  std::to_string(kMaxMitsubaValueBytes) +
                                  " bytes; expected at most that after substitution");
      substituted_bytes_ += it->second.size();
      if (substituted_bytes_ > kMaxMitsubaSubstitutedBytes)
        return at.Error(node, "parameter substitutions ('$" + name + "') insert more than " +
                                  std::to_string(kMaxMitsubaSubstitutedBytes) +
                                  " bytes over the scene; expected at most that");
      *out += it->second;
      i = end;
    }
    return Status::Ok();
  }

  Status NameValue(const XmlLocator& at, const pugi::xml_node& node, std::string* name,
                   std::string* value) {
    for (const pugi::xml_attribute a : node.attributes())
      if (std::string_view(a.name()) != "name" && std::string_view(a.name()) != "value")
        return at.Error(node, "unknown attribute '" + std::string(a.name()) +
                                  "' on <default>; expected name, value");
    if (!node.attribute("name") || !node.attribute("value"))
      return at.Error(node, "<default> needs the attributes 'name' and 'value'");
    if (node.first_child()) return at.Error(node, "<default> takes no children");
    *name = node.attribute("name").value();
    if (name->empty() || !std::all_of(name->begin(), name->end(), IsNameChar))
      return at.Error(node,
                      "malformed parameter name '" + *name + "'; expected letters, digits and _");
    return Substitute(at, node, node.attribute("value").value(), value);
  }

  Status OnlyAttribute(const XmlLocator& at, const pugi::xml_node& node, const char* attribute,
                       std::string* value) {
    for (const pugi::xml_attribute a : node.attributes())
      if (std::string_view(a.name()) != attribute)
        return at.Error(node, "unknown attribute '" + std::string(a.name()) + "' on <" +
                                  node.name() + ">; expected " + attribute);
    if (!node.attribute(attribute))
      return at.Error(
          node, "<" + std::string(node.name()) + "> is missing the attribute '" + attribute + "'");
    if (node.first_child())
      return at.Error(node, "<" + std::string(node.name()) + "> takes no children");
    return Substitute(at, node, node.attribute(attribute).value(), value);
  }

  const LoadOptions& options_;
  std::map<std::string, std::string> params_;
  size_t substituted_bytes_ = 0;       // against kMaxMitsubaSubstitutedBytes
  size_t repeated_include_bytes_ = 0;  // against kMaxMitsubaRepeatedIncludeBytes
  size_t include_count_ = 0;           // against kMaxMitsubaIncludes
  std::vector<std::unique_ptr<XmlLocator>> locators_;
};

}  // namespace

std::string ResolveMitsubaPath(const std::vector<std::string>& search_paths,
                               const std::string& name) {
  std::error_code ec;
  const fs::path p(name);
  if (p.is_absolute()) return fs::exists(p, ec) ? p.lexically_normal().string() : "";
  for (const std::string& dir : search_paths) {
    const fs::path candidate = (fs::path(dir) / p).lexically_normal();
    if (fs::exists(candidate, ec)) return candidate.string();
  }
  return "";
}

StatusOr<MitsubaDocument> ReadMitsubaDocument(const std::string& xml, const std::string& base_dir,
                                              const std::string& display_name,
                                              const LoadOptions& options) {
  Preprocessor pre(options);
  PTLAB_RETURN_IF_ERROR(pre.SetDefines(display_name));
  MitsubaDocument doc;
  std::error_code ec;
  pre.include_stack.push_back(fs::weakly_canonical(display_name, ec).string());
  PTLAB_RETURN_IF_ERROR(pre.ReadScene(xml, base_dir, display_name, 0, &doc.root, &doc.version));
  doc.search_paths = pre.search_paths;
  doc.search_paths.push_back(base_dir.empty() ? "." : base_dir);
  doc.files = pre.files;
  doc.input_bytes = xml.size() + pre.distinct_bytes;
  return doc;
}

bool LooksLikeMitsubaScene(const std::string& xml) {
  pugi::xml_document doc;
  // Only the start tag matters: parse the head and accept the unfinished-document error.
  const std::string head = xml.substr(0, 65536);
  doc.load_buffer(head.data(), head.size(), pugi::parse_default, pugi::encoding_utf8);
  const pugi::xml_node root = doc.document_element();
  if (!root || std::string_view(root.name()) != "scene") return false;
  if (root.attribute("version")) return true;
  for (const pugi::xml_node child : root.children()) {
    const std::string_view tag = child.name();
    if (tag == "sensor" || tag == "default" || tag == "include" || tag == "path") return true;
  }
  return false;
}

}  // namespace ptlab::internal
