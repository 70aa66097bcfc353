// Chi-square subjects of the BSDFs: each model's Sample against its Pdf, scalar and SIMD.
#pragma once

#include <memory>
#include <string>

#include "engine/core/vec.h"
#include "engine/scene/material_tables.h"
#include "tools/chi2/subjects.h"

namespace ptlab {

/// The models with a sampled lobe (mirror and dielectric are delta lobes: nothing to histogram).
/// kBeckmannReflection is the bare microfacet step (reflect wo about h ~ BeckmannPdfH).
enum class Chi2BsdfModel { kDiffuse, kConductor, kRoughPlastic, kBeckmannReflection };

/// Which code draws the samples. kScalar: the per-model functions of engine/bsdf/ (DiffuseSample,
/// ConductorSample, RoughPlasticSample; SampleBeckmannReflectionBatch for the bare step).
/// kSimd: the Highway kernels through Chi2Subject::sample_batch (simd::ShadeBatch on a one-row
/// MaterialTables; simd::SampleBeckmannReflectionBatch). The pdf is the scalar one either way.
enum class Chi2BsdfPath { kScalar, kSimd };

/// Lobes with α below this are tested on a LobeDisk (tools/chi2/lobe_disk.h) around the mirror
/// direction with k = 2α (the reflected lobe is about twice as wide as the half-vector lobe);
/// wider ones on Chi2Domain::Hemisphere(), whose (φ, cosθ) grid resolves them.
inline constexpr float kChi2BsdfZoomAlpha = 0.3f;

/// The rough plastic of the subjects: kd (0.35, 0.3, 0.2), so ks = 0.65; Nori's IORs.
inline constexpr Color3f kChi2PlasticKd{0.35f, 0.3f, 0.2f};

/// Probability that wi = reflect(wo, h), h ~ BeckmannPdfH(α), lies above the surface, for
/// cos θo = cos_theta_o > 0: the mass of a Beckmann reflection sampler (it absorbs the rest).
/// For h at azimuth φ from wo's plane, wi.z = sinθo cosφ sin2θh + cosθo cos2θh > 0 iff
/// θh < θmax(φ) = δ/2 + π/4, δ = atan2(sinθo cosφ, cosθo), whose Beckmann mass is
/// 1 − exp(−tan²θmax/α²); the mean over φ is integrated by adaptive Simpson in double. It
/// uses neither the sampler nor the reflection pdf, so it checks both.
double BeckmannReflectionAlbedo(float alpha, float cos_theta_o);

/// Unit direction at polar angle theta_deg from +z and azimuth phi_deg from +x.
Vec3f Chi2Direction(float theta_deg, float phi_deg);

/// The subject of `model` sampled by `path` at roughness alpha (ignored by kDiffuse) and
/// incident direction wo (local shading frame, wo.z > 0). Reflection only: samples live on the
/// hemisphere, or with `zoom` on its LobeDisk when α < kChi2BsdfZoomAlpha. The albedo is exact: 1
/// (diffuse), A = BeckmannReflectionAlbedo (conductor, bare step), ks A + 1 − ks (rough plastic)
/// — minus 1e-12 where it would be 1 with a cosine lobe, whose sampler drops ~8e-8 of the draws
/// (z = 0 on the square's edge: see bsdf_subjects.cpp);
/// the samples that go below the horizon are absorbed (the lab tests their count too). Rough
/// plastic draws 3 uniforms (u1 picks the lobe). The conductor's and the bare step's pdf go
/// through FlushLobeTail with their value at the mirror direction as the peak.
Chi2Subject BsdfChi2Subject(std::string name, Chi2BsdfModel model, Chi2BsdfPath path, float alpha,
                            const Vec3f& wo, bool zoom = true);

/// A batch sampler for the χ² lab running simd::ShadeBatch on one row `ref` of `m` with wo
/// broadcast (no light evaluation); a sample is valid where its pdf is > 0 and, with
/// `reject_delta`, where it did not take a Dirac-delta lobe (ShadeOutputs::delta: the
/// non-delta part of a model that mixes both).
Chi2BatchSampleFn ShadeBatchSampler(std::shared_ptr<const MaterialTables> m, MaterialRef ref,
                                    const Vec3f& wo, bool reject_delta = false);

/// Registers, all expected to pass unless named "broken/...", incidences θ ∈ {0°, 30°, 60°, 85°}
/// with azimuths φ ∈ {0°, 35°, 110°, 250°}:
/// - "bsdf/diffuse_t{0,30,60,85}";
/// - "bsdf/conductor_a{0p005,0p05,0p2,0p5,1}_t{0,30,60,85}" and hard roughness
///   "bsdf/conductor_a0p0001_t{0,60}", "bsdf/conductor_a2_t{0,60,85}";
/// - "bsdf/rough_plastic_a{0p005,0p05,0p2,0p5,1}_t{0,30,60,85}";
/// - "simd/beckmann_reflection_a{0p005_t30,0p05_t60,0p5_t85}", "simd/shade_diffuse_t60",
///   "simd/shade_conductor_a{0p05_t30,0p5_t85}", "simd/shade_rough_plastic_a{0p05_t60,0p5_t30}";
/// - "broken/conductor_pdf_no_reflection_jacobian": the half-vector density BeckmannPdfH(h)
///   claimed for wi, without 1/(4 wo·h) (α = 0.2, θ = 30°);
/// - "broken/rough_plastic_pdf_swapped_weights": (1 − ks) specular + ks diffuse (α = 0.5,
///   θ = 30°).
void RegisterBsdfSubjects(Chi2Registry* registry);

/// matB (tools/chi2/coated_subjects.cpp; called by RegisterBsdfSubjects): the non-delta
/// samples of the smooth plastic ("bsdf/plastic_eta*_t*", η ∈ {1.1, 1.5, 3}, θ ∈ {0°, 30°,
/// 60°, 85°}, both models; "simd/shade_plastic_eta1p5_t*") and of a blend of a diffuse and a
/// plastic ("bsdf/blend_w{0p25,0p7}", "simd/shade_blend_w*"); a delta sample counts as
/// absorbed, so the mass is the non-delta lobes' probability.
void RegisterCoatedBsdfSubjects(Chi2Registry* registry);

}  // namespace ptlab
