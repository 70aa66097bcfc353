// Mitsuba value syntax: attribute checks, number lists, vectors, colours, spectra.
#include "engine/io/mitsuba_values.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "engine/io/text_parsing.h"

namespace ptlab::internal::mitsuba_values {
namespace {

float SrgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

std::string Join(const std::vector<const char*>& names) {
  std::string s;
  for (const char* n : names) s += (s.empty() ? "" : ", ") + std::string(n);
  return s.empty() ? "none" : s;
}

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

}  // namespace ptlab::internal::mitsuba_values
