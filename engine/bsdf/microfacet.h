// Microfacet distributions (Beckmann, GGX; isotropic or anisotropic): D, Smith G1 and G, and
// sampling of all normals (D cos θm) or of the visible ones, with Mitsuba 3's semantics.
#pragma once

#include <cmath>
#include <cstdint>

#include "engine/bsdf/erf.h"
#include "engine/core/vec.h"

namespace ptlab {

// Conventions (Mitsuba 3's MicrofacetDistribution, Walter et al. 2007, Heitz 2014):
// - local frame, z = macro-surface normal, x = the tangent of alpha_u, y = that of alpha_v;
//   microfacet normals m are unit vectors with m.z > 0;
// - D(m) is normalised as ∫ D(m) cos θm dω_m = 1 over the hemisphere;
// - G(wi, wo, m) = G1(wi, m) G1(wo, m) (Smith, separable), G1 = 0 where v sees the back of
//   the microfacet (v·m and v.z of opposite sign);
// - the visible-normal density of a direction w (w.z > 0) is D_w(m) = G1(w, m) max(0, w·m)
//   D(m) / w.z (Heitz 2014), which integrates to 1.
// Beckmann's G1 is the exact Smith form 2 / (1 + erf(a) + e^(−a²)/(a√π)), a = 1/(α tan θ),
// not Mitsuba's rational approximation (≤ 0.35 % away): the visible-normal sampler draws from
// the exact form, so with it the pdf is the sampler's density and a sample's weight
// f cos/pdf is unbiased. GGX's G1 = 2 / (1 + √(1 + α² tan²θ)) is exact.

enum class MicrofacetType : uint8_t { kBeckmann = 0, kGgx = 1 };

/// Roughnesses are clamped into [kMicrofacetMinAlpha, kMicrofacetMaxAlpha] (NaN → the
/// minimum) by MakeMicrofacet; 1e-4 is Mitsuba's own lower clamp.
inline constexpr float kMicrofacetMinAlpha = 1e-4f;
inline constexpr float kMicrofacetMaxAlpha = 1e2f;

inline float ClampMicrofacetAlpha(float alpha) {
  return !(alpha > kMicrofacetMinAlpha)
             ? kMicrofacetMinAlpha
             : (alpha < kMicrofacetMaxAlpha ? alpha : kMicrofacetMaxAlpha);
}

/// One distribution: its type, the roughness along x (alpha_u) and y (alpha_v), and whether
/// SampleMicrofacet draws visible normals (Mitsuba's `sample_visible`, default true).
struct Microfacet {
  MicrofacetType type = MicrofacetType::kBeckmann;
  float alpha_u = 0.1f, alpha_v = 0.1f;
  bool sample_visible = true;
};

/// A Microfacet with its roughnesses clamped (see ClampMicrofacetAlpha). The functions below
/// expect this clamping.
inline Microfacet MakeMicrofacet(MicrofacetType type, float alpha_u, float alpha_v,
                                 bool sample_visible = true) {
  return {type, ClampMicrofacetAlpha(alpha_u), ClampMicrofacetAlpha(alpha_v), sample_visible};
}

/// D(m) for a unit m; 0 for m.z ≤ 0, and (as Mitsuba) where D cos θm ≤ 1e-20 or D is not
/// finite. Beckmann: exp(−(x²/αu² + y²/αv²)/z²) / (π αu αv z⁴);
/// GGX: 1 / (π αu αv (x²/αu² + y²/αv² + z²)²).
inline float MicrofacetD(const Microfacet& d, const Vec3f& m) {
  if (!(m.z > 0)) return 0.0f;
  const float x = m.x / d.alpha_u, y = m.y / d.alpha_v, z2 = m.z * m.z;
  float r;
  if (d.type == MicrofacetType::kBeckmann) {
    r = std::exp(-(x * x + y * y) / z2) / (kPi * d.alpha_u * d.alpha_v * (z2 * z2));
  } else {
    const float t = x * x + y * y + z2;
    r = 1.0f / (kPi * d.alpha_u * d.alpha_v * (t * t));
  }
  return (r * m.z > 1e-20f && std::isfinite(r)) ? r : 0.0f;
}

/// G1(v) / |v.z| without the orientation test, finite for every v (v.z = 0 included):
/// GGX 2 / (|z| + √(z² + s²)); Beckmann 2 / (|z| (1 + erf a) + s e^(−a²)/√π), with
/// s² = (αu v.x)² + (αv v.y)² and a = |z| / s; 1/|z| where s = 0 (normal incidence).
/// v is a unit vector; 0 only if v is 0 or not finite.
inline float MicrofacetG1OverCos(const Microfacet& d, const Vec3f& v) {
  const float ax = d.alpha_u * v.x, ay = d.alpha_v * v.y;
  const float s2 = ax * ax + ay * ay, z = std::fabs(v.z);
  float r;
  if (d.type == MicrofacetType::kGgx) {
    r = 2.0f / (z + std::sqrt(z * z + s2));
  } else if (!(s2 > 0)) {
    r = 1.0f / z;
  } else {
    const float s = std::sqrt(s2), a = z / s;
    r = 2.0f / (z * (1.0f + ErfApprox(a)) + s * kInvSqrtPi * std::exp(-(a * a)));
  }
  return std::isfinite(r) ? r : 0.0f;
}

/// Smith's G1(v, m) ∈ [0, 1]: |v.z| MicrofacetG1OverCos, 0 unless (v·m) v.z > 0.
inline float MicrofacetG1(const Microfacet& d, const Vec3f& v, const Vec3f& m) {
  if (!(Dot(v, m) * v.z > 0)) return 0.0f;
  const float g = std::fabs(v.z) * MicrofacetG1OverCos(d, v);
  return g < 1.0f ? g : 1.0f;
}

/// Smith's separable shadowing-masking G1(wi, m) G1(wo, m).
inline float MicrofacetG(const Microfacet& d, const Vec3f& wi, const Vec3f& wo, const Vec3f& m) {
  return MicrofacetG1(d, wi, m) * MicrofacetG1(d, wo, m);
}

/// Density over unit normals m with which SampleMicrofacet(d, w, ·) draws m, for w.z > 0 (0
/// otherwise): D_w(m) = D(m) G1(w, m) (w·m) / w.z with sample_visible, else D(m) m.z.
inline float MicrofacetPdf(const Microfacet& d, const Vec3f& w, const Vec3f& m) {
  if (!(w.z > 0)) return 0.0f;
  const float dm = MicrofacetD(d, m);
  if (!d.sample_visible) return dm * m.z;
  const float w_m = Dot(w, m);
  if (!(w_m > 0)) return 0.0f;
  const float p = dm * MicrofacetG1OverCos(d, w) * w_m;
  return std::isfinite(p) ? p : 0.0f;
}

inline float ClampMicrofacetSample(float u) {
  return !(u > 0) ? 0.0f : (u < kOneMinusEpsilon ? u : kOneMinusEpsilon);
}

/// Slopes (x̃, ỹ) of a visible normal of the α = 1 Beckmann distribution seen at cos θ = cos_t
/// ∈ (0, 1] along +x (Jakob 2015, "An Improved Visible Normal Sampling Routine for the
/// Beckmann Distribution": the x slope by Newton's method on its CDF in the erf domain, the
/// y slope independent and Gaussian). u is clamped into [1e-6, 1 − 1e-6] as there.
inline Vec2f SampleBeckmannVisibleSlope(float cos_t, const Vec2f& u) {
  const float ux = std::fmin(std::fmax(u.x, 1e-6f), 1.0f - 1e-6f);
  const float uy = std::fmin(std::fmax(u.y, 1e-6f), 1.0f - 1e-6f);
  const float sin_t = std::sqrt(std::fmax(0.0f, (1.0f - cos_t) * (1.0f + cos_t)));
  const float tan_t = sin_t / cos_t, cot_t = cos_t / sin_t;  // cot = ∞ at normal incidence
  // The CDF of the x slope, times its normaliser 1 + erf(cot) + tan e^(−cot²)/√π, in
  // x = erf(slope) ∈ [−1, erf(cot)] is 1 + x + tan e^(−slope²)/√π.
  const float max_x = ErfApprox(cot_t);
  const float tail = tan_t > 0 ? tan_t * kInvSqrtPi * std::exp(-(cot_t * cot_t)) : 0.0f;
  const float target = ux * (1.0f + max_x + tail);
  // Start from the exact inverse for grazing incidence, the most curved case.
  float x = max_x - (max_x + 1.0f) * ErfApprox(std::sqrt(-std::log(ux)));
  for (int i = 0; i < 3; ++i) {
    const float slope = ErfInvApprox(x);
    const float value = 1.0f + x + tan_t * kInvSqrtPi * std::exp(-(slope * slope)) - target;
    const float derivative = 1.0f - slope * tan_t;
    x -= value / derivative;
  }
  return {ErfInvApprox(x), ErfInvApprox(2.0f * uy - 1.0f)};
}

/// Draws a microfacet normal for the direction w (w.z > 0, unit; the viewer's wo in a BRDF)
/// from u ∈ [0, 1)² and sets *pdf = MicrofacetPdf(d, w, m). sample_visible: GGX by Heitz 2018
/// ("Sampling the GGX Distribution of Visible Normals"), Beckmann by stretching to α = 1,
/// SampleBeckmannVisibleSlope and unstretching (Heitz & d'Eon 2014). Otherwise m ~ D cos θm:
/// the azimuth φ with tan φ = (αv/αu) tan 2πu.y, the elevation from u.x by the inverse CDF of
/// tan²θ (Beckmann −α² log(1 − u), GGX α² u/(1 − u)) with α² = (αu cos 2πu.y)² +
/// (αv sin 2πu.y)², the roughness along φ. *pdf = 0 (and m = +z) when w.z ≤ 0 or the density is
/// not positive and finite.
inline Vec3f SampleMicrofacet(const Microfacet& d, const Vec3f& w, const Vec2f& u, float* pdf) {
  *pdf = 0.0f;
  if (!(w.z > 0)) return {0, 0, 1};
  Vec3f m;
  if (!d.sample_visible) {
    const float u1 = ClampMicrofacetSample(u.x), phi = (2.0f * kPi) * ClampMicrofacetSample(u.y);
    const float c = std::cos(phi), s = std::sin(phi);
    const float ac = d.alpha_u * c, as = d.alpha_v * s;
    const float a2 = ac * ac + as * as, inv_a = 1.0f / std::sqrt(a2);
    const float tan2 = d.type == MicrofacetType::kBeckmann ? -a2 * std::log1p(-u1)
                                                           : a2 * u1 / (1.0f - u1);
    const float cos_t = 1.0f / std::sqrt(1.0f + tan2), sin_t = std::sqrt(tan2) * cos_t;
    m = {sin_t * ac * inv_a, sin_t * as * inv_a, cos_t};
  } else {
    // Stretch w to the α = 1 configuration.
    const Vec3f v = Normalize(Vec3f{d.alpha_u * w.x, d.alpha_v * w.y, w.z});
    const float r2 = v.x * v.x + v.y * v.y;
    if (d.type == MicrofacetType::kGgx) {
      // Heitz 2018: an orthonormal basis (t1, t2, v), a uniform point of the unit disk, its
      // y warped to the visible projected half disk, lifted to the hemisphere around v.
      const float inv_r = r2 > 0 ? 1.0f / std::sqrt(r2) : 0.0f;
      const Vec3f t1 = r2 > 0 ? Vec3f{-v.y * inv_r, v.x * inv_r, 0.0f} : Vec3f{1, 0, 0};
      const Vec3f t2 = Cross(v, t1);
      const float r = std::sqrt(ClampMicrofacetSample(u.x));
      const float phi = (2.0f * kPi) * ClampMicrofacetSample(u.y);
      const float p1 = r * std::cos(phi);
      const float s = 0.5f * (1.0f + v.z);
      const float p2 = (1.0f - s) * std::sqrt(std::fmax(0.0f, 1.0f - p1 * p1)) +
                       s * (r * std::sin(phi));
      const float pz = std::sqrt(std::fmax(0.0f, 1.0f - p1 * p1 - p2 * p2));
      const Vec3f nh = t1 * p1 + t2 * p2 + v * pz;
      m = Normalize(Vec3f{d.alpha_u * nh.x, d.alpha_v * nh.y, std::fmax(0.0f, nh.z)});
    } else {
      float cos_phi = 1.0f, sin_phi = 0.0f;
      if (r2 > 0) {
        const float inv_r = 1.0f / std::sqrt(r2);
        cos_phi = v.x * inv_r, sin_phi = v.y * inv_r;
      }
      const Vec2f slope = SampleBeckmannVisibleSlope(v.z, u);
      // Rotate to w's azimuth and unstretch.
      const float sx = (cos_phi * slope.x - sin_phi * slope.y) * d.alpha_u;
      const float sy = (sin_phi * slope.x + cos_phi * slope.y) * d.alpha_v;
      m = Normalize(Vec3f{-sx, -sy, 1.0f});
    }
  }
  if (!std::isfinite(m.x) || !std::isfinite(m.y) || !(m.z > 0)) return {0, 0, 1};
  const float p = MicrofacetPdf(d, w, m);
  if (p > 0 && std::isfinite(p)) *pdf = p;
  return m;
}

}  // namespace ptlab
