// Chi-square subjects of emission sampling (engine/light/emission.h): where light subpaths
// start, for every emitter kind.
#pragma once

#include "tools/chi2/subjects.h"

namespace ptlab {

/// Registers, expected to pass unless named "broken/...":
/// - "emission/area_direction": an area light's emitted direction (cosine around its normal,
///   a tilted quad) against EmissionPdf's pdf_dir, on the sphere;
/// - "emission/area_position": the point on a fan of twelve uneven triangles (the plane z = 0)
///   against pdf_pos = 1 / area inside the fan;
/// - "emission/point_direction": a point light's (uniform) directions against pdf_dir;
/// - "emission/distant_disk_direction": the direction light travels from a distant disk,
///   against pdf_dir;
/// - "emission/spot_direction": a spot's directions (uniform over its cone) against pdf_dir;
/// - "emission/environment_direction": an environment map's emitted directions in the map's
///   (u, v), against pdf_dir × 2π² sin θ (on the sphere the 1/sin θ poles defeat the cells'
///   integration);
/// - "emission/infinite_origin_disk": an environment map's ray origin on the scene disk, in the
///   disk's unit coordinates, against pdf_pos × r²;
/// - "broken/emission_area_claims_uniform_direction": cosine-sampled area emission claimed
///   uniform over the hemisphere.
void RegisterEmissionSubjects(Chi2Registry* registry);

}  // namespace ptlab
