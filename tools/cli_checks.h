// Strict CLI11 validators shared by ptlab, chi2 and imgdiff, all through the checked parser of
// engine/core/parse_number.h. CLI11's own Range and PositiveNumber let "nan" through (every
// comparison with NaN is false) and an unsigned option takes "-1" as 2^64-1; these refuse
// both, never throw (std::stod threw on "1e-320"), and name the accepted range.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <CLI/CLI.hpp>

#include "engine/core/parse_number.h"

namespace ptlab {

/// A finite decimal number in [min, max]. For a float option keep [min, max] within float
/// range (FloatRange also refuses values that a float would flush to 0).
inline CLI::Validator FiniteRange(double min, double max) {
  return CLI::Validator(
      [min, max](std::string& text) -> std::string {
        double v = 0;
        return ParseNumber<double>(text, min, max, &v);
      },
      "FINITE in " + FormatRange(min, max));
}

/// A finite decimal number in [min, max] that a 32-bit float holds (not flushed to 0).
inline CLI::Validator FloatRange(float min, float max) {
  return CLI::Validator(
      [min, max](std::string& text) -> std::string {
        float v = 0;
        return ParseNumber<float>(text, min, max, &v);
      },
      "FLOAT in " + FormatRange(min, max));
}

/// A finite number > 0.
inline CLI::Validator FinitePositive() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double v = 0;
        switch (ParseNumberQuietly<double>(text, -HUGE_VAL, HUGE_VAL, &v)) {
          case NumberError::kOk:
            return v > 0 ? std::string()
                         : QuoteForMessage(text) + " is out of range; expected a number > 0";
          case NumberError::kNotANumber:
            return QuoteForMessage(text) + " is not a number; expected a finite number > 0";
          default:
            return QuoteForMessage(text) + " is not a finite number > 0";
        }
      },
      "FINITE > 0");
}

/// An unsigned decimal integer (digits only: no sign, no exponent) that fits 64 bits.
inline CLI::Validator UnsignedDecimal() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        uint64_t v = 0;
        if ((!text.empty() && text[0] == '+') ||
            ParseNumberQuietly<uint64_t>(text, 0, UINT64_MAX, &v) != NumberError::kOk)
          return QuoteForMessage(text) + " is not an unsigned integer in 0..18446744073709551615";
        return std::string();
      },
      "UINT64");
}

/// A decimal integer in [min, max] (no fraction, no exponent).
inline CLI::Validator IntegerRange(int64_t min, int64_t max) {
  return CLI::Validator(
      [min, max](std::string& text) -> std::string {
        int64_t v = 0;
        return ParseNumber<int64_t>(text, min, max, &v);
      },
      "INT in " + FormatIntegerRange(min, max));
}

}  // namespace ptlab
