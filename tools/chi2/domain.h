// Domains of the chi-square lab: where samples live and the 2-D parameter grid that bins them.
#pragma once

#include <string>

#include "engine/core/vec.h"

namespace ptlab {

/// A sample point: (x, y) on planar domains (z unused, 0); a unit direction on spherical ones.
using Chi2Point = Vec3f;

/// A point of the parameter rectangle the histogram grid covers.
struct Chi2Param {
  double x = 0, y = 0;
};

enum class Chi2DomainKind {
  kBox,         // (x, y) in [x0, x1] × [y0, y1]; densities per unit area
  kDisk,        // unit disk x² + y² <= 1, binned on [-1, 1]²; densities per unit area
  kSphere,      // unit directions, binned in (φ, cosθ) ∈ [0, 2π) × [-1, 1]; per steradian
  kHemisphere,  // unit directions with z >= 0, binned in (φ, cosθ) ∈ [0, 2π) × [0, 1]
};

/// A test domain and its parameter rectangle [x0, x1] × [y0, y1]. On the sphere the
/// parameters are (φ, cosθ), θ measured from +z, φ from +x towards +y; dφ dcosθ is solid
/// angle, so densities integrate over the rectangle without a Jacobian.
struct Chi2Domain {
  Chi2DomainKind kind = Chi2DomainKind::kBox;
  double x0 = 0, y0 = 0, x1 = 1, y1 = 1;

  static Chi2Domain Box(double x0, double y0, double x1, double y1) {
    return {Chi2DomainKind::kBox, x0, y0, x1, y1};
  }
  static Chi2Domain UnitSquare() { return Box(0, 0, 1, 1); }
  static Chi2Domain Disk() { return {Chi2DomainKind::kDisk, -1, -1, 1, 1}; }
  static Chi2Domain Sphere() { return {Chi2DomainKind::kSphere, 0, -1, 2 * kPiD, 1}; }
  static Chi2Domain Hemisphere() { return {Chi2DomainKind::kHemisphere, 0, 0, 2 * kPiD, 1}; }

  bool spherical() const {
    return kind == Chi2DomainKind::kSphere || kind == Chi2DomainKind::kHemisphere;
  }

  static constexpr double kPiD = 3.14159265358979323846;
};

/// "box [x0,x1]x[y0,y1]", "disk", "sphere" or "hemisphere".
std::string Chi2DomainName(const Chi2Domain& domain);

/// Grid cells along x for `res` cells along y: 2·res on spherical domains (φ spans 2π), else res.
int Chi2GridWidth(const Chi2Domain& domain, int res);

/// True when p is finite and lies in the domain, up to float rounding: 1e-6 of the extent on a
/// box, r² <= 1 + 1e-6 on the disk, |‖p‖² - 1| <= 1e-4 on the sphere (and z >= -1e-6 on the
/// hemisphere).
bool Chi2Contains(const Chi2Domain& domain, const Chi2Point& p);

/// Parameter coordinates of a point of the domain (identity, or (φ ∈ [0, 2π], cosθ = z)).
Chi2Param Chi2ToParam(const Chi2Domain& domain, const Chi2Point& p);

/// The point at parameter coordinates q (inverse of Chi2ToParam on the domain).
Chi2Point Chi2FromParam(const Chi2Domain& domain, const Chi2Param& q);

/// The part [*lo, *hi] of the parameter segment {x} × [y0, y1] that lies in the domain's
/// support; empty (*lo >= *hi) when none does. Only the disk clips (to |y| <= sqrt(1 - x²)),
/// which keeps its boundary out of the integrand, so Simpson sees no discontinuity there.
void Chi2SupportY(const Chi2Domain& domain, double x, double y0, double y1, double* lo, double* hi);

}  // namespace ptlab
