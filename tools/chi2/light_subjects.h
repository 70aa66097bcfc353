// Chi-square subjects of the infinite lights: environment maps, distant disks, 1-D/2-D
// distributions.
#pragma once

#include <string>

#include "tools/chi2/subjects.h"

namespace ptlab {

/// Where RegisterLightSubjects(registry) looks for envmaps/venice_sunset_1k.exr: the
/// PTLAB_DATA environment variable if set and not empty, else <source tree>/../shared/data (from
/// this file's compile-time path).
std::string DefaultLightDataDir();

/// Registers, all expected to pass unless named "broken/...":
/// - "envmap/importance_{gradient,hot_pixel,pole_rows,1x1,rotated_gradient}": importance
///   sampling of synthetic maps (a 16x8 luminance gradient with colour, one hot pixel in 32x16,
///   bright rows at both poles, a 1x1 map, the gradient under another rotation). Their toWorld
///   puts the map's poles on the domain's poles: the importance pdf grows as 1/sinθ there, a
///   point singularity Simpson cannot integrate inside the (φ, cosθ) rectangle; at cosθ = ±1 it
///   integrates, to within ~5e-4 of 1 (the lab allows 1e-3);
/// - "envmap/uniform_gradient": the uniform strategy (default orientation);
/// - "envmap/importance_venice_32x16": venice_sunset_1k.exr box-filtered to 32x16 (a real map at
///   a resolution whose cells the pdf integration can resolve), only when the file is present
///   under data_dir;
/// - "simd/env_<what>" for each "envmap/importance_<what>" above (venice when present): the same
///   map and pdf, samples drawn by simd::SampleEnvironmentBatch;
/// - "distantdisk/{cone_10deg_rotated,cone_90deg,full_sphere}";
/// - "distribution/{1d,2d}": Distribution1D (x; y uniform) and Distribution2D on the unit square,
///   random weights with zero bins and rows;
/// - "broken/envmap_pdf_half_pixel_shift" (the pdf read half a cell off in u: mass 1 but wrong),
///   "broken/simd_env_pdf_half_pixel_shift" (the same, drawn by the SIMD batch)
///   and "broken/distantdisk_pdf_cos_weighted" (cosine-weighted claim for uniform samples).
/// The black map has no subject (it never samples: the lab needs mass); unit tests cover it.
void RegisterLightSubjects(Chi2Registry* registry, const std::string& data_dir);
void RegisterLightSubjects(Chi2Registry* registry);

}  // namespace ptlab
