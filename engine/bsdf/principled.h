// Mitsuba 3 `principled`: Burley's Disney BSDF (2015) — a diffuse/retro/sheen base, a GGX
// specular lobe whose Fresnel term blends dielectric, metallic and tinted responses, a GTR1
// clearcoat and a rough specular transmission — with Mitsuba's lobe sampling probabilities.
#pragma once

#include <cmath>

#include "engine/bsdf/bsdf_sample.h"
#include "engine/bsdf/fresnel.h"
#include "engine/bsdf/principled_lobes.h"
#include "engine/sampling/warp.h"

namespace ptlab {

// Conventions: wo (the viewer) and wi (the light) in the local frame; wo below the surface
// (wo.z < 0) is inside the object, where only the dielectric interface exists (reflection
// weighted by the transmission lobe's weight, and transmission). Transmitted radiance is
// scaled by (η_o/η_i)² (Mitsuba's radiance mode), which cancels the Jacobian's η² as in
// `roughdielectric`. Eval returns f (Mitsuba's value divided by |cos θi|). Mitsuba's quirks
// are kept: the clearcoat term 0.25 cc F D G has no 1/(4 cos θo cos θi), the transmission is
// tinted by √base_color, the sheen is weighted by (1 − metallic) only, and it is added where
// the diffuse lobe is active (as Mitsuba's scalar variants do).

namespace principled_internal {

/// The lobe probabilities of Mitsuba's principled sampler for a dielectric Fresnel term f:
/// [diffuse, clearcoat, transmission, reflection], normalised. From outside: reflection
/// 1 − bsdf (1 − f), transmission bsdf (1 − f), clearcoat cc/4, diffuse brdf (the first two
/// sum to 1, so the diffuse and clearcoat ones do not depend on f); from inside: f and 1 − f
/// (none of the transmission when bsdf = 0).
struct PrincipledLobes {
  float diffuse = 0, clearcoat = 0, transmission = 0, reflection = 0;
};
inline PrincipledLobes PrincipledLobeProbabilities(const PrincipledParams& p, bool front,
                                                   float f) {
  const float brdf = (1.0f - p.metallic) * (1.0f - p.spec_trans);
  const float bsdf = (1.0f - p.metallic) * p.spec_trans;
  PrincipledLobes l;
  if (front) {
    l.reflection = 1.0f - bsdf * (1.0f - f);
    l.transmission = bsdf * (1.0f - f);
    l.clearcoat = 0.25f * p.clearcoat;
    l.diffuse = brdf;
  } else {
    l.reflection = f;
    l.transmission = bsdf > 0 ? 1.0f - f : 0.0f;
  }
  const float total = l.diffuse + l.clearcoat + l.transmission + l.reflection;
  if (!(total > 0)) return {};
  const float inv = 1.0f / total;
  l.diffuse *= inv, l.clearcoat *= inv, l.transmission *= inv, l.reflection *= inv;
  return l;
}

/// The specular lobe's Fresnel term from outside: the dielectric f weighted by
/// (1 − metallic)(1 − spec_tint), plus Schlick terms of the metal (R0 = base colour) and of
/// the tinted dielectric (R0 = tint · R0(η)); from inside, bsdf · f.
inline Color3f PrincipledFresnel(const PrincipledParams& p, float f, float cos_i, bool front) {
  const float bsdf = (1.0f - p.metallic) * p.spec_trans;
  if (!front) return Color3f{f, f, f} * bsdf;
  Color3f r = Color3f{f, f, f} * ((1.0f - p.metallic) * (1.0f - p.spec_tint));
  if (p.metallic > 0) r += SchlickFresnel(p.base_color, cos_i, p.eta) * p.metallic;
  if (p.spec_tint > 0) {
    const float eta_it = cos_i >= 0 ? p.eta : 1.0f / p.eta;
    const Color3f r0 = TintColor(p.base_color) * SchlickR0(eta_it);
    r += SchlickFresnel(r0, cos_i, p.eta) * ((1.0f - p.metallic) * p.spec_tint);
  }
  return r;
}

/// The half vector of (wo, wi) turned to m.z ≥ 0 (wo + wi, or wo + η_path wi for a
/// refraction); false if it is undefined.
inline bool PrincipledHalfVector(const Vec3f& wo, const Vec3f& wi, float eta_path, bool reflect,
                                 Vec3f* h) {
  const Vec3f sum = reflect ? wo + wi : wo + wi * eta_path;
  const float len2 = Dot(sum, sum);
  if (!(len2 > 0) || !std::isfinite(len2)) return false;
  Vec3f m = sum * (1.0f / std::sqrt(len2));
  if (m.z < 0) m = m * -1.0f;
  *h = m;
  return true;
}

}  // namespace principled_internal

/// f(wo, wi) and (*pdf) the density of PrincipledSample, at once. Both 0 where wo or wi
/// lies in the surface plane.
inline Color3f PrincipledEvalPdf(const PrincipledParams& p, const Vec3f& wo, const Vec3f& wi,
                                 float* pdf) {
  namespace pi = principled_internal;
  *pdf = 0.0f;
  const float cos_o = wo.z, cos_i = wi.z;
  const bool reflect = cos_o * cos_i > 0, refract = cos_o * cos_i < 0;
  if (!reflect && !refract) return {};
  const bool front = cos_o > 0;
  const float eta = p.eta, eta_path = front ? eta : 1.0f / eta;
  const float brdf = (1.0f - p.metallic) * (1.0f - p.spec_trans);
  const float bsdf = (1.0f - p.metallic) * p.spec_trans;
  const float abs_o = std::fabs(cos_o), abs_i = std::fabs(cos_i);
  Color3f f{};
  float density = 0.0f;
  Vec3f h;
  if (pi::PrincipledHalfVector(wo, wi, eta_path, reflect, &h)) {
    const Microfacet dist = pi::PrincipledDistribution(p.roughness, p.anisotropic);
    const float wo_h = Dot(wo, h), wi_h = Dot(wi, h);
    float cos_t;
    const float fd = FresnelDielectric(wo_h, eta, &cos_t);
    const pi::PrincipledLobes lobes = pi::PrincipledLobeProbabilities(p, front, fd);
    const bool reflect_ok = reflect && pi::MicroMacroCompatible(h, wo, wi, cos_o, true);
    const bool refract_ok = refract && pi::MicroMacroCompatible(h, wo, wi, cos_o, false);
    const Vec3f wo_up = front ? wo : wo * -1.0f;
    float jacobian;  // |dh/dwi|
    if (reflect) {
      jacobian = std::fabs(1.0f / (4.0f * wi_h));
    } else {
      const float denom = wo_h + eta_path * wi_h;
      jacobian = std::fabs(eta_path * eta_path * wi_h / (denom * denom));
    }
    if (reflect_ok || refract_ok) {
      const float d = MicrofacetD(dist, h);
      const float g = MicrofacetG(dist, wo, wi, h);
      const float pm = MicrofacetPdf(dist, wo_up, h);
      if (reflect_ok && fd > 0) {
        f += pi::PrincipledFresnel(p, fd, wo_h, front) * (d * g / (4.0f * abs_o * abs_i));
      }
      if (refract_ok && bsdf > 0 && fd < 1) {
        const float denom = wo_h + eta_path * wi_h;
        const float t = bsdf * std::fabs((1.0f - fd) * d * g * wo_h * wi_h /
                                         (abs_o * abs_i * (denom * denom)));
        const Color3f& b = p.base_color;
        f += Color3f{std::sqrt(b.r), std::sqrt(b.g), std::sqrt(b.b)} * t;
      }
      density += (reflect_ok ? lobes.reflection : lobes.transmission) * pm * jacobian;
    }
    if (reflect_ok && front) {
      const float alpha_cc = pi::ClearcoatAlpha(p.clearcoat_gloss);
      if (p.clearcoat > 0) {
        const float fcc = pi::SchlickFresnel(0.04f, wo_h, eta);
        const float v = 0.25f * p.clearcoat * fcc * pi::Gtr1D(alpha_cc, h) * pi::ClearcoatG(wo, wi, h);
        f += Color3f{v, v, v};
      }
      density += lobes.clearcoat * pi::Gtr1Pdf(alpha_cc, h) * jacobian;
    }
    if (reflect && front) {
      density += lobes.diffuse * CosineHemispherePdf(wi);
      if (brdf > 0) {
        const float cos_d = wi_h;
        f += p.base_color *
             (brdf * kInvPi * pi::DiffuseFactor(p.roughness, p.flatness, abs_o, abs_i, cos_d));
        if (p.sheen > 0 && p.metallic < 1) {
          const float v = p.sheen * (1.0f - p.metallic) * pi::SchlickWeight(std::fabs(cos_d));
          f += pi::SheenColor(p) * v;
        }
      }
    }
  }
  if (!IsFinite(f) || !std::isfinite(density)) return *pdf = 0.0f, Color3f{};
  *pdf = density;
  return f;
}

inline Color3f PrincipledEval(const PrincipledParams& p, const Vec3f& wo, const Vec3f& wi) {
  float pdf;
  return PrincipledEvalPdf(p, wo, wi, &pdf);
}
inline float PrincipledPdf(const PrincipledParams& p, const Vec3f& wo, const Vec3f& wi) {
  float pdf;
  PrincipledEvalPdf(p, wo, wi, &pdf);
  return pdf;
}

/// Mitsuba's sampler: a GGX visible normal m for wo turned up, the dielectric F(wo·m) sets
/// the lobe probabilities (PrincipledLobeProbabilities), u_lobe picks diffuse (cosine
/// hemisphere), clearcoat (a GTR1 normal), transmission (refraction about m) or reflection
/// (about m), in that order. pdf = PrincipledPdf and weight = f |cos θi| / pdf at the result;
/// false where the lobe's direction is on the wrong side. eta = η_t/η_i for a refraction.
inline bool PrincipledSample(const PrincipledParams& p, const Vec3f& wo, float u_lobe,
                             const Vec2f& u, BsdfSample* s) {
  namespace pi = principled_internal;
  const float cos_o = wo.z;
  if (cos_o == 0 || !std::isfinite(cos_o)) return false;
  const bool front = cos_o > 0;
  const float bsdf = (1.0f - p.metallic) * p.spec_trans;
  if (!front && !(bsdf > 0)) return false;
  const Microfacet dist = pi::PrincipledDistribution(p.roughness, p.anisotropic);
  const Vec3f wo_up = front ? wo : wo * -1.0f;
  float pm;
  const Vec3f m = SampleMicrofacet(dist, wo_up, u, &pm);
  const float wo_m = Dot(wo, m);
  float cos_t;
  const float fd = FresnelDielectric(wo_m, p.eta, &cos_t);
  const pi::PrincipledLobes lobes = pi::PrincipledLobeProbabilities(p, front, fd);
  Vec3f wi;
  float eta_out = 1.0f;
  if (u_lobe < lobes.diffuse) {
    wi = SampleCosineHemisphere(u);
    if (!(wi.z > 0)) return false;
  } else if (u_lobe < lobes.diffuse + lobes.clearcoat) {
    const Vec3f mc = pi::SampleGtr1(pi::ClearcoatAlpha(p.clearcoat_gloss), u);
    wi = pi::ReflectAbout(wo, mc);
    if (!(wi.z * cos_o > 0) || !pi::MicroMacroCompatible(mc, wo, wi, cos_o, true)) return false;
  } else if (u_lobe < lobes.diffuse + lobes.clearcoat + lobes.transmission) {
    if (!(pm > 0)) return false;
    const float eta_r = wo_m > 0 ? p.eta : 1.0f / p.eta, inv = 1.0f / eta_r;
    const float ct = wo_m > 0 ? -cos_t : cos_t;  // signed cosine of wi w.r.t. m
    wi = m * (wo_m * inv + ct) - wo * inv;
    if (!(wi.z * cos_o < 0) || !pi::MicroMacroCompatible(m, wo, wi, cos_o, false)) return false;
    eta_out = eta_r;
  } else {
    if (!(pm > 0)) return false;
    wi = pi::ReflectAbout(wo, m);
    if (!(wi.z * cos_o > 0) || !pi::MicroMacroCompatible(m, wo, wi, cos_o, true)) return false;
  }
  if (!std::isfinite(wi.x) || !std::isfinite(wi.y) || !std::isfinite(wi.z)) return false;
  float pdf;
  const Color3f f = PrincipledEvalPdf(p, wo, wi, &pdf);
  if (!(pdf > 0)) return false;
  const Color3f w = f * (std::fabs(wi.z) / pdf);
  if (!IsFinite(w)) return false;
  s->wi = wi;
  s->pdf = pdf;
  s->weight = w;
  s->delta = false;
  s->eta = eta_out;
  return true;
}

}  // namespace ptlab
