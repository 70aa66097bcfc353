// Mitsuba `plastic` / `roughplastic` rows: a dielectric coating over a diffuse base (SoA).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/aligned.h"
#include "engine/core/vec.h"

namespace ptlab {

/// The coating's surface: smooth (`plastic`) or a rough microfacet interface (`roughplastic`).
enum class CoatingDistribution : uint8_t { kSmooth = 0, kBeckmann = 1, kGgx = 2 };

/// Points of the rough coating's external transmittance table over cos θ ∈ [0, 1] (uniform in
/// cos θ, linear interpolation; Mitsuba uses the same resolution).
inline constexpr int kCoatingTransmittanceRes = 64;

/// One row as the BSDF reads it; every derived term is computed once at load by
/// MakePlasticRow (engine/bsdf/plastic_precompute.h).
struct PlasticRow {
  CoatingDistribution distribution = CoatingDistribution::kSmooth;
  float alpha = 0.0f;  // isotropic roughness (rough rows only)
  float eta = 1.49f / 1.000277f;  // int_ior / ext_ior
  /// The diffuse base as the coated BSDF sees it: diffuse_reflectance / (1 − (nonlinear ? ρ_d
  /// F_dr,int : F_dr,int)) / η², so that f_diffuse = base · T(θo) T(θi) / π.
  Color3f base{0.5f, 0.5f, 0.5f};
  Color3f specular{1, 1, 1};  // specular_reflectance
  float specular_sampling_weight = 0.5f;  // mean(specular) / (mean(diffuse) + mean(specular))
  /// Rough rows: the coating's external transmittance T(μ) at μ = j / (Res − 1), j < Res.
  float transmittance[kCoatingTransmittanceRes] = {};
};

/// Rows of PlasticRow, one column per field; `transmittance` holds kCoatingTransmittanceRes
/// floats per row (row-major), and is filled for rough rows only (smooth rows keep zeros: their
/// transmittance 1 − F is exact).
struct PlasticTable {
  AlignedVector<uint8_t> distribution;
  AlignedVector<float> alpha, eta, base_r, base_g, base_b, specular_r, specular_g, specular_b,
      specular_sampling_weight;
  AlignedVector<float> transmittance;
  size_t size() const { return alpha.size(); }

  uint32_t Add(const PlasticRow& r) {
    distribution.push_back(static_cast<uint8_t>(r.distribution));
    alpha.push_back(r.alpha), eta.push_back(r.eta);
    base_r.push_back(r.base.r), base_g.push_back(r.base.g), base_b.push_back(r.base.b);
    specular_r.push_back(r.specular.r), specular_g.push_back(r.specular.g),
        specular_b.push_back(r.specular.b);
    specular_sampling_weight.push_back(r.specular_sampling_weight);
    transmittance.insert(transmittance.end(), r.transmittance,
                         r.transmittance + kCoatingTransmittanceRes);
    return uint32_t(size() - 1);
  }
  PlasticRow Row(size_t i) const {
    PlasticRow r;
    r.distribution = static_cast<CoatingDistribution>(distribution[i]);
    r.alpha = alpha[i], r.eta = eta[i];
    r.base = {base_r[i], base_g[i], base_b[i]};
    r.specular = {specular_r[i], specular_g[i], specular_b[i]};
    r.specular_sampling_weight = specular_sampling_weight[i];
    for (int j = 0; j < kCoatingTransmittanceRes; ++j)
      r.transmittance[j] = transmittance[i * kCoatingTransmittanceRes + j];
    return r;
  }
};

}  // namespace ptlab
