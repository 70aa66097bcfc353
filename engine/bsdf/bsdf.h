// BSDF dispatch over the closed set of material models: one switch on the MaterialRef tag.
#pragma once

#include "engine/bsdf/bsdf_sample.h"
#include "engine/scene/material_tables.h"
#include "engine/texture/texture_site.h"

namespace ptlab {

/// True for models whose every lobe is a Dirac delta (mirror, smooth dielectric).
constexpr bool IsDeltaMaterial(MaterialTag tag) {
  return tag == MaterialTag::kMirror || tag == MaterialTag::kDielectric ||
         tag == MaterialTag::kThinDielectric;
}
/// True for models that are not delta materials but whose samples may come from a delta lobe
/// (a plastic's coating, a blend's delta child): BsdfSample::delta says which lobe a sample
/// took, and a path that continues from such a sample is specular (its emission is not seen
/// by emitter sampling), while Eval / Pdf cover the non-delta lobes only.
constexpr bool MixesDeltaLobes(MaterialTag tag) {
  return tag == MaterialTag::kPlastic || tag == MaterialTag::kBlend ||
         tag == MaterialTag::kMask;  // mask: a delta nested material's samples
}

// The functions below are the scalar oracle of every model, addressed by MaterialRef (the
// per-model free functions live in diffuse.h, mirror.h, dielectric.h, conductor.h and
// rough_plastic.h). Directions are unit vectors in the local shading frame (z = shading
// normal); wo points to the viewer, wi to the light. No NaN or Inf ever comes out: f ≥ 0,
// pdf ≥ 0 and finite, and a sample's weight is finite.

// `site`: the shading point's textures, which a textured parameter (engine/texture/
// texture_site.h) reads; a scene without textures passes none (a textured row without a site
// stops at a PTLAB_CHECK).

/// f(wo, wi) in the local shading frame (0 for delta models).
Color3f BsdfEval(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, const Vec3f& wi,
                 const TextureSite& site = {});
/// Solid-angle pdf with which BsdfSampleDirection would pick wi (0 for delta models).
float BsdfPdf(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, const Vec3f& wi,
              const TextureSite& site = {});
/// BsdfEval and (*pdf) BsdfPdf at once, bit for bit: one dispatch, and the rough plastic's
/// Beckmann D, which both evaluate, once (an MIS-weighted emitter sample needs the two).
Color3f BsdfEvalPdf(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, const Vec3f& wi,
                    float* pdf, const TextureSite& site = {});
/// Samples wi given wo; u1 picks a lobe, u2 the direction. False when no sample is possible.
/// For non-delta models sample->weight = Eval·|cos θi|/Pdf and sample->pdf = Pdf(wo, wi).
bool BsdfSampleDirection(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, float u1,
                         const Vec2f& u2, BsdfSample* sample, const TextureSite& site = {});

/// Row i's diffuse albedo: the constant or, when textured, its texture at `site`.
inline Color3f DiffuseAlbedo(const DiffuseTable& t, uint32_t i, const TextureSite& site) {
  return TexturedColor(t.albedo_texture, i, t.Albedo(i), site);
}

}  // namespace ptlab
