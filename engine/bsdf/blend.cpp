// Mitsuba `blendbsdf`: the mixture f = (1 − w) f_first + w f_second of two materials.
#include "engine/bsdf/blend.h"

#include "engine/bsdf/bsdf.h"

namespace ptlab {

Color3f BlendEval(const MaterialTables& m, uint32_t row, const Vec3f& wo, const Vec3f& wi,
                  const TextureSite& site) {
  const float w = BlendWeight(m.blend, row, site);
  return BsdfEval(m, m.blend.First(row), wo, wi, site) * (1.0f - w) +
         BsdfEval(m, m.blend.Second(row), wo, wi, site) * w;
}

float BlendPdf(const MaterialTables& m, uint32_t row, const Vec3f& wo, const Vec3f& wi,
               const TextureSite& site) {
  const float w = BlendWeight(m.blend, row, site);
  return (1.0f - w) * BsdfPdf(m, m.blend.First(row), wo, wi, site) +
         w * BsdfPdf(m, m.blend.Second(row), wo, wi, site);
}

Color3f BlendEvalPdf(const MaterialTables& m, uint32_t row, const Vec3f& wo, const Vec3f& wi,
                     float* pdf, const TextureSite& site) {
  const float w = BlendWeight(m.blend, row, site);
  float p0 = 0.0f, p1 = 0.0f;
  const Color3f f0 = BsdfEvalPdf(m, m.blend.First(row), wo, wi, &p0, site);
  const Color3f f1 = BsdfEvalPdf(m, m.blend.Second(row), wo, wi, &p1, site);
  *pdf = (1.0f - w) * p0 + w * p1;
  return f0 * (1.0f - w) + f1 * w;
}

bool BlendSample(const MaterialTables& m, uint32_t row, const Vec3f& wo, float u_lobe,
                 const Vec2f& u, BsdfSample* s, const TextureSite& site) {
  const float w = BlendWeight(m.blend, row, site);
  float u_child;
  const bool second = BlendPicksSecond(w, u_lobe, &u_child);
  const MaterialRef child = second ? m.blend.Second(row) : m.blend.First(row);
  if (!BsdfSampleDirection(m, child, wo, u_child, u, s, site)) return false;
  if (s->delta) {
    s->pdf *= second ? w : 1.0f - w;
    return s->pdf > 0;
  }
  float pdf = 0.0f;
  const Color3f f = BlendEvalPdf(m, row, wo, s->wi, &pdf, site);
  if (!(pdf > 0) || !std::isfinite(pdf)) return false;
  const Color3f weight = f * (AbsCosTheta(s->wi) / pdf);
  if (!IsFinite(weight)) return false;
  s->pdf = pdf;
  s->weight = weight;
  return true;
}

}  // namespace ptlab
