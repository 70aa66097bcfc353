// Mitsuba `mask`: a nested material seen with probability `opacity` (a constant or a texture),
// else the surface is passed through (Mitsuba's null lobe).
#pragma once

#include <cstdint>

#include "engine/bsdf/bsdf_sample.h"
#include "engine/scene/material_tables.h"
#include "engine/texture/texture_site.h"

namespace ptlab {

// The rule (Mitsuba 3's mask.cpp and path.cpp, docs/materials.md "mask"):
// - f = opacity · f_nested, pdf = opacity · pdf_nested (emitter sampling at a mask hit sees the
//   nested material scaled by its opacity).
// - A sample picks the nested material with probability opacity (u_lobe < opacity, u_lobe /
//   opacity passed on as its lobe number): its wi and weight, its pdf times opacity.
// - Otherwise a pass-through: wi = −wo, weight 1, eta 1, pdf = 1 − opacity (the discrete
//   probability of the lobe), delta = true: Mitsuba's null lobe counts as a delta lobe
//   (BSDFFlags::Delta = Null | DeltaReflection | DeltaTransmission), so the emission the
//   continued path hits is counted in full (no MIS against emitter sampling), as after a
//   mirror. The pass-through counts as a bounce towards max_depth (Mitsuba's path tracer
//   increments its depth at every surface interaction).
// - Shadow rays see the mask as an opaque surface (Mitsuba's path tracer tests visibility with
//   ray_test, which ignores opacity).

/// Row `row`'s opacity at `site`: the constant or its texture's value, clipped to [0, 1].
inline float MaskOpacity(const MaskTable& t, uint32_t row, const TextureSite& site) {
  return TexturedUnitFloat(t.opacity_texture, row, t.opacity[row], site);
}

/// The nested pick of MaskSample: true for the nested material (*u_nested its lobe number).
inline bool MaskPicksNested(float opacity, float u_lobe, float* u_nested) {
  constexpr float kBelowOne = 0x1.fffffep-1f;
  if (!(u_lobe < opacity)) return false;
  const float v = u_lobe / opacity;
  *u_nested = v < kBelowOne ? v : kBelowOne;
  return true;
}

Color3f MaskEval(const MaterialTables& m, uint32_t row, const Vec3f& wo, const Vec3f& wi,
                 const TextureSite& site);
float MaskPdf(const MaterialTables& m, uint32_t row, const Vec3f& wo, const Vec3f& wi,
              const TextureSite& site);
Color3f MaskEvalPdf(const MaterialTables& m, uint32_t row, const Vec3f& wo, const Vec3f& wi,
                    float* pdf, const TextureSite& site);
bool MaskSample(const MaterialTables& m, uint32_t row, const Vec3f& wo, float u_lobe,
                const Vec2f& u, BsdfSample* s, const TextureSite& site);

}  // namespace ptlab
