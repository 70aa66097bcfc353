// Load-time terms of Mitsuba's coated plastics, computed by numerical integration.
#pragma once

#include "engine/core/status.h"
#include "engine/core/vec.h"
#include "engine/scene/plastic_table.h"

namespace ptlab {

/// What a `plastic` / `roughplastic` element says.
struct PlasticDesc {
  CoatingDistribution distribution = CoatingDistribution::kSmooth;
  float alpha = 0.1f;                 // rough coatings only
  float int_ior = 1.49f;              // Mitsuba's default, polypropylene
  float ext_ior = 1.000277f;          // air
  Color3f diffuse{0.5f, 0.5f, 0.5f};  // diffuse_reflectance, in [0, 1]
  Color3f specular{1, 1, 1};          // specular_reflectance, ≥ 0
  bool nonlinear = false;
};

/// Hemispherical reflectance 2 ∫₀¹ F(μ) μ dμ of a smooth interface of relative IOR eta for light
/// arriving from inside (F = FresnelDielectric(−μ, eta), total internal reflection included),
/// by adaptive Gauss–Kronrod quadrature split at the critical angle (error < 1e-9).
double InternalDiffuseFresnel(double eta);

/// The row the BSDF reads (see PlasticRow): base = diffuse / (1 − F_int) / η² (linear) or
/// diffuse / (1 − diffuse F_int) / η² (nonlinear), F_int the coating's internal hemispherical
/// reflectance (InternalDiffuseFresnel for a smooth coating); the specular sampling weight
/// mean(specular) / (mean(diffuse) + mean(specular)) (0.5 when both are 0). Rough coatings:
/// T(μ) at kCoatingTransmittanceRes cosines and R_int = 2 ∫ R(μ; 1/η) μ dμ, each expectation
/// over visible normals by a 48 × 48 Gauss–Legendre rule on the sampling square
/// (engine/bsdf/microfacet.h's SampleMicrofacet, whose pdf cancels), μ by 48-point
/// Gauss–Legendre; separable Smith G1, energy (not radiance) transmittance.
StatusOr<PlasticRow> MakePlasticRow(const PlasticDesc& desc);

}  // namespace ptlab
