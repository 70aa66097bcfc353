// The pieces that Mitsuba 3's `principled` and `principledthin` share (Burley 2012/2015, "Physically
// Based Shading at Disney" and "Extending the Disney BRDF to a BSDF"): Schlick weights, the
// GTR1 clearcoat distribution, the roughness → GGX mapping, the diffuse/retro/sheen terms.
#pragma once

#include <algorithm>
#include <cmath>

#include "engine/bsdf/microfacet.h"
#include "engine/core/vec.h"
#include "engine/scene/principled_table.h"
#include "engine/texture/texture_site.h"

namespace ptlab {

/// The parameters of one principled shading point (after texture lookups and clamping; see
/// PrincipledAt). eta is the relative IOR (interior over exterior). diff_trans is already
/// halved into [0, 1] (principledthin's parameter is in [0, 2]).
struct PrincipledParams {
  Color3f base_color{0.5f, 0.5f, 0.5f};
  float roughness = 0.5f, anisotropic = 0, metallic = 0, spec_tint = 0, sheen = 0,
        sheen_tint = 0, clearcoat = 0, clearcoat_gloss = 0, spec_trans = 0, flatness = 0,
        diff_trans = 0, eta = 1.5f;
};

/// Row i of `t` at `site`: every parameter its constant or its texture there (TexturedColor /
/// TexturedFloat), then clamped into the range where the model is defined (weights into
/// [0, 1], diff_trans into [0, 2] and halved, eta into [1e-4, 1e4]); Mitsuba does not clamp,
/// but its scenes stay within these ranges, and outside them it returns NaN.
inline PrincipledParams PrincipledAt(const PrincipledTable& t, size_t i, const TextureSite& site) {
  auto value = [&](PrincipledParam k) {
    return TexturedFloat(t.texture[k], i, t.value[k][i], site);
  };
  auto unit = [&](PrincipledParam k) { return std::clamp(value(k), 0.0f, 1.0f); };
  PrincipledParams p;
  const Color3f c = TexturedColor(t.base_color_texture, i, t.BaseColor(i), site);
  p.base_color = {std::max(c.r, 0.0f), std::max(c.g, 0.0f), std::max(c.b, 0.0f)};
  p.roughness = unit(kPrincipledRoughness);
  p.anisotropic = unit(kPrincipledAnisotropic);
  p.metallic = unit(kPrincipledMetallic);
  p.spec_tint = unit(kPrincipledSpecTint);
  p.sheen = unit(kPrincipledSheen);
  p.sheen_tint = unit(kPrincipledSheenTint);
  p.clearcoat = unit(kPrincipledClearcoat);
  p.clearcoat_gloss = unit(kPrincipledClearcoatGloss);
  p.spec_trans = unit(kPrincipledSpecTrans);
  p.flatness = unit(kPrincipledFlatness);
  p.diff_trans = 0.5f * std::clamp(value(kPrincipledDiffTrans), 0.0f, 2.0f);
  p.eta = std::clamp(value(kPrincipledEta), 1e-4f, 1e4f);
  return p;
}

/// Mitsuba's principled IOR from its `specular` parameter s: the η whose normal-incidence
/// reflectance ((η − 1)/(η + 1))² is 0.08 s, η = 2 / (1 − √(0.08 s)) − 1 (s = 0.5: η = 1.5).
inline float PrincipledEtaFromSpecular(float specular) {
  return 2.0f * (1.0f / (1.0f - std::sqrt(0.08f * specular))) - 1.0f;
}

namespace principled_internal {

/// (1 − c)⁵ with 1 − c clamped into [0, 1] (Schlick's weight).
inline float SchlickWeight(float c) {
  const float m = std::clamp(1.0f - c, 0.0f, 1.0f);
  const float m2 = m * m;
  return m2 * m2 * m;
}

/// Schlick's Fresnel R0 + (1 − R0) w for light arriving at cosine cos_i w.r.t. a microfacet
/// (negative = from inside) of relative IOR eta: w is taken at the incident cosine when the
/// ray goes into the denser medium, else at the refracted cosine (0 beyond the critical angle).
inline float SchlickFresnel(float r0, float cos_i, float eta) {
  const bool outside = cos_i >= 0;
  const float eta_it = outside ? eta : 1.0f / eta, eta_ti = outside ? 1.0f / eta : eta;
  float w;
  if (eta_it > 1.0f) {
    w = SchlickWeight(std::fabs(cos_i));
  } else {
    const float ct2 = 1.0f - (1.0f - cos_i * cos_i) * (eta_ti * eta_ti);
    w = SchlickWeight(std::sqrt(std::max(ct2, 0.0f)));
  }
  return r0 + (1.0f - r0) * w;
}
inline Color3f SchlickFresnel(const Color3f& r0, float cos_i, float eta) {
  return {SchlickFresnel(r0.r, cos_i, eta), SchlickFresnel(r0.g, cos_i, eta),
          SchlickFresnel(r0.b, cos_i, eta)};
}

/// ((η − 1)/(η + 1))², the normal-incidence reflectance of relative IOR η.
inline float SchlickR0(float eta) {
  const float r = (eta - 1.0f) / (eta + 1.0f);
  return r * r;
}

/// The base colour divided by its luminance (white where the luminance is 0).
inline Color3f TintColor(const Color3f& base) {
  const float lum = Luminance(base);
  return lum > 0 ? base / lum : Color3f{1, 1, 1};
}

inline Color3f Lerp(const Color3f& a, const Color3f& b, float t) { return a + (b - a) * t; }
inline float Lerp(float a, float b, float t) { return a + (b - a) * t; }

/// Burley's mapping of roughness r and anisotropic a ∈ [0, 1] to GGX: α = r², stretched by
/// 1/√(1 − 0.9 a) along the tangent and shrunk by it along the bitangent, each ≥ 0.001.
inline Microfacet PrincipledDistribution(float roughness, float anisotropic) {
  const float r2 = roughness * roughness, aspect = std::sqrt(1.0f - 0.9f * anisotropic);
  return MakeMicrofacet(MicrofacetType::kGgx, std::max(0.001f, r2 / aspect),
                        std::max(0.001f, r2 * aspect), true);
}

/// The clearcoat's GTR1 roughness: 0.1 at gloss 0 to 0.001 at gloss 1.
inline float ClearcoatAlpha(float gloss) { return Lerp(0.1f, 0.001f, gloss); }

/// GTR1 ("generalized Trowbridge–Reitz", γ = 1; Burley 2012 eq. 4):
/// D(m) = (α² − 1) / (π log α² (1 + (α² − 1) cos²θm)); 0 where D cos θm ≤ 1e-20.
inline float Gtr1D(float alpha, const Vec3f& m) {
  const float a2 = alpha * alpha, c = m.z;
  const float r = (a2 - 1.0f) / (kPi * std::log(a2) * (1.0f + (a2 - 1.0f) * (c * c)));
  return r * c > 1e-20f && std::isfinite(r) ? r : 0.0f;
}
/// Density of SampleGtr1 over normals: D(m) cos θm (0 below the surface).
inline float Gtr1Pdf(float alpha, const Vec3f& m) { return m.z < 0 ? 0.0f : m.z * Gtr1D(alpha, m); }
/// A normal drawn with density D cos θm: φ = 2π u.x, cos²θ = (1 − α^(2(1 − u.y))) / (1 − α²).
inline Vec3f SampleGtr1(float alpha, const Vec2f& u) {
  const float phi = 2.0f * kPi * u.x, a2 = alpha * alpha;
  const float c2 = (1.0f - std::pow(a2, 1.0f - u.y)) / (1.0f - a2);
  const float s = std::sqrt(std::max(0.0f, 1.0f - c2)), c = std::sqrt(std::max(0.0f, c2));
  return {std::cos(phi) * s, std::sin(phi) * s, c};
}

/// The clearcoat's shadowing-masking: separable Smith GGX with α = 0.25 (Burley 2012).
inline float ClearcoatG(const Vec3f& wo, const Vec3f& wi, const Vec3f& m) {
  const Microfacet d{MicrofacetType::kGgx, 0.25f, 0.25f, true};
  return MicrofacetG(d, wo, wi, m);
}

/// Burley's diffuse, retro-reflection and (with flatness) Hanrahan–Krueger-like fake
/// subsurface, as the factor of base/π: cos_o, cos_i the two |cosines|, cos_d = wi·h.
inline float DiffuseFactor(float roughness, float flatness, float cos_o, float cos_i,
                           float cos_d) {
  // Symmetric in the two directions (reciprocal).
  const float fl = SchlickWeight(cos_i), fv = SchlickWeight(cos_o);
  const float f_diff = (1.0f - 0.5f * fv) * (1.0f - 0.5f * fl);
  const float rr = 2.0f * roughness * (cos_d * cos_d);
  const float f_retro = rr * (fl + fv + fl * fv * (rr - 1.0f));
  if (!(flatness > 0)) return f_diff + f_retro;
  const float fss90 = 0.5f * rr;
  const float fss = Lerp(1.0f, fss90, fl) * Lerp(1.0f, fss90, fv);
  const float f_ss = 1.25f * (fss * (1.0f / (cos_i + cos_o) - 0.5f) + 0.5f);
  return Lerp(f_diff + f_retro, f_ss, flatness);
}

/// The sheen colour: white tinted towards the base colour's hue by sheen_tint.
inline Color3f SheenColor(const PrincipledParams& p) {
  if (!(p.sheen_tint > 0)) return {1, 1, 1};
  return Lerp(Color3f{1, 1, 1}, TintColor(p.base_color), p.sheen_tint);
}

/// w reflected about the unit normal m.
inline Vec3f ReflectAbout(const Vec3f& w, const Vec3f& m) { return m * (2.0f * Dot(w, m)) - w; }

/// True if wo and wi (local frame) are on the sides of the microfacet m that a reflection
/// (`reflect`) or a refraction about m needs, m turned to wo's side of the macro surface.
inline bool MicroMacroCompatible(const Vec3f& m, const Vec3f& wo, const Vec3f& wi, float cos_o,
                                 bool reflect) {
  const Vec3f ms = cos_o < 0 ? m * -1.0f : m;
  return Dot(wo, ms) > 0 && (reflect ? Dot(wi, ms) > 0 : Dot(wi, ms) < 0);
}

}  // namespace principled_internal
}  // namespace ptlab
