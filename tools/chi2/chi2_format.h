// Message helpers of the chi-square test driver (tools/chi2/chi2.cpp, chi2_integration.cpp).
#pragma once

#include <cstdio>
#include <string>

#include "tools/chi2/chi2.h"

namespace ptlab::chi2_internal {

/// "(x, y)" or, on the sphere, "(x, y, z)", for messages.
inline std::string FormatPoint(const Chi2Domain& domain, const Chi2Point& p) {
  char buf[96];
  if (domain.spherical()) {
    std::snprintf(buf, sizeof(buf), "(%.7g, %.7g, %.7g)", p.x, p.y, p.z);
  } else {
    std::snprintf(buf, sizeof(buf), "(%.7g, %.7g)", p.x, p.y);
  }
  return buf;
}

/// snprintf of up to three numbers into a message.
inline std::string Format(const char* fmt, double a, double b = 0, double c = 0) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), fmt, a, b, c);
  return buf;
}

}  // namespace ptlab::chi2_internal
