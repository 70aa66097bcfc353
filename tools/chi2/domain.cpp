// Domains of the chi-square lab: containment, parameterisation and support clipping.
#include "tools/chi2/domain.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ptlab {

std::string Chi2DomainName(const Chi2Domain& domain) {
  switch (domain.kind) {
    case Chi2DomainKind::kBox: {
      char buf[128];
      std::snprintf(buf, sizeof(buf), "box [%g,%g]x[%g,%g]", domain.x0, domain.x1, domain.y0,
                    domain.y1);
      return buf;
    }
    case Chi2DomainKind::kDisk:
      return "disk";
    case Chi2DomainKind::kSphere:
      return "sphere";
    case Chi2DomainKind::kHemisphere:
      return "hemisphere";
  }
  return "?";
}

int Chi2GridWidth(const Chi2Domain& domain, int res) { return domain.spherical() ? 2 * res : res; }

bool Chi2Contains(const Chi2Domain& domain, const Chi2Point& p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  const double x = p.x, y = p.y, z = p.z;
  switch (domain.kind) {
    case Chi2DomainKind::kBox: {
      const double ex = 1e-6 * (domain.x1 - domain.x0), ey = 1e-6 * (domain.y1 - domain.y0);
      return x >= domain.x0 - ex && x <= domain.x1 + ex && y >= domain.y0 - ey &&
             y <= domain.y1 + ey;
    }
    case Chi2DomainKind::kDisk:
      return x * x + y * y <= 1.0 + 1e-6;
    case Chi2DomainKind::kSphere:
      return std::fabs(x * x + y * y + z * z - 1.0) <= 1e-4;
    case Chi2DomainKind::kHemisphere:
      return std::fabs(x * x + y * y + z * z - 1.0) <= 1e-4 && z >= -1e-6;
  }
  return false;
}

Chi2Param Chi2ToParam(const Chi2Domain& domain, const Chi2Point& p) {
  if (!domain.spherical()) return {p.x, p.y};
  double phi = std::atan2(double(p.y), double(p.x));
  if (phi < 0) phi += 2 * Chi2Domain::kPiD;
  return {phi, std::clamp(double(p.z), -1.0, 1.0)};
}

Chi2Point Chi2FromParam(const Chi2Domain& domain, const Chi2Param& q) {
  if (!domain.spherical()) return {float(q.x), float(q.y), 0.0f};
  const double cos_theta = q.y, sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  return {float(sin_theta * std::cos(q.x)), float(sin_theta * std::sin(q.x)), float(cos_theta)};
}

void Chi2SupportY(const Chi2Domain& domain, double x, double y0, double y1, double* lo,
                  double* hi) {
  *lo = y0, *hi = y1;
  if (domain.kind != Chi2DomainKind::kDisk) return;
  const double s = std::sqrt(std::max(0.0, 1.0 - x * x));
  *lo = std::max(y0, -s), *hi = std::min(y1, s);
}

}  // namespace ptlab
