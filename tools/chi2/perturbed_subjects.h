// Chi-square subjects of the normalmap / bumpmap wrappers (engine/bsdf/perturbed_frame.h): a
// row sampled in its perturbed shading frame, against BsdfPdf of the same row and site.
#pragma once

#include "tools/chi2/subjects.h"

namespace ptlab {

/// Registers (all expected to pass; the mass is unknown, as a sample on the other side of the
/// perturbed frame than of the shading frame is absorbed), on the hemisphere of the shading
/// frame, over one triangle with ∂p/∂u = (0.8, 0.6, 0.1), ∂p/∂v = (−0.6, 0.8, 0):
/// - "bsdf/normalmap_diffuse_t{20,70}" and "bsdf/normalmap_ggx_conductor_t{20,70}": a constant
///   normal map of RGB (0.85, 0.35, 0.8) (a normal tilted by ~50°) over a diffuse and over an
///   anisotropic visible-normal GGX conductor (αu 0.25, αv 0.1);
/// - "bsdf/bumpmap_diffuse_t{20,70}": a height ramp along u (a 2 × 1 clamped bitmap, scale
///   0.4) over a diffuse.
void RegisterPerturbedBsdfSubjects(Chi2Registry* registry);

}  // namespace ptlab
