// Strict number parsing and file reading shared by the scene loaders (XML, OBJ).
#pragma once

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/input_file.h"
#include "engine/core/status.h"

namespace ptlab {

/// from_chars takes no '+': drop one, and refuse "", "+", "++1" and "+-1".
inline bool StripPlusSign(std::string_view* token) {
  if (!token->empty() && (*token)[0] == '+') {
    token->remove_prefix(1);
    if (token->empty() || (*token)[0] == '+' || (*token)[0] == '-') return false;
  }
  return !token->empty();
}

/// Parses the whole of `token` as a finite decimal float (optional sign, digits, optional
/// fraction and exponent). Rejects empty text, trailing junk ("1x", "1.2.3"), "nan", "inf",
/// hexadecimal and values out of float range.
inline bool ParseFloat(std::string_view token, float* value) {
  if (!StripPlusSign(&token)) return false;
  float v = 0;
  const auto [end, error] =
      std::from_chars(token.data(), token.data() + token.size(), v, std::chars_format::general);
  if (error != std::errc() || end != token.data() + token.size() || !std::isfinite(v)) return false;
  *value = v;
  return true;
}

/// Parses the whole of `token` as a decimal int (optional sign); "1.0", "1e3", "0x1" and
/// out-of-range values are rejected.
inline bool ParseInt(std::string_view token, int* value) {
  if (!StripPlusSign(&token)) return false;
  int v = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (error != std::errc() || end != token.data() + token.size()) return false;
  *value = v;
  return true;
}

/// Splits a list written "1,2,3", "1 2 3" or "1, 2, 3" into its items. Items are separated by
/// whitespace or by one comma with optional whitespace around it; leading and trailing
/// whitespace is ignored. Returns false on an empty item (",1", "1,,2", "1,").
inline bool SplitList(std::string_view text, std::vector<std::string_view>* items) {
  items->clear();
  const auto is_space = [](char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
  };
  size_t i = 0;
  const size_t n = text.size();
  while (i < n && is_space(text[i])) ++i;
  if (i == n) return true;
  while (true) {
    const size_t start = i;
    while (i < n && !is_space(text[i]) && text[i] != ',') ++i;
    if (i == start) return false;
    items->push_back(text.substr(start, i - start));
    while (i < n && is_space(text[i])) ++i;
    if (i == n) return true;
    if (text[i] == ',') {
      ++i;
      while (i < n && is_space(text[i])) ++i;
      if (i == n) return false;
    }
  }
}

/// Reads a whole file (a regular file within the size limit of input_file.h). On failure the
/// Status reads "path: cannot read <what>: <reason>".
inline Status ReadTextFile(const std::string& path, const char* what, std::string* text) {
  return ReadInputFile(path, what, text);
}

}  // namespace ptlab
