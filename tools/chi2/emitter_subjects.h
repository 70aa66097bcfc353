// Chi-square subjects of emitter sampling: solid-angle sampling of triangles, and the choice of
// an emitter by power, as distributions of directions seen from a shading point.
#pragma once

#include "tools/chi2/subjects.h"

namespace ptlab {

/// Registers, expected to pass unless named "broken/...":
/// - "emitter/spherical_triangle_{near,oblique,wide}": SampleSphericalTriangle from the origin
///   (directions on the sphere) against 1 / solid angle inside the triangle's projection, the
///   solid angle by Girard's theorem in double (not the sampler's formula): a triangle of
///   0.54 sr ahead, a tilted one seen at grazing angles, and one of 2.6 sr;
/// - "emitter/power_selection_four_quads": three quad lights of different power (radiance and
///   area) around the origin, and a fourth, small and far, that solid-angle mode samples by area; u1 picks the light by power (and, rescaled, its triangle), u2 the
///   point by solid angle; pdf = Σ pmf(light) × AreaLightPdf;
/// - "emitter/uniform_selection_area_sampling": the same scene, uniform pick, area sampling;
/// - "broken/power_selection_claims_uniform_pmf": power picks with a pdf built on 1/3 per light;
/// - "simd/area_light_fan_{area,solid_angle}": simd::SampleAreaLightBatch on one light of twelve
///   uneven triangles with vertex normals (a planar fan facing the origin), by area and by solid
///   angle; "simd/area_light_four_quads_area": the four quads, u1 picking a light per row
///   uniformly; pdf = AreaLightPdf (× 1/4 for the quads), the scalar oracle's density;
/// - "broken/simd_area_light_fan_claims_solid_angle_pdf": the fan's area samples against the
///   solid-angle pdf;
/// - "emitter/mitsuba_cylinder_and_disk_area", "simd/area_light_mitsuba_cylinder_and_disk_area":
///   an emitting Mitsuba cylinder and disk (engine/io/mitsuba_meshes.h), uniform pick, area
///   sampling, scalar and SIMD.
void RegisterEmitterSubjects(Chi2Registry* registry);

}  // namespace ptlab
