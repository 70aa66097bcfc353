// Mitsuba 3 `principledthin`: Burley's thin-surface Disney BSDF (2015 §5) — a diffuse/retro/sheen
// reflection, a Lambertian diffuse transmission, and a GGX specular reflection plus a
// straight-through rough transmission (roughness scaled by 0.65 η − 0.35), the two weighted by
// spec_trans as in Mitsuba. Symmetric: wo below the surface is shaded as its mirror image.
#pragma once

#include <cmath>

#include "engine/bsdf/bsdf_sample.h"
#include "engine/bsdf/fresnel.h"
#include "engine/bsdf/principled_lobes.h"
#include "engine/sampling/warp.h"

namespace ptlab {

namespace principled_internal {

/// Lobe probabilities of Mitsuba's principledthin sampler: [specular reflection, specular
/// transmission, diffuse reflection, diffuse transmission] = [st/2, st/2, (1 − st)(1 − dt),
/// (1 − st) dt], which sum to 1.
struct ThinLobes {
  float reflection = 0, transmission = 0, diffuse = 0, diffuse_transmission = 0;
};
inline ThinLobes ThinLobeProbabilities(const PrincipledParams& p) {
  ThinLobes l;
  l.reflection = 0.5f * p.spec_trans;
  l.transmission = 0.5f * p.spec_trans;
  l.diffuse = (1.0f - p.spec_trans) * (1.0f - p.diff_trans);
  l.diffuse_transmission = (1.0f - p.spec_trans) * p.diff_trans;
  const float total = l.reflection + l.transmission + l.diffuse + l.diffuse_transmission;
  if (!(total > 0)) return {};
  const float inv = 1.0f / total;
  l.reflection *= inv, l.transmission *= inv, l.diffuse *= inv, l.diffuse_transmission *= inv;
  return l;
}

/// The transmission lobe's GGX: roughness scaled by 0.65 η − 0.35 (Burley 2015, fig. 15).
inline Microfacet ThinTransmissionDistribution(const PrincipledParams& p) {
  return PrincipledDistribution((0.65f * p.eta - 0.35f) * p.roughness, p.anisotropic);
}

}  // namespace principled_internal

/// f(wo, wi) and (*pdf) the density of PrincipledThinSample, at once. With wo and wi turned so
/// that wo is above (wo', wi'), h = normalize(wo' + wi' with |z|).
inline Color3f PrincipledThinEvalPdf(const PrincipledParams& p, const Vec3f& wo, const Vec3f& wi,
                                     float* pdf) {
  namespace pi = principled_internal;
  *pdf = 0.0f;
  if (wo.z == 0 || !std::isfinite(wo.z)) return {};
  const bool flip = wo.z < 0;
  const Vec3f v = flip ? wo * -1.0f : wo, l = flip ? wi * -1.0f : wi;
  const bool reflect = l.z > 0, refract = l.z < 0;
  if (!reflect && !refract) return {};
  const float cos_o = v.z, abs_i = std::fabs(l.z);
  const Vec3f l_up{l.x, l.y, abs_i};
  const Vec3f sum = v + l_up;
  const float len2 = Dot(sum, sum);
  if (!(len2 > 0) || !std::isfinite(len2)) return {};
  const Vec3f h = sum * (1.0f / std::sqrt(len2));
  const pi::ThinLobes lobes = pi::ThinLobeProbabilities(p);
  const float st = p.spec_trans, dt = p.diff_trans;
  Color3f f{};
  float density = 0.0f;
  if (st > 0) {
    const float jacobian = std::fabs(1.0f / (4.0f * Dot(l_up, h)));
    float cos_t;
    const float fd = FresnelDielectric(Dot(v, h), p.eta, &cos_t);
    if (reflect && pi::MicroMacroCompatible(h, v, l, cos_o, true)) {
      const Microfacet dist = pi::PrincipledDistribution(p.roughness, p.anisotropic);
      Color3f fr{fd, fd, fd};
      if (p.spec_tint > 0) {
        const Color3f r0 = pi::TintColor(p.base_color) * pi::SchlickR0(p.eta);
        fr = pi::Lerp(fr, pi::SchlickFresnel(r0, Dot(v, h), p.eta), p.spec_tint);
      }
      const float dg = MicrofacetD(dist, h) * MicrofacetG(dist, v, l, h);
      f += fr * (st * dg / (4.0f * cos_o * abs_i));
      density += lobes.reflection * MicrofacetPdf(dist, v, h) * jacobian;
    }
    if (refract && pi::MicroMacroCompatible(h, v, l, cos_o, false)) {
      const Microfacet dist = pi::ThinTransmissionDistribution(p);
      const float dg = MicrofacetD(dist, h) * MicrofacetG(dist, v, l, h);
      f += p.base_color * (st * (1.0f - fd) * dg / (4.0f * cos_o * abs_i));
      density += lobes.transmission * MicrofacetPdf(dist, v, h) * jacobian;
    }
  }
  if (reflect) {
    density += lobes.diffuse * CosineHemispherePdf(l);
    if (st < 1 && dt < 1) {
      const float cos_d = Dot(h, l);
      f += p.base_color * ((1.0f - st) * kInvPi * (1.0f - dt) *
                           pi::DiffuseFactor(p.roughness, p.flatness, cos_o, abs_i, cos_d));
      if (p.sheen > 0) {
        const float s = p.sheen * (1.0f - st) * pi::SchlickWeight(std::fabs(cos_d)) * (1.0f - dt);
        f += pi::SheenColor(p) * s;
      }
    }
  } else {
    density += lobes.diffuse_transmission * CosineHemispherePdf(l_up);
    if (st < 1 && dt > 0) f += p.base_color * ((1.0f - st) * dt * kInvPi);
  }
  if (!IsFinite(f) || !std::isfinite(density)) return {};
  *pdf = density;
  return f;
}

inline Color3f PrincipledThinEval(const PrincipledParams& p, const Vec3f& wo, const Vec3f& wi) {
  float pdf;
  return PrincipledThinEvalPdf(p, wo, wi, &pdf);
}
inline float PrincipledThinPdf(const PrincipledParams& p, const Vec3f& wo, const Vec3f& wi) {
  float pdf;
  PrincipledThinEvalPdf(p, wo, wi, &pdf);
  return pdf;
}

/// Mitsuba's sampler, wo turned above: u_lobe picks specular reflection (a visible GGX
/// normal, reflect), specular transmission (a visible normal of the scaled GGX, reflect and
/// mirror through the surface), diffuse reflection or diffuse transmission (cosine
/// hemisphere, below for the latter); the result turned back. pdf = PrincipledThinPdf,
/// weight = f |cos θi| / pdf; eta = 1 (a thin surface bends no ray).
inline bool PrincipledThinSample(const PrincipledParams& p, const Vec3f& wo, float u_lobe,
                                 const Vec2f& u, BsdfSample* s) {
  namespace pi = principled_internal;
  if (wo.z == 0 || !std::isfinite(wo.z)) return false;
  const bool flip = wo.z < 0;
  const Vec3f v = flip ? wo * -1.0f : wo;
  const pi::ThinLobes lobes = pi::ThinLobeProbabilities(p);
  Vec3f l;
  if (u_lobe < lobes.reflection + lobes.transmission) {
    const bool reflect = u_lobe < lobes.reflection;
    const Microfacet dist = reflect ? pi::PrincipledDistribution(p.roughness, p.anisotropic)
                                    : pi::ThinTransmissionDistribution(p);
    float pm;
    const Vec3f m = SampleMicrofacet(dist, v, u, &pm);
    if (!(pm > 0)) return false;
    l = pi::ReflectAbout(v, m);
    if (!reflect) l.z = -l.z;
    if (!(reflect ? l.z > 0 : l.z < 0) || !pi::MicroMacroCompatible(m, v, l, v.z, reflect))
      return false;
  } else {
    l = SampleCosineHemisphere(u);
    if (u_lobe >= lobes.reflection + lobes.transmission + lobes.diffuse) l.z = -l.z;
    if (l.z == 0) return false;
  }
  const Vec3f wi = flip ? l * -1.0f : l;
  if (!std::isfinite(wi.x) || !std::isfinite(wi.y) || !std::isfinite(wi.z)) return false;
  float pdf;
  const Color3f f = PrincipledThinEvalPdf(p, wo, wi, &pdf);
  if (!(pdf > 0)) return false;
  const Color3f w = f * (std::fabs(wi.z) / pdf);
  if (!IsFinite(w)) return false;
  s->wi = wi;
  s->pdf = pdf;
  s->weight = w;
  s->delta = false;
  s->eta = 1.0f;
  return true;
}

}  // namespace ptlab
