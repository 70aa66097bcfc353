// Warps from the unit square to other domains, as (Sample, Pdf) pairs; pdfs are w.r.t. the
// natural measure of the target domain (area for square/disk/triangle, solid angle for directions).
#pragma once

#include <algorithm>
#include <cmath>

#include "engine/core/vec.h"

namespace ptlab {

/// Identity warp of [0,1)²; pdf 1 inside the square.
inline Vec2f SampleUniformSquare(const Vec2f& u) { return u; }
inline float UniformSquarePdf(const Vec2f& p) {
  return (p.x >= 0 && p.x <= 1 && p.y >= 0 && p.y <= 1) ? 1.0f : 0.0f;
}

/// Tent on [-1,1]² (separable, pdf (1-|x|)(1-|y|)), by inverting the 1-D tent CDF.
inline float SampleTent1D(float u) {
  return u < 0.5f ? std::sqrt(2.0f * u) - 1.0f : 1.0f - std::sqrt(std::max(0.0f, 2.0f - 2.0f * u));
}
inline Vec2f SampleTent(const Vec2f& u) { return {SampleTent1D(u.x), SampleTent1D(u.y)}; }
inline float TentPdf(const Vec2f& p) {
  const float px = 1.0f - std::fabs(p.x), py = 1.0f - std::fabs(p.y);
  return (px > 0 && py > 0) ? px * py : 0.0f;
}

/// Uniform on the unit disk by polar mapping (r = sqrt(u1)).
inline Vec2f SampleUniformDisk(const Vec2f& u) {
  const float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi)};
}
inline float UniformDiskPdf(const Vec2f& p) { return (p.x * p.x + p.y * p.y <= 1.0f) ? kInvPi : 0.0f; }

/// Uniform on the unit disk, Shirley & Chiu 1997 concentric mapping (low distortion).
inline Vec2f SampleConcentricDisk(const Vec2f& u) {
  const float ox = 2.0f * u.x - 1.0f, oy = 2.0f * u.y - 1.0f;
  if (ox == 0 && oy == 0) return {0, 0};
  float r, theta;
  if (std::fabs(ox) > std::fabs(oy)) {
    r = ox, theta = (kPi / 4) * (oy / ox);
  } else {
    r = oy, theta = (kPi / 2) - (kPi / 4) * (ox / oy);
  }
  return {r * std::cos(theta), r * std::sin(theta)};
}
inline float ConcentricDiskPdf(const Vec2f& p) { return UniformDiskPdf(p); }

/// Uniform over the unit sphere.
inline Vec3f SampleUniformSphere(const Vec2f& u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float UniformSpherePdf(const Vec3f&) { return kInv4Pi; }

/// Uniform over the upper (z >= 0) hemisphere.
inline Vec3f SampleUniformHemisphere(const Vec2f& u) {
  const float z = u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float UniformHemispherePdf(const Vec3f& w) { return w.z >= 0 ? kInv2Pi : 0.0f; }

/// Cosine-weighted upper hemisphere (Malley's method over the concentric disk); pdf cosθ/π.
inline Vec3f SampleCosineHemisphere(const Vec2f& u) {
  const Vec2f d = SampleConcentricDisk(u);
  const float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}
inline float CosineHemispherePdf(const Vec3f& w) { return w.z > 0 ? w.z * kInvPi : 0.0f; }

/// Uniform barycentrics (b1, b2) over a triangle (b0 = 1 - b1 - b2); pdf 1/area.
inline Vec2f SampleUniformTriangle(const Vec2f& u) {
  const float su = std::sqrt(u.x);
  return {1.0f - su, u.y * su};
}

}  // namespace ptlab
