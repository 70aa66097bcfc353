// Nori test file loader: strict `<test>` properties; scenes and BSDFs go through the XML parser.
#include "engine/io/nori_test_loader.h"

#include <algorithm>
#include <filesystem>
#include <pugixml.hpp>
#include <string_view>
#include <utility>

#include "engine/io/text_parsing.h"
#include "engine/io/xml_loader_internal.h"
#include "engine/io/xml_locator.h"

namespace ptlab {
namespace {

using Locator = internal::XmlLocator;

struct PropertySpec {
  const char* name;
  const char* tag;  // float, integer or string
};

constexpr PropertySpec kTTestProperties[] = {{"significanceLevel", "float"},
                                             {"sampleCount", "integer"},
                                             {"references", "string"},
                                             {"angles", "string"}};
constexpr PropertySpec kChi2TestProperties[] = {{"significanceLevel", "float"},
                                                {"resolution", "integer"},
                                                {"minExpFrequency", "integer"},
                                                {"sampleCount", "integer"},
                                                {"testCount", "integer"}};

bool IsPropertyTag(std::string_view tag) {
  for (const char* t :
       {"boolean", "integer", "float", "string", "point", "vector", "color", "transform"})
    if (tag == t) return true;
  return false;
}

class TestParser {
 public:
  TestParser(const std::string& xml, const Locator& at, std::string base_dir,
             std::string display_name, const LoadOptions& options)
      : xml_(xml),
        at_(at),
        base_dir_(std::move(base_dir)),
        display_name_(std::move(display_name)),
        options_(options) {}

  Status Parse(const pugi::xml_document& doc, NoriTestFile* out) {
    pugi::xml_node root;
    PTLAB_RETURN_IF_ERROR(at_.FindSingleRoot(doc, "test", &root));
    if (std::string_view(root.name()) != "test")
      return at_.Error(root, "root element <" + std::string(root.name()) +
                                 ">; expected <test type=\"ttest\"> or <test type=\"chi2test\"> "
                                 "(scenes are rendered with `ptlab render`)");
    PTLAB_RETURN_IF_ERROR(CheckAttributes(root));
    const std::string type = root.attribute("type").value();
    if (type == "ttest") {
      out->type = NoriTestType::kTTest;
    } else if (type == "chi2test") {
      out->type = NoriTestType::kChi2Test;
      out->properties.sample_count = -1;
    } else {
      return at_.Error(root, "unknown test type '" + type + "'; expected ttest or chi2test");
    }
    root_ = root;
    std::vector<pugi::xml_node> scene_nodes, bsdf_nodes;
    for (const pugi::xml_node child : root.children()) {
      if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata)
        return at_.Error(root, "unexpected text inside <test>; expected only elements");
      if (child.type() != pugi::node_element) continue;
      const std::string_view tag = child.name();
      if (IsPropertyTag(tag)) {
        PTLAB_RETURN_IF_ERROR(ParseProperty(child, out));
      } else if (tag == "scene" && out->type == NoriTestType::kTTest) {
        scene_nodes.push_back(child);
      } else if (tag == "bsdf") {
        bsdf_nodes.push_back(child);
      } else {
        return at_.Error(child,
                         "<" + std::string(tag) + "> is not allowed inside <test type=\"" + type +
                             "\">; expected a property or " +
                             (out->type == NoriTestType::kTTest ? "<scene> or <bsdf>" : "<bsdf>"));
      }
    }
    PTLAB_RETURN_IF_ERROR(CheckCounts(out, scene_nodes, bsdf_nodes));
    for (const pugi::xml_node& node : scene_nodes) {
      StatusOr<Scene> scene =
          internal::ParseSceneElement(xml_, node, base_dir_, display_name_, options_);
      if (!scene.ok()) return scene.status();
      out->scenes.push_back(std::move(*scene));
      out->child_lines.push_back(at_.Line(node));
    }
    if (!bsdf_nodes.empty()) {
      StatusOr<internal::ParsedBsdfs> bsdfs =
          internal::ParseBsdfElements(xml_, bsdf_nodes, display_name_);
      if (!bsdfs.ok()) return bsdfs.status();
      out->materials = std::move(bsdfs->materials);
      out->bsdfs = std::move(bsdfs->refs);
      for (const pugi::xml_node& node : bsdf_nodes) out->child_lines.push_back(at_.Line(node));
    }
    return Status::Ok();
  }

 private:
  Status CheckAttributes(const pugi::xml_node& node) const {
    for (const pugi::xml_attribute a : node.attributes())
      if (std::string_view(a.name()) != "type")
        return at_.Error(
            node, "unknown attribute '" + std::string(a.name()) + "' on <test>; expected type");
    if (!node.attribute("type")) return at_.Error(node, "<test> is missing the attribute 'type'");
    return Status::Ok();
  }

  Status ParseProperty(const pugi::xml_node& node, NoriTestFile* out) {
    const std::string tag = node.name();
    for (const pugi::xml_attribute a : node.attributes()) {
      const std::string_view n = a.name();
      if (n != "name" && n != "value")
        return at_.Error(node, "unknown attribute '" + std::string(n) + "' on <" + tag +
                                   ">; expected name, value");
    }
    if (!node.attribute("name") || !node.attribute("value"))
      return at_.Error(node, "<" + tag + "> needs the attributes 'name' and 'value'");
    for (const pugi::xml_node child : node.children())
      if (child.type() == pugi::node_element || child.type() == pugi::node_pcdata ||
          child.type() == pugi::node_cdata)
        return at_.Error(node,
                         "unexpected content inside <" + tag + ">; expected an empty element");
    const std::string name = node.attribute("name").value();
    const std::string value = node.attribute("value").value();

    const bool ttest = out->type == NoriTestType::kTTest;
    const PropertySpec* begin =
        ttest ? std::begin(kTTestProperties) : std::begin(kChi2TestProperties);
    const PropertySpec* end = ttest ? std::end(kTTestProperties) : std::end(kChi2TestProperties);
    const PropertySpec* spec =
        std::find_if(begin, end, [&](const PropertySpec& s) { return name == s.name; });
    if (spec == end) {
      std::string names;
      for (const PropertySpec* s = begin; s != end; ++s)
        names += (names.empty() ? "" : ", ") + std::string(s->name);
      return at_.Error(node, "unknown property '" + name + "' for <test type=\"" +
                                 (ttest ? "ttest" : "chi2test") + "\">; expected one of: " + names);
    }
    if (tag != spec->tag)
      return at_.Error(node, "property '" + name + "' has the wrong type <" + tag +
                                 ">; expected <" + spec->tag + ">");
    for (const auto& [seen, line] : seen_)
      if (seen == name)
        return at_.Error(node, "duplicate property '" + name + "' (first given at line " +
                                   std::to_string(line) + "); expected each property at most once");
    seen_.emplace_back(name, at_.Line(node));

    NoriTestProperties& p = out->properties;
    if (name == "significanceLevel") {
      std::vector<std::string_view> items;
      float v = 0;
      if (!SplitList(value, &items) || items.size() != 1 || !ParseFloat(items[0], &v))
        return at_.Error(node, "malformed number '" + value + "'; expected one decimal number");
      if (!(v > 0 && v < 1))
        return at_.Error(node,
                         "significanceLevel = " + value + " is out of range; expected (0, 1)");
      p.significance_level = v;
      return Status::Ok();
    }
    if (name == "references" || name == "angles") {
      std::vector<float>* list = name == "references" ? &p.references : &p.angles;
      std::vector<std::string_view> items;
      if (!SplitList(value, &items))
        return at_.Error(node, "malformed list '" + value + "' in '" + name +
                                   "'; expected numbers separated by commas and/or whitespace");
      for (std::string_view item : items) {
        float v = 0;
        if (!ParseFloat(item, &v))
          return at_.Error(node, "malformed number '" + std::string(item) + "' in '" + name +
                                     "'; expected finite decimal numbers");
        list->push_back(v);
      }
      if (list->empty()) return at_.Error(node, "'" + name + "' is empty; expected numbers");
      return Status::Ok();
    }
    int v = 0;
    if (const std::string error = ParseNumber<int>(value, &v); !error.empty())
      return at_.Error(node, "integer " + error);
    if (name == "sampleCount") {
      const bool ok = (ttest ? v >= 2 : (v == -1 || v >= 1)) && v <= kMaxNoriTestSampleCount;
      if (!ok)
        return at_.Error(node, "sampleCount = " + value + " is out of range; expected " +
                                   (ttest ? "2.." : "1..") +
                                   std::to_string(kMaxNoriTestSampleCount) +
                                   (ttest ? "" : ", or -1 for automatic"));
      p.sample_count = v;
    } else {
      const int max = name == "resolution" ? kMaxNoriTestResolution
                                           : (name == "testCount" ? kMaxNoriTestCount
                                                                  : kMaxNoriTestSampleCount);
      if (v < 1 || v > max)
        return at_.Error(node, name + " = " + value + " is out of range; expected 1.." +
                                   std::to_string(max));
      (name == "resolution"        ? p.resolution
       : name == "minExpFrequency" ? p.min_exp_frequency
                                   : p.test_count) = v;
    }
    return Status::Ok();
  }

  int PropertyLine(const char* name) const {
    for (const auto& [seen, line] : seen_)
      if (seen == name) return line;
    return 0;
  }

  // An error at property `name` if it was given, else at the <test> element.
  Status PropertyError(const char* name, const std::string& message) const {
    for (const pugi::xml_node child : root_.children())
      if (IsPropertyTag(child.name()) && std::string_view(child.attribute("name").value()) == name)
        return at_.Error(child, message);
    return at_.Error(root_, message);
  }

  Status CheckCounts(NoriTestFile* out, const std::vector<pugi::xml_node>& scenes,
                     const std::vector<pugi::xml_node>& bsdfs) const {
    const NoriTestProperties& p = out->properties;
    if (out->type == NoriTestType::kChi2Test) {
      if (bsdfs.empty())
        return at_.Error(root_, "<test type=\"chi2test\"> has no <bsdf>; expected one or more");
      if (p.sample_count == -1)
        out->properties.sample_count = p.resolution * 2 * p.resolution * 5000;
      return Status::Ok();
    }
    if (PropertyLine("references") == 0)
      return at_.Error(root_,
                       "<test type=\"ttest\"> is missing the required property <string "
                       "name=\"references\">");
    if (!scenes.empty() && !bsdfs.empty())
      return at_.Error(bsdfs[0],
                       "<bsdf> next to <scene>; expected a t-test of scenes or of BSDFs, "
                       "not both");
    if (scenes.empty() && bsdfs.empty())
      return at_.Error(root_,
                       "<test type=\"ttest\"> has no <scene> or <bsdf>; expected one or more");
    const size_t refs = p.references.size();
    if (!scenes.empty()) {
      if (PropertyLine("angles") != 0)
        return PropertyError("angles",
                             "'angles' in a t-test of scenes; expected angles only "
                             "with <bsdf> children");
      if (refs != scenes.size())
        return PropertyError("references", std::to_string(refs) + " references for " +
                                               std::to_string(scenes.size()) +
                                               " scenes; expected one reference per <scene>");
      return Status::Ok();
    }
    if (PropertyLine("angles") == 0)
      return at_.Error(root_,
                       "a t-test of BSDFs is missing the required property <string "
                       "name=\"angles\">");
    if (refs != p.angles.size() * bsdfs.size())
      return PropertyError("references", std::to_string(refs) + " references for " +
                                             std::to_string(p.angles.size()) + " angles and " +
                                             std::to_string(bsdfs.size()) +
                                             " BSDFs; expected one reference per (BSDF, angle)");
    return Status::Ok();
  }

  const std::string& xml_;
  const Locator& at_;
  std::string base_dir_, display_name_;
  LoadOptions options_;
  pugi::xml_node root_;
  std::vector<std::pair<std::string, int>> seen_;  // property name, line
};

}  // namespace

StatusOr<NoriTestFile> LoadNoriTestFileFromString(const std::string& xml,
                                                  const std::string& base_dir,
                                                  const std::string& display_name,
                                                  const LoadOptions& options) {
  const Locator at(xml, display_name);
  pugi::xml_document doc;
  const pugi::xml_parse_result result =
      doc.load_buffer(xml.data(), xml.size(), pugi::parse_default, pugi::encoding_utf8);
  if (result.status == pugi::status_no_document_element)
    return Status::Error(at.AtOffset(0) + ": no root element; expected <test>");
  if (!result)
    return Status::Error(at.AtOffset(result.offset) +
                         ": XML syntax error: " + result.description());
  NoriTestFile file;
  file.path = display_name;
  TestParser parser(xml, at, base_dir, display_name, options);
  PTLAB_RETURN_IF_ERROR(parser.Parse(doc, &file));
  return file;
}

StatusOr<NoriTestFile> LoadNoriTestFile(const std::string& path, const LoadOptions& options) {
  std::string xml;
  PTLAB_RETURN_IF_ERROR(ReadTextFile(path, "test file", &xml));
  return LoadNoriTestFileFromString(xml, std::filesystem::path(path).parent_path().string(), path,
                                    options);
}

}  // namespace ptlab
