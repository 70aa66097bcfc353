// Chi-square subjects of the Mitsuba microfacet models: rough conductor and rough dielectric,
// each model's Sample against its Pdf, scalar and SIMD.
#pragma once

#include "tools/chi2/subjects.h"

namespace ptlab {

/// Registers (all expected to pass), each with the sampler's mass unknown (samples that leave
/// the hemisphere, or the sphere's valid side, are absorbed) and the pdf BsdfPdf of the same
/// one-row table:
/// - "bsdf/rough_conductor_{ggx,beckmann}{,_dcos}_a<αu>[x<αv>]_t<θ>": GGX and Beckmann,
///   visible normals or D cos θ sampling, isotropic and anisotropic, on the hemisphere (α ≥ 0.3)
///   or on a LobeDisk around the mirror direction (narrower lobes);
/// - "bsdf/rough_dielectric_{ggx,beckmann}{,_dcos}_a<α>[x<αv>]_eta<η>_t<θ>" on the sphere, θ
///   > 90° meaning wo inside (incl. beyond the critical angle);
/// - "simd/shade_rough_conductor_..." and "simd/shade_rough_dielectric_...": the same through
///   simd::ShadeBatch.
void RegisterMicrofacetBsdfSubjects(Chi2Registry* registry);

}  // namespace ptlab
