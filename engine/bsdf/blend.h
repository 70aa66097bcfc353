// Mitsuba `blendbsdf`: the mixture f = (1 − w) f_first + w f_second of two materials.
#pragma once

#include <cstdint>

#include "engine/bsdf/bsdf_sample.h"
#include "engine/scene/material_tables.h"
#include "engine/texture/texture_site.h"

namespace ptlab {

// Sampling picks one child per hit (the second with probability w) and samples it; a delta
// sample keeps the child's weight and its pdf is multiplied by the pick's probability, which
// is unbiased: the expected weight over the pick is Σ_k P(k) f_k,δ / p_k,δ · p_k,δ / 1 … i.e.
// each child's delta lobes arrive with probability P(k) p_k and carry f_k,δ / p_k, so their
// contribution is exactly Σ_k P(k) f_k,δ = the mixture's delta part. A non-delta sample is
// given the mixture's own numbers instead of the child's: pdf = Σ P(k) pdf_k(wi) (the density
// with which the whole procedure produces wi) and weight = f cos / pdf of the mixture. The
// child's weight alone would also be unbiased for BSDF sampling on its own, but MIS with
// emitter sampling combines this pdf with BlendPdf's, and the two must be the same density for
// the weights to sum to one; weight = Eval cos / Pdf also holds then, as for every model.

/// f of row `row` (children evaluated through BsdfEval, so nested blends and two-sided
/// children work).
Color3f BlendEval(const MaterialTables& m, uint32_t row, const Vec3f& wo, const Vec3f& wi,
                  const TextureSite& site = {});
/// Σ P(k) pdf_k(wi): the density of BlendSample's non-delta samples.
float BlendPdf(const MaterialTables& m, uint32_t row, const Vec3f& wo, const Vec3f& wi,
               const TextureSite& site = {});
Color3f BlendEvalPdf(const MaterialTables& m, uint32_t row, const Vec3f& wo, const Vec3f& wi,
                     float* pdf, const TextureSite& site = {});
/// u_lobe < w picks the second child (u_lobe / w is passed on as its lobe number), else the
/// first ((u_lobe − w) / (1 − w)); see above for the sample's weight and pdf.
bool BlendSample(const MaterialTables& m, uint32_t row, const Vec3f& wo, float u_lobe,
                 const Vec2f& u, BsdfSample* s, const TextureSite& site = {});
/// mask: row `row`'s weight at `site`: the constant or its texture's value (TexturedFloat),
/// clamped to [0, 1] as Mitsuba clips it (NaN → 1). The children get the same site.
inline float BlendWeight(const BlendTable& t, uint32_t row, const TextureSite& site) {
  return TexturedUnitFloat(t.weight_texture, row, t.weight[row], site);
}

/// The child pick of BlendSample: true for the second child, *u_child its lobe number.
inline bool BlendPicksSecond(float weight, float u_lobe, float* u_child) {
  constexpr float kBelowOne = 0x1.fffffep-1f;
  if (u_lobe < weight) {
    const float v = u_lobe / weight;
    *u_child = v < kBelowOne ? v : kBelowOne;
    return true;
  }
  const float v = (u_lobe - weight) / (1.0f - weight);
  *u_child = v < kBelowOne ? (v > 0 ? v : 0.0f) : kBelowOne;
  return false;
}

}  // namespace ptlab
