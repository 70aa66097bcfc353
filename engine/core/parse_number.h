// The one checked number parser of ptlab: flags (CLI11 validators), scene and camera files,
// image headers and the chi² lab's files all turn text into numbers here. It never throws
// (std::stod/std::stoi throw out_of_range on "1e-320" and "99999999999"), refuses NaN, Inf,
// hexadecimal, blanks and trailing junk, and says which range a number must lie in.
#pragma once

#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>

namespace ptlab {

/// `text` quoted for an error message: at most `max_bytes` bytes of it (then "..."), with NUL,
/// other control bytes, quotes and backslashes escaped (\0, \n, \xNN), so a message is never
/// cut by a NUL or broken across lines by the input it quotes.
inline std::string QuoteForMessage(std::string_view text, size_t max_bytes = 40) {
  std::string out = "'";
  for (size_t i = 0; i < text.size() && i < max_bytes; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == 0) {
      out += "\\0";
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\\' || c == '\'') {
      out += '\\';
      out += char(c);
    } else if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", unsigned(c));
      out += buf;
    } else {
      out += char(c);
    }
  }
  if (text.size() > max_bytes) out += "...";
  return out + "'";
}

/// A limit as people write it: 1e20, -1e20, 0.5, 65536, 3.4e38 (at most 6 significant digits,
/// no "+" or leading zeros in the exponent).
inline std::string FormatLimit(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  std::string s = buf;
  const size_t e = s.find('e');
  if (e == std::string::npos) return s;
  std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
  std::string sign;
  if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) {
    if (exponent[0] == '-') sign = "-";
    exponent.erase(0, 1);
  }
  while (exponent.size() > 1 && exponent[0] == '0') exponent.erase(0, 1);
  return mantissa + "e" + sign + exponent;
}

/// "[min, max]" with FormatLimit's numbers.
inline std::string FormatRange(double min, double max) {
  // Appended piece by piece: GCC 12 warns (-Wrestrict, falsely) on "[" + std::string.
  std::string range = "[";
  range += FormatLimit(min);
  range += ", ";
  range += FormatLimit(max);
  range += "]";
  return range;
}

/// "[min, max]" of two integers, exactly.
template <typename T>
std::string FormatIntegerRange(T min, T max) {
  std::string range = "[";
  range += std::to_string(min);
  range += ", ";
  range += std::to_string(max);
  range += "]";
  return range;
}

/// Parses all of `text` as a decimal number of type T (float, double or an integer type) in
/// [min, max]. Accepted: an optional sign, digits, for floating types an optional fraction and
/// exponent. Returns "" and sets *value, or a message without a location, e.g.
///   "'1e38' is out of range [-1e20, 1e20]", "'abc' is not a number",
///   "'nan' is not a finite number", "'1e-50' is too close to 0 for a 32-bit float".
/// Integer types refuse "1.0", "1e3" and "0x1"; *value is left alone on error.
/// Why ParseNumber refused a text (kOk: it did not).
enum class NumberError { kOk, kNotANumber, kNotFinite, kOutOfRange, kTooSmallForFloat };

/// The check of ParseNumber without its message (what hot loops over millions of tokens call:
/// it allocates nothing).
template <typename T>
NumberError ParseNumberQuietly(std::string_view t, T min, T max, T* value) {
  static_assert(std::is_arithmetic_v<T>, "ParseNumber parses numbers");
  // from_chars takes no '+': drop one, but refuse "+", "++1" and "+-1".
  if (!t.empty() && t[0] == '+') {
    t.remove_prefix(1);
    if (t.empty() || t[0] == '+' || t[0] == '-') return NumberError::kNotANumber;
  }
  if (t.empty()) return NumberError::kNotANumber;
  if constexpr (std::is_floating_point_v<T>) {
    double v = 0;
    const auto [end, error] =
        std::from_chars(t.data(), t.data() + t.size(), v, std::chars_format::general);
    if (end != t.data() + t.size() ||
        (error != std::errc() && error != std::errc::result_out_of_range))
      return NumberError::kNotANumber;
    // Overflow (1e400) or underflow (1e-400): either way not the number written.
    if (error == std::errc::result_out_of_range) return NumberError::kOutOfRange;
    if (!std::isfinite(v)) return NumberError::kNotFinite;
    if (!(v >= double(min) && v <= double(max))) return NumberError::kOutOfRange;
    if constexpr (std::is_same_v<T, float>) {
      if (v != 0 && float(v) == 0.0f) return NumberError::kTooSmallForFloat;
    }
    *value = T(v);
  } else {
    // Parsed in the widest type of the same signedness, so "99999999999" is out of range
    // rather than not a number.
    using Wide = std::conditional_t<std::is_signed_v<T>, long long, unsigned long long>;
    if (std::is_unsigned_v<T> && t[0] == '-') {
      Wide ignored = 0;
      const auto [end, error] = std::from_chars(t.data() + 1, t.data() + t.size(), ignored);
      return end == t.data() + t.size() && end != t.data() + 1 ? NumberError::kOutOfRange
                                                               : NumberError::kNotANumber;
    }
    Wide v = 0;
    const auto [end, error] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (end != t.data() + t.size() ||
        (error != std::errc() && error != std::errc::result_out_of_range))
      return NumberError::kNotANumber;
    if (error == std::errc::result_out_of_range) return NumberError::kOutOfRange;
    if (v < Wide(min) || v > Wide(max)) return NumberError::kOutOfRange;
    *value = T(v);
  }
  return NumberError::kOk;
}

/// The message of a NumberError for `text` and the accepted `range` ("[min, max]"; no location).
inline std::string NumberErrorMessage(NumberError error, std::string_view text,
                                      const std::string& range, bool integer) {
  const std::string quoted = QuoteForMessage(text);
  switch (error) {
    case NumberError::kOk:
      return std::string();
    case NumberError::kNotANumber:
      return quoted + (integer ? " is not an integer; expected an integer in "
                               : " is not a number; expected a number in ") + range;
    case NumberError::kNotFinite:
      return quoted + " is not a finite number; expected a number in " + range;
    case NumberError::kOutOfRange:
      return quoted + " is out of range " + range;
    case NumberError::kTooSmallForFloat:
      return quoted + " is too close to 0 for a 32-bit float (|x| >= 1.4e-45, or 0); expected "
                      "a number in " + range;
  }
  return quoted + " is not a number";
}

/// Parses all of `text` as a decimal number of type T (float, double or an integer type) in
/// [min, max]. Accepted: an optional sign, digits, for floating types an optional fraction and
/// exponent. Returns "" and sets *value, or a message without a location, e.g.
///   "'1e38' is out of range [-1e20, 1e20]", "'abc' is not a number; expected a number in
///   [0, 1]", "'nan' is not a finite number; ...", "'1e-50' is too close to 0 for a 32-bit
///   float ...". Integer types refuse "1.0", "1e3" and "0x1". *value is kept on error.
template <typename T>
std::string ParseNumber(std::string_view text, T min, T max, T* value) {
  const NumberError error = ParseNumberQuietly<T>(text, min, max, value);
  if (error == NumberError::kOk) return std::string();
  if constexpr (std::is_integral_v<T>)
    return NumberErrorMessage(error, text, FormatIntegerRange(min, max), true);
  else
    return NumberErrorMessage(error, text, FormatRange(double(min), double(max)), false);
}

/// A decimal number where non-finite values are data to judge, not errors (a chi² sample or a
/// density that a test reports): like ParseNumber<double>, but "nan" and "inf" (any case) give
/// NaN and ±Inf, and a magnitude past double range gives ±Inf (or 0 for 1e-400). False only
/// for text that is not a number.
inline bool ParseDoubleOrNonFinite(std::string_view token, double* x) {
  const NumberError e = ParseNumberQuietly<double>(token, -HUGE_VAL, HUGE_VAL, x);
  if (e == NumberError::kOk) return true;
  if (e == NumberError::kNotANumber || token.empty()) return false;
  std::string_view unsigned_part = token;
  const bool negative = token[0] == '-';
  if (token[0] == '+' || token[0] == '-') unsigned_part.remove_prefix(1);
  if (e == NumberError::kNotFinite) {
    if (token[0] == '+') token.remove_prefix(1);
    return std::from_chars(token.data(), token.data() + token.size(), *x).ec == std::errc();
  }
  // kOutOfRange over the whole double range: an exponent past it, one way or the other.
  const size_t e_at = unsigned_part.find_first_of("eE");
  const bool tiny = e_at != std::string_view::npos && e_at + 1 < unsigned_part.size() &&
                    unsigned_part[e_at + 1] == '-';
  *x = tiny ? (negative ? -0.0 : 0.0) : (negative ? -HUGE_VAL : HUGE_VAL);
  return true;
}

/// ParseNumber over the whole range of T (for floating types: the finite values).
template <typename T>
std::string ParseNumber(std::string_view text, T* value) {
  if constexpr (std::is_floating_point_v<T>)
    return ParseNumber<T>(text, -std::numeric_limits<T>::max(), std::numeric_limits<T>::max(),
                          value);
  else
    return ParseNumber<T>(text, std::numeric_limits<T>::min(), std::numeric_limits<T>::max(),
                          value);
}

}  // namespace ptlab
