// Strict number parsing and file reading shared by the scene loaders (XML, OBJ).
#pragma once

#include <cerrno>
#include <cfloat>
#include <climits>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/input_file.h"
#include "engine/core/parse_number.h"
#include "engine/core/status.h"

namespace ptlab {

/// Parses the whole of `token` as a finite decimal float (optional sign, digits, optional
/// fraction and exponent). Rejects empty text, trailing junk ("1x", "1.2.3"), "nan", "inf",
/// hexadecimal and values out of float range. The bool face of engine/core/parse_number.h
/// (ParseNumber<float> gives the message).
inline bool ParseFloat(std::string_view token, float* value) {
  return ParseNumberQuietly<float>(token, -FLT_MAX, FLT_MAX, value) == NumberError::kOk;
}

/// Parses the whole of `token` as a decimal int (optional sign); "1.0", "1e3", "0x1" and
/// out-of-range values are rejected. The bool face of ParseNumber<int>.
inline bool ParseInt(std::string_view token, int* value) {
  return ParseNumberQuietly<int>(token, INT_MIN, INT_MAX, value) == NumberError::kOk;
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
