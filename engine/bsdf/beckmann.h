// Beckmann microfacet distribution: D, Smith G1 (rational approx.), half-vector sampling, pdf.
#pragma once

#include <cmath>

#include "engine/core/vec.h"

namespace ptlab {

// Conventions (see shared/data/SOURCES.md, "Nori conventions"). Two functions of the half
// vector h, which differ by one factor cos θh, and which this file keeps apart by name:
//
//   BeckmannD(h)    = exp(−tan²θh/α²) / (π α² cos⁴θh)
//       the microfacet *distribution* of pbrt, Mitsuba and Walter et al. 2007 (eq. 25):
//       ∫ BeckmannD(h) cos θh dω_h = 1 over the hemisphere. The BRDFs use this one:
//       f = F D G / (4 cos θi cos θo).
//   BeckmannPdfH(h) = BeckmannD(h) cos θh = exp(−tan²θh/α²) / (π α² cos³θh)
//       a *density* of h (∫ BeckmannPdfH dω_h = 1). This is what Nori's course text calls D;
//       its BRDF kd/π + ks D F G / (4 cos θi cos θo cos θh) is therefore the same function.
//
// SampleBeckmannNormal draws h with density BeckmannPdfH; reflecting wo about h gives wi with
// solid-angle density BeckmannPdfH(h) / (4 |wo·h|) (BeckmannReflectionPdf).
//
// Half vectors are passed unnormalised (e.g. wo + wi): tan²θ = (x² + y²)/z² is then computed
// from the components without the cancellation of 1 − cos²θ, which matters for α ≲ 1e-3.
// α is clamped into [kBeckmannMinAlpha, kBeckmannMaxAlpha] (NaN → min): α → 0 becomes a very
// sharp lobe that behaves as a mirror, never a NaN.

inline constexpr float kBeckmannMinAlpha = 1e-4f;
inline constexpr float kBeckmannMaxAlpha = 1e2f;

inline float ClampBeckmannAlpha(float alpha) {
  return !(alpha > kBeckmannMinAlpha) ? kBeckmannMinAlpha
                                      : (alpha < kBeckmannMaxAlpha ? alpha : kBeckmannMaxAlpha);
}
inline float ClampSample(float u) {
  return !(u > 0) ? 0.0f : (u < kOneMinusEpsilon ? u : kOneMinusEpsilon);
}

/// BeckmannD for the half vector h (any length > 0); 0 when h.z ≤ 0 or exp underflows.
inline float BeckmannD(float alpha, const Vec3f& h) {
  if (!(h.z > 0)) return 0.0f;
  alpha = ClampBeckmannAlpha(alpha);
  const float a2 = alpha * alpha;
  const float s2 = h.x * h.x + h.y * h.y, z2 = h.z * h.z;
  const float e = std::exp(-s2 / (z2 * a2));  // exp(−tan²θ/α²)
  if (!(e > 0)) return 0.0f;                  // also catches 0/0 for a zero-length h
  const float cos2 = z2 / (s2 + z2);
  return e / (kPi * a2 * (cos2 * cos2));
}

/// BeckmannPdfH = BeckmannD cos θh, Nori's "D": a density over half vectors.
inline float BeckmannPdfH(float alpha, const Vec3f& h) {
  const float d = BeckmannD(alpha, h);
  return d > 0 ? d * (h.z / std::sqrt(h.x * h.x + h.y * h.y + h.z * h.z)) : 0.0f;
}

/// Smith G1 for Beckmann, Walter et al. 2007's rational approximation (eq. 27):
/// b = 1/(α tan θv), G1 = (3.535 b + 2.181 b²)/(1 + 2.276 b + 2.577 b²) for b < 1.6, else 1.
/// v is a unit direction with v.z > 0; the caller applies χ⁺(v·h / v.z).
inline float BeckmannG1(float alpha, const Vec3f& v) {
  alpha = ClampBeckmannAlpha(alpha);
  const float b = v.z / (alpha * std::sqrt(v.x * v.x + v.y * v.y));
  if (!(b < 1.6f)) return 1.0f;
  return b * (3.535f + 2.181f * b) / (1.0f + b * (2.276f + 2.577f * b));
}

/// G1(v) / cos θv, finite as cos θv → 0: for b < 1.6 it is
/// (3.535 + 2.181 b) / ((1 + 2.276 b + 2.577 b²) α sin θv), else 1 / cos θv. Same
/// preconditions as BeckmannG1. The BRDFs use it so that f = F D (G1/cos)(G1/cos) / 4 never
/// divides by a vanishing cosine.
inline float BeckmannG1OverCos(float alpha, const Vec3f& v) {
  alpha = ClampBeckmannAlpha(alpha);
  const float as = alpha * std::sqrt(v.x * v.x + v.y * v.y);
  const float b = v.z / as;
  if (!(b < 1.6f)) return 1.0f / v.z;
  return (3.535f + 2.181f * b) / ((1.0f + b * (2.276f + 2.577f * b)) * as);
}

/// Draws a unit half vector h with density BeckmannPdfH (Walter et al. 2007 eqs. 28–29):
/// tan²θ = −α² log(1 − u.x), φ = 2π u.y. u is clamped into [0, 1 − 2⁻²⁴].
inline Vec3f SampleBeckmannNormal(float alpha, const Vec2f& u) {
  alpha = ClampBeckmannAlpha(alpha);
  const float u1 = ClampSample(u.x), u2 = ClampSample(u.y);
  const float tan2 = -(alpha * alpha) * std::log1p(-u1);
  const float cos_t = 1.0f / std::sqrt(1.0f + tan2);
  const float sin_t = std::sqrt(tan2) * cos_t;
  const float phi = (2.0f * kPi) * u2;
  return {sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t};
}

/// Mirror reflection of wo about the unit vector h: 2 (wo·h) h − wo.
inline Vec3f ReflectAbout(const Vec3f& wo, const Vec3f& h) {
  const float dot2 = 2.0f * Dot(wo, h);
  return {dot2 * h.x - wo.x, dot2 * h.y - wo.y, dot2 * h.z - wo.z};
}

/// BeckmannEvalPdf's pdf D(H) H.z / (4 wo·H) given its D(H) = dv, H = wo + wi (wo and wi above
/// the surface): false (*pdf untouched) where dv or wo·H is not positive or a value is not
/// finite (non-unit or non-finite inputs). For callers that have D already
/// (RoughPlasticEvalPdf).
inline bool BeckmannReflectionPdfOfD(float dv, const Vec3f& wo, const Vec3f& h, float* pdf) {
  const float wo_h = Dot(wo, h);
  if (!(dv > 0) || !(wo_h > 0)) return false;
  const float p = dv * h.z / (4.0f * wo_h);
  if (!std::isfinite(dv) || !std::isfinite(p)) return false;
  *pdf = p;
  return true;
}

/// D(h) and the solid-angle density of wi when h ~ BeckmannPdfH and wi = reflect(wo, h):
/// pdf = D(h) cos θh / (4 wo·h) with h = H/|H|, H = wo + wi, i.e. pdf = D(H) H.z / (4 wo·H).
/// wo·H is a dot product rather than |H|/2 (equal for exactly unit vectors) because at
/// grazing, nearly opposite wo and wi the latter turns the ~1e-7 length error of
/// float-normalised inputs into a relative error ~1e-7/|H|², against ~1e-7/|H| here.
/// Both are 0 unless wo and wi are above the surface (one-sided, as Nori and Mitsuba).
/// Scalar oracle of simd::BeckmannEvalPdfBatch.
inline void BeckmannEvalPdf(float alpha, const Vec3f& wo, const Vec3f& wi, float* d, float* pdf) {
  *d = 0.0f;
  *pdf = 0.0f;
  if (!(wo.z > 0) || !(wi.z > 0)) return;
  const Vec3f h = wo + wi;
  const float dv = BeckmannD(alpha, h);
  float p;
  if (!BeckmannReflectionPdfOfD(dv, wo, h, &p)) return;
  *d = dv;
  *pdf = p;
}

/// Solid-angle pdf of wi for Beckmann reflection sampling (see BeckmannEvalPdf).
inline float BeckmannReflectionPdf(float alpha, const Vec3f& wo, const Vec3f& wi) {
  float d, pdf;
  BeckmannEvalPdf(alpha, wo, wi, &d, &pdf);
  return pdf;
}

}  // namespace ptlab
