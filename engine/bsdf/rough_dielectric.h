// Mitsuba 3 `roughdielectric`: a rough interface between two dielectrics (Walter et al. 2007),
// Beckmann or GGX, reflection and refraction chosen by the Fresnel term.
#pragma once

#include <cmath>

#include "engine/bsdf/bsdf_sample.h"
#include "engine/bsdf/fresnel.h"
#include "engine/bsdf/microfacet.h"

namespace ptlab {

/// One row of RoughDielectricTable. eta = int_ior / ext_ior (the normal points to the
/// exterior); reflectance and transmittance are Mitsuba's specular_reflectance and
/// specular_transmittance.
struct RoughDielectricParams {
  Microfacet dist;
  float eta = 1.5046f / 1.000277f;
  Color3f reflectance{1, 1, 1}, transmittance{1, 1, 1};
};

// Conventions: wo (the viewer) and wi may each be on either side; the refracted radiance is
// scaled by (η_o/η_i)² (η on wo's side over η on wi's side, Mitsuba's radiance transport mode),
// so, as for `dielectric` with kDielectricScaleRadiance, a non-absorbing interface carries
// radiance without gain. η_r below is η on the side opposite wo over η on wo's side.

namespace rough_dielectric_internal {

/// The generalised half vector (Walter et al. 2007 eq. 16) turned to m.z > 0, and whether
/// (wo, wi) is a reflection. False when it is undefined (a direction in the plane, h = 0 as
/// for η_r = 1 and wi = −wo) or seen from the back (orientation test of Mitsuba's eval/pdf).
inline bool HalfVector(float eta, const Vec3f& wo, const Vec3f& wi, Vec3f* h, bool* reflect,
                       float* eta_r) {
  const float cos_o = wo.z, cos_i = wi.z;
  if (cos_o == 0 || cos_i == 0) return false;
  *reflect = cos_o * cos_i > 0;
  *eta_r = cos_o > 0 ? eta : 1.0f / eta;
  const Vec3f sum = *reflect ? wo + wi : wo + wi * *eta_r;
  const float len2 = Dot(sum, sum);
  if (!(len2 > 0) || !std::isfinite(len2)) return false;
  Vec3f m = sum * (1.0f / std::sqrt(len2));
  if (m.z < 0) m = m * -1.0f;
  if (!(m.z > 0)) return false;
  if (!(Dot(wo, m) * cos_o > 0) || !(Dot(wi, m) * cos_i > 0)) return false;
  *h = m;
  return true;
}

/// The distribution that draws the normals: as given with visible normals, else with both
/// roughnesses scaled by 1.2 − 0.2 √|cos θo| (Walter et al. 2007 §5.3, as Mitsuba).
inline Microfacet SamplingDistribution(const Microfacet& d, float cos_o) {
  if (d.sample_visible) return d;
  const float s = 1.2f - 0.2f * std::sqrt(std::fabs(cos_o));
  return MakeMicrofacet(d.type, d.alpha_u * s, d.alpha_v * s, false);
}

/// wo turned to the upper side.
inline Vec3f Upper(const Vec3f& w) { return w.z < 0 ? w * -1.0f : w; }

}  // namespace rough_dielectric_internal

/// f(wo, wi): reflection R F D G / (4 |cos θo cos θi|); refraction
/// T (1 − F) D G |wo·h| |wi·h| / (|cos θo cos θi| (wo·h + η_r wi·h)²) (Walter et al. eq. 21
/// with the radiance scale 1/η_r², which cancels its η_r²). F = FresnelDielectric(wo·h, η).
inline Color3f RoughDielectricEval(const RoughDielectricParams& p, const Vec3f& wo,
                                   const Vec3f& wi) {
  namespace rd = rough_dielectric_internal;
  Vec3f h;
  bool reflect;
  float eta_r;
  if (!rd::HalfVector(p.eta, wo, wi, &h, &reflect, &eta_r)) return {};
  const float d = MicrofacetD(p.dist, h);
  if (!(d > 0)) return {};
  float cos_t;
  const float f = FresnelDielectric(Dot(wo, h), p.eta, &cos_t);
  const float g = MicrofacetG(p.dist, wo, wi, h);
  const float cos_oi = std::fabs(wo.z * wi.z);
  Color3f r;
  if (reflect) {
    r = p.reflectance * (f * d * g / (4.0f * cos_oi));
  } else {
    const float wo_h = Dot(wo, h), wi_h = Dot(wi, h);
    const float denom = wo_h + eta_r * wi_h;
    r = p.transmittance *
        ((1.0f - f) * d * g * std::fabs(wo_h * wi_h) / (cos_oi * (denom * denom)));
  }
  return IsFinite(r) ? r : Color3f{};
}

/// Density of RoughDielectricSample: the normal's density (SamplingDistribution) times the
/// lobe's probability (F or 1 − F) times |dh/dwi| (1/(4 |wi·h|), or η_r² |wi·h| / (wo·h +
/// η_r wi·h)² for refraction).
inline float RoughDielectricPdf(const RoughDielectricParams& p, const Vec3f& wo, const Vec3f& wi) {
  namespace rd = rough_dielectric_internal;
  Vec3f h;
  bool reflect;
  float eta_r;
  if (!rd::HalfVector(p.eta, wo, wi, &h, &reflect, &eta_r)) return 0.0f;
  const float wo_h = Dot(wo, h), wi_h = Dot(wi, h);
  float jacobian;
  if (reflect) {
    jacobian = 1.0f / (4.0f * std::fabs(wi_h));
  } else {
    const float denom = wo_h + eta_r * wi_h;
    jacobian = eta_r * eta_r * std::fabs(wi_h) / (denom * denom);
  }
  const float pm = MicrofacetPdf(rd::SamplingDistribution(p.dist, wo.z), rd::Upper(wo), h);
  float cos_t;
  const float f = FresnelDielectric(wo_h, p.eta, &cos_t);
  const float pdf = pm * (reflect ? f : 1.0f - f) * jacobian;
  return std::isfinite(pdf) ? pdf : 0.0f;
}

/// Draws m from SamplingDistribution for wo turned up, then reflects about m if u_lobe <
/// F(wo·m) (always under total internal reflection) and refracts otherwise; false if the
/// result is on the wrong side. As in Mitsuba the pdf and weight are those of the sampled m
/// (not of the half vector recomputed from wi, which is ill-conditioned as η → 1):
/// pdf = MicrofacetPdf(m) · (F or 1 − F) · |dm/dwi|, weight = f |cos θi| / pdf, which with
/// visible normals is R G1(wi, m) or T G1(wi, m) / η_r², else the D G |wo·m| / (pdf_m |cos θo|)
/// of the scaled distribution times R or T / η_r². s->eta = η_r for refraction, 1 for
/// reflection.
inline bool RoughDielectricSample(const RoughDielectricParams& p, const Vec3f& wo, float u_lobe,
                                  const Vec2f& u, BsdfSample* s) {
  namespace rd = rough_dielectric_internal;
  const float cos_o = wo.z;
  if (cos_o == 0 || !std::isfinite(cos_o)) return false;
  const Microfacet sd = rd::SamplingDistribution(p.dist, cos_o);
  float pdf_m;
  const Vec3f m = SampleMicrofacet(sd, rd::Upper(wo), u, &pdf_m);
  if (!(pdf_m > 0)) return false;
  const float wo_m = Dot(wo, m);
  if (!(wo_m * cos_o > 0)) return false;  // the back of m (D cos θm sampling only)
  float cos_t;
  const float f = FresnelDielectric(wo_m, p.eta, &cos_t);
  const bool reflect = u_lobe < f;
  Vec3f wi;
  float jacobian, lobe, eta_r = 1.0f;
  if (reflect) {
    wi = m * (2.0f * wo_m) - wo;
    if (!(wi.z * cos_o > 0)) return false;
    jacobian = 1.0f / (4.0f * std::fabs(wo_m));
    lobe = f;
  } else {
    // η_r relative to m's side of wo, which the orientation of m (m.z > 0) makes wo's side.
    eta_r = wo_m > 0 ? ClampRelativeIor(p.eta) : 1.0f / ClampRelativeIor(p.eta);
    const float inv = 1.0f / eta_r;
    const float ct = wo_m > 0 ? -cos_t : cos_t;  // signed cosine of wi w.r.t. m
    wi = m * (wo_m * inv + ct) - wo * inv;
    if (!(wi.z * cos_o < 0)) return false;
    const float wi_m = Dot(wi, m), denom = wo_m + eta_r * wi_m;
    jacobian = eta_r * eta_r * std::fabs(wi_m) / (denom * denom);
    lobe = 1.0f - f;
  }
  const float pdf = pdf_m * lobe * jacobian;
  if (!(pdf > 0) || !std::isfinite(pdf)) return false;
  float g;
  if (p.dist.sample_visible) {
    g = MicrofacetG1(p.dist, wi, m);
  } else {
    g = MicrofacetD(p.dist, m) * MicrofacetG(p.dist, wo, wi, m) * std::fabs(wo_m) /
        (pdf_m * std::fabs(cos_o));
  }
  const Color3f w =
      reflect ? p.reflectance * g : p.transmittance * (g / (eta_r * eta_r));
  if (!IsFinite(w) || !std::isfinite(wi.x) || !std::isfinite(wi.y)) return false;
  s->wi = wi;
  s->pdf = pdf;
  s->weight = w;
  s->delta = false;
  s->eta = reflect ? 1.0f : eta_r;
  return true;
}

}  // namespace ptlab
