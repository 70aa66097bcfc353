// JSON output of ptlab's tools, written through nlohmann/json (no hand-made escaping): one
// value on one line with ", " and ": " between items, the layout the tools have always
// printed (scripts such as benchmarks/render_times read it with sed).
#pragma once

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

namespace ptlab {

/// An object that keeps its keys in the order they were set.
using Json = nlohmann::ordered_json;

/// A number, or null when it is NaN or Inf (JSON has neither).
inline Json JsonNumberOrNull(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

/// `j` on one line. Strings are escaped by nlohmann/json; bytes that are not UTF-8 (a path's,
/// say) become U+FFFD instead of an exception.
inline std::string DumpJsonLine(const Json& j) {
  const auto scalar = [](const Json& v) {
    return v.dump(-1, ' ', false, Json::error_handler_t::replace);
  };
  if (j.is_object()) {
    std::string out = "{";
    bool first = true;
    for (auto it = j.begin(); it != j.end(); ++it) {
      out += first ? "" : ", ";
      first = false;
      out += scalar(Json(it.key())) + ": " + DumpJsonLine(it.value());
    }
    return out + "}";
  }
  if (j.is_array()) {
    std::string out = "[";
    for (size_t i = 0; i < j.size(); ++i) out += (i ? ", " : "") + DumpJsonLine(j[i]);
    return out + "]";
  }
  return scalar(j);
}

}  // namespace ptlab
