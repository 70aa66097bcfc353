// Vectorized shading: batched Beckmann/Fresnel kernels and the per-material shade step (plain API).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/wavefront/bsdf.h"
#include "engine/scene/material_tables.h"

namespace ptlab::simd {

// Every function here runs an 8-wide Highway kernel (hn::CappedTag<float, 8>: one iteration
// per 8 rows on AVX2/AVX-512, two on SSE4) chosen at run time among the compiled targets, and
// has a scalar oracle of the same name in namespace ptlab (engine/wavefront/bsdf.h). Arrays
// hold n entries (any n; no padding or alignment needed); outputs may not alias inputs.
// Directions are unit vectors in the local shading frame (the "non-unit" guarantee is only: finite out).
// The kernels repeat the oracle's operations in order. They differ from it only through
// hwy/contrib/math (Exp ≤ 1 ulp, Log1p ≤ 2 ulp, Sin/Cos ≤ 3 ulp) and FMA contraction, which is
// blocked where a sum cancels, so the differences stay at a few ulp except where the math is
// ill-conditioned. tests/simd/wavefront/bsdf8_test.cpp checks the contracts below on every compiled
// target, for ≥ 10⁶ random and hard-case inputs: α ∈ [1e-4, 2] and clamped values beyond,
// cos θ down to 0 and denormals, u ∈ {0, 1 − 2⁻²⁴}, η ∈ {1, 1 ± 1e-6, 1.5, 1/1.5}, the
// critical angle. Measured worst cases are in the comments ("seen").

/// Oracle: ptlab::BeckmannEvalPdfBatch (BeckmannEvalPdf in engine/bsdf/beckmann.h).
/// D and pdf: |simd − oracle| ≤ 1e-5 |oracle| + 1e-30 for all inputs (the 1e-30 floor covers
/// values whose exp(−tan²θ/α²) factor underflows; such values are < 1e-30). Seen: 3.2e-7.
void BeckmannEvalPdfBatch(const float* alpha, DirectionArrays wo, DirectionArrays wi, size_t n,
                          float* d, float* pdf);

/// Oracle: ptlab::SampleBeckmannReflectionBatch. wi: |Δ| ≤ 2e-6 per component; pdf equals the
/// oracle's BeckmannReflectionPdf at the returned wi within the contract above. A sample may
/// be valid on one path and not the other only where |wi.z| ≤ 2e-6. Seen: wi 4e-7, pdf 1.1e-6.
void SampleBeckmannReflectionBatch(const float* alpha, DirectionArrays wo, const float* u_x,
                                   const float* u_y, size_t n, DirectionOutArrays wi, float* pdf);

/// Oracle: ptlab::ConductorFresnelBatch (FresnelConductor). |ΔF| ≤ 2e-6 for all η, κ (clamped
/// to [0, 1e4]) and cos ∈ [−1, 1]; relative ≤ 1e-5 for the presets of conductor_presets.h.
/// Seen: 2.4e-7 absolute, 2.9e-7 relative on presets.
void ConductorFresnelBatch(const float* cos_i, const float* eta, const float* k, size_t n,
                           float* f);

/// Oracle: ptlab::DielectricFresnelBatch (FresnelDielectric). |ΔF| ≤ 1e-6 and
/// |Δcos_t| ≤ 1e-6 for all η and cos ∈ [−1, 1], including at the critical angle.
/// Seen: F 6e-8 (1 ulp), cos_t bit-identical.
void DielectricFresnelBatch(const float* cos_i, const float* eta, size_t n, float* f, float* cos_t);

/// One shading step for n hits of material tag `tag` (oracle: ptlab::ShadeBatch, i.e.
/// BsdfEval / BsdfPdf / BsdfSampleDirection per row). Each row gathers its few table
/// parameters by material_index. Contract, per row:
/// - f(wo, wl), pdf(wo, wl): |Δ| ≤ 2e-5 |oracle| + 1e-30 per channel (seen 7.3e-7);
/// - all outputs finite, f, pdf, weight ≥ 0;
/// - the sample has the same validity (pdf > 0) and, for the dielectric, the same lobe, except
///   on a decision boundary: |wi.z| ≤ 2e-6 (|wi.z| ≤ 2e-3 for cosine-hemisphere samples, whose
///   z = √(1 − x² − y²)), or |u_lobe − F| ≤ 2e-6;
/// - wi: |Δx|, |Δy| ≤ 2e-6 and |Δz| ≤ 2e-6 or |Δ(z²)| ≤ 4e-6 (seen 1.5e-5 relative);
/// - non-delta models: pdf and weight equal the oracle's BsdfPdf and BsdfEval |cos θi| /
///   BsdfPdf at the returned wi within 2e-5 relative (+1e-30, +1e-20) when cos θo, cos θi ≥
///   1e-30 (below, values pass through denormals: finiteness only); eta = 1;
/// - delta models: pdf within 2e-6, weight within 2e-5 relative, eta equal;
/// - textured parameters (in.texture set; the diffuse albedo today): the parameter is
///   bit-identical to the oracle's TexturedColor (EvalTexture8, simd/texture/texture8.h), so
///   a textured diffuse row's f and sample weight are too
///   (tests/simd/wavefront/bsdf8_texture_test.cpp).
void ShadeBatch(const MaterialTables& m, MaterialTag tag, const uint32_t* material_index, size_t n,
                const ShadeInputs& in, const ShadeOutputs& out);

/// The shading stage for hits with arbitrary materials (ptlab::ShadeHitsWith around
/// simd::ShadeBatch): partition by tag, one contiguous SIMD batch per tag present, scatter.
/// Oracle: ptlab::ShadeHits; same contract as ShadeBatch.
void ShadeHits(const MaterialTables& m, const MaterialRef* refs, size_t n, const ShadeInputs& in,
               const ShadeOutputs& out, ShadeScratch* scratch);

}  // namespace ptlab::simd
