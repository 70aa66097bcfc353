// Strict CLI11 validators shared by ptlab, chi2 and imgdiff. CLI11's own Range and
// PositiveNumber let "nan" through (every comparison with NaN is false) and an unsigned option
// takes "-1" as 2^64-1; these refuse both.
#pragma once

#include <charconv>
#include <cmath>
#include <string>

#include <CLI/CLI.hpp>

namespace ptlab {

/// A finite decimal number in [min, max].
inline CLI::Validator FiniteRange(double min, double max) {
  const std::string range = "[" + CLI::detail::to_string(min) + ", " +
                            CLI::detail::to_string(max) + "]";
  return CLI::Validator(
      [min, max, range](std::string& text) -> std::string {
        double v = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, v);
        if (text.empty() || error != std::errc() || stop != end || !std::isfinite(v))
          return "'" + text + "' is not a finite number";
        if (v < min || v > max) return "'" + text + "' is out of range; expected " + range;
        return std::string();
      },
      "FINITE in " + range);
}

/// A finite number > 0.
inline CLI::Validator FinitePositive() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::string copy = text;
        const std::string finite = FiniteRange(-HUGE_VAL, HUGE_VAL)(copy);
        if (!finite.empty()) return finite;
        return std::stod(text) > 0 ? std::string()
                                   : "'" + text + "' is out of range; expected a number > 0";
      },
      "FINITE > 0");
}

/// An unsigned decimal integer (digits only: no sign, no exponent) that fits 64 bits.
inline CLI::Validator UnsignedDecimal() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        unsigned long long v = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, v);
        if (text.empty() || text[0] == '-' || text[0] == '+' || error != std::errc() ||
            stop != end)
          return "'" + text + "' is not an unsigned integer in 0..18446744073709551615";
        return std::string();
      },
      "UINT64");
}

}  // namespace ptlab
