// Nori `microfacet`: Beckmann rough plastic, f = kd/π + ks D F G / (4 cos θi cos θo cos θh).
#pragma once

#include <algorithm>

#include "engine/bsdf/beckmann.h"
#include "engine/bsdf/bsdf_sample.h"
#include "engine/bsdf/fresnel.h"
#include "engine/sampling/warp.h"

namespace ptlab {

/// One row of RoughPlasticTable, with Nori's defaults (alpha 0.1, intIOR 1.5046,
/// extIOR 1.000277, kd 0.5). eta = intIOR / extIOR; ks = 1 − max(kd) (clamped to [0, 1]).
struct RoughPlasticParams {
  float alpha = 0.1f;
  float eta = 1.5046f / 1.000277f;
  Color3f kd{0.5f, 0.5f, 0.5f};
  float ks = 0.5f;
};

inline RoughPlasticParams MakeRoughPlasticParams(float alpha, float int_ior, float ext_ior,
                                                 const Color3f& kd) {
  RoughPlasticParams p;
  p.alpha = alpha;
  p.eta = int_ior / ext_ior;
  p.kd = kd;
  p.ks = std::clamp(1.0f - MaxComponent(kd), 0.0f, 1.0f);
  return p;
}

/// RoughPlasticEval's value given the Beckmann D of H = wo + wi (both above the surface).
inline Color3f RoughPlasticEvalOfD(const RoughPlasticParams& p, const Vec3f& wo, const Vec3f& wi,
                                   const Vec3f& h, float d) {
  Color3f f = p.kd * kInvPi;
  if (d > 0 && p.ks > 0) {
    float cos_t;
    const float fr = FresnelDielectric(0.5f * std::sqrt(Dot(h, h)), p.eta, &cos_t);
    const float g = BeckmannG1OverCos(p.alpha, wo) * BeckmannG1OverCos(p.alpha, wi);
    const float spec = p.ks * fr * (0.25f * d * g);
    if (std::isfinite(spec)) f += Color3f{spec, spec, spec};
  }
  return f;
}

/// Nori's BRDF (SOURCES.md): kd/π + ks D_Nori F(wh·wi) G / (4 cos θi cos θo cos θh) with
/// D_Nori = BeckmannPdfH, i.e. ks BeckmannD F G / (4 cos θi cos θo); F is the exact dielectric
/// Fresnel term for η = intIOR/extIOR and G = G1(wi) G1(wo). One-sided (0 unless both
/// directions are above the surface) and symmetric in (wo, wi).
inline Color3f RoughPlasticEval(const RoughPlasticParams& p, const Vec3f& wo, const Vec3f& wi) {
  if (!(wo.z > 0) || !(wi.z > 0)) return {};
  const Vec3f h = wo + wi;
  return RoughPlasticEvalOfD(p, wo, wi, h, BeckmannD(p.alpha, h));
}

/// Mixture density of RoughPlasticSample: ks BeckmannReflectionPdf + (1 − ks) cos θi / π.
inline float RoughPlasticPdf(const RoughPlasticParams& p, const Vec3f& wo, const Vec3f& wi) {
  if (!(wo.z > 0) || !(wi.z > 0)) return 0.0f;
  return p.ks * BeckmannReflectionPdf(p.alpha, wo, wi) + (1.0f - p.ks) * (wi.z * kInvPi);
}

/// RoughPlasticEval and (*pdf) RoughPlasticPdf, bit for bit, with the Beckmann D of H = wo + wi
/// that both evaluate computed once.
inline Color3f RoughPlasticEvalPdf(const RoughPlasticParams& p, const Vec3f& wo, const Vec3f& wi,
                                   float* pdf) {
  *pdf = 0.0f;
  if (!(wo.z > 0) || !(wi.z > 0)) return {};
  const Vec3f h = wo + wi;
  const float d = BeckmannD(p.alpha, h);
  float specular_pdf = 0.0f;
  BeckmannReflectionPdfOfD(d, wo, h, &specular_pdf);
  *pdf = p.ks * specular_pdf + (1.0f - p.ks) * (wi.z * kInvPi);
  return RoughPlasticEvalOfD(p, wo, wi, h, d);
}

/// u_lobe < ks picks the specular lobe (h ~ BeckmannPdfH from u, wi = reflect(wo, h)), else
/// wi is cosine-distributed from u. The weight is Eval cos θi / Pdf of the whole mixture.
inline bool RoughPlasticSample(const RoughPlasticParams& p, const Vec3f& wo, float u_lobe,
                               const Vec2f& u, BsdfSample* s) {
  if (!(wo.z > 0)) return false;
  const Vec3f wi = u_lobe < p.ks ? ReflectAbout(wo, SampleBeckmannNormal(p.alpha, u))
                                 : SampleCosineHemisphere(u);
  if (!(wi.z > 0)) return false;
  const float pdf = RoughPlasticPdf(p, wo, wi);
  if (!(pdf > 0) || !std::isfinite(pdf)) return false;
  const Color3f w = RoughPlasticEval(p, wo, wi) * (wi.z / pdf);
  if (!IsFinite(w)) return false;
  s->wi = wi;
  s->pdf = pdf;
  s->weight = w;
  s->delta = false;
  s->eta = 1.0f;
  return true;
}

}  // namespace ptlab
