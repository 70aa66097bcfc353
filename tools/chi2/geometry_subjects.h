// Chi-square subjects of geometric samplers: Beckmann normals, area lights, the thin lens.
#pragma once

#include "engine/core/vec.h"
#include "tools/chi2/subjects.h"

namespace ptlab {

/// The planar quad of "area_light/quad": corners in counter-clockwise order in the plane
/// z = kChi2QuadZ, split along A–C into triangles (A, B, C) and (A, C, D) of areas 0.2938 and
/// 0.11395, so sampling by area and sampling the triangles uniformly differ (2.6 : 1).
inline constexpr Vec2f kChi2QuadA{0.08f, 0.13f}, kChi2QuadB{0.93f, 0.21f}, kChi2QuadC{0.81f, 0.89f},
    kChi2QuadD{0.27f, 0.64f};
inline constexpr float kChi2QuadZ = 0.25f;

/// Registers, expected to pass unless named "broken/...":
/// - "warp/beckmann_normal_a{0p3,1,2}": SampleBeckmannNormal against BeckmannPdfH on the
///   hemisphere (the (φ, cosθ) grid resolves these lobes);
/// - "warp/beckmann_normal_zoom_a{0p0001,0p001,0p05,0p3}": the same on a LobeDisk around +z
///   with k = α (narrower lobes fall inside the top row of the hemisphere grid; α = 1e-4 is
///   the clamp limit kBeckmannMinAlpha);
/// - "area_light/quad": SampleAreaLight over a two-triangle mesh built in code (the quad above),
///   (x, y) on the unit square, pdf 1/area inside the quad (u.x picks the triangle, rescaled);
/// - "camera/thin_lens_aperture": the origins of Camera::GenerateRay (identity camera_to_world,
///   aperture radius 0.3) divided by the radius: uniform on the unit disk;
/// - "broken/beckmann_normal_pdf_no_sin_jacobian": claims the (θ, φ) density D cosθ sinθ as a
///   solid-angle density (α = 0.5);
/// - "broken/beckmann_normal_theta_from_tan": samples θ = α √(−log(1 − u)), i.e. the
///   tan θ of Walter et al.'s eq. 28 taken for θ, against the true pdf (α = 0.5);
/// - "broken/area_light_uniform_triangle_choice": the same light with a triangle CDF of
///   (1/2, 1), as if FinalizeAreaLights ignored the areas.
void RegisterGeometrySubjects(Chi2Registry* registry);

}  // namespace ptlab
