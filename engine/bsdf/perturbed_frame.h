// normal: Mitsuba 3's `normalmap` and `bumpmap` wrappers: a material row's BSDF evaluated in a
// shading frame that a texture perturbs (the component engine/scene/shading_perturbation.h).
#pragma once

#include "engine/bsdf/bsdf_sample.h"
#include "engine/core/frame.h"
#include "engine/scene/material_tables.h"
#include "engine/texture/texture_site.h"

namespace ptlab {

/// True when row `ref` is perturbed and this call is not yet inside its wrapper: then the
/// dispatch (engine/bsdf/bsdf.cpp) hands the call to the Perturbed* functions below, which
/// call the dispatch again with site.frame_perturbed set (the row's own BSDF).
inline bool PerturbsFrame(const MaterialTables& m, MaterialRef ref, const TextureSite& site) {
  return !m.perturbation.empty() && !site.frame_perturbed && m.perturbation.Of(ref) >= 0;
}

/// The surface's uv tangents at `site` in the local shading frame (z = shading normal): the
/// triangle's ∂p/∂u, ∂p/∂v (ShadingPerturbations' columns) and the geometric normal ng. A
/// sphere, an instanced triangle or a triangle whose uv map is degenerate (zero uv area, or
/// tangents that are not finite) gets Mitsuba's fallback: ∂p/∂u, ∂p/∂v = the Duff et al.
/// basis (Frame) around ng.
struct LocalTangents {
  Vec3f dp_du, dp_dv, ng;
};
LocalTangents LocalTangentsAt(const ShadingPerturbations& p, const TextureSite& site);

/// The perturbed shading frame of row `ref` (perturbation id `id`) in the local shading frame,
/// for the viewer direction wo (local). Mitsuba's frame of the unperturbed surface has its s
/// along ∂p/∂u projected onto the tangent plane (Duff's s where that projection vanishes); then
/// - normal map: n = normalize(2c − 1) with c the texture's RGB, in that frame;
/// - bump map: ∂p/∂u' = ∂p/∂u + (scale ∂h/∂u − n·∂p/∂u) n, likewise ∂p/∂v', and
///   n = normalize(∂p/∂u' × ∂p/∂v'), flipped to the side of ng;
/// in both, n's tangential part is negated where wo.z · (wo · n) ≤ 0 (Mitsuba's
/// flip_invalid_normals), s = ∂p/∂u-direction (normal map: the frame's s) made orthogonal to n,
/// t = n × s. A normal that vanishes or is not finite becomes (0, 0, 1), an s that does,
/// Frame(n)'s: the frame is orthonormal and finite for every input.
Frame PerturbedFrame(const MaterialTables& m, int64_t id, const Vec3f& wo, const TextureSite& site);

/// Mitsuba's shadowing term for bump and normal maps (Estevez et al., "A Microfacet-Based
/// Shadowing Function to Solve the Bump Terminator Problem", Ray Tracing Gems 2019):
/// 2 / (1 + sqrt(1 + α² tan²θ(w))) with α² = min(tan²θ(n) / 8, 1); n the perturbed normal and
/// w a direction, both local. 1 for n = z; 0 for w in the tangent plane when n ≠ z.
float ShadowTerminator(const Vec3f& n, const Vec3f& w);

// The wrapped calls (BsdfEval, BsdfPdf, BsdfEvalPdf, BsdfSampleDirection of row `ref` whose
// PerturbsFrame holds), Mitsuba's semantics in ptlab's conventions (wo to the viewer, wi to
// the light, f without the cosine): wo and wi go into the perturbed frame P; a wi on
// different sides of P and of the shading frame (wi.z · P(wi).z ≤ 0) gets f = 0, pdf = 0 and
// is no sample; f = f_row(P wo, P wi) · |P(wi).z| / |wi.z| · ShadowTerminator(P.n, wi), so that
// f |cos θi| is Mitsuba's cosine-weighted value; a sample's weight is the row's times the
// shadowing term, its pdf the row's (a solid-angle density, the same in both frames).
Color3f PerturbedBsdfEval(const MaterialTables& m, MaterialRef ref, const Vec3f& wo,
                          const Vec3f& wi, const TextureSite& site);
float PerturbedBsdfPdf(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, const Vec3f& wi,
                       const TextureSite& site);
Color3f PerturbedBsdfEvalPdf(const MaterialTables& m, MaterialRef ref, const Vec3f& wo,
                             const Vec3f& wi, float* pdf, const TextureSite& site);
bool PerturbedBsdfSample(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, float u1,
                         const Vec2f& u2, BsdfSample* sample, const TextureSite& site);

}  // namespace ptlab
