// Environment map emitter (Mitsuba `envmap`): lat-long radiance, uniform or importance sampling.
#pragma once

#include <cstdint>
#include <string>

#include "engine/core/frame.h"
#include "engine/core/status.h"
#include "engine/core/vec.h"
#include "engine/image/image.h"
#include "engine/light/environment_sample.h"
#include "engine/sampling/distribution2d.h"
#include "engine/scene/emitter_tables.h"

namespace ptlab {

// Lat-long convention (Mitsuba's envmap: φ origin and direction, row 0 = up).
// In the map's local frame, +y is up. A local unit direction d = (x, y, z) has
//   θ = angle(d, +y) ∈ [0, π],  φ = atan2(x, -z) ∈ [0, 2π)  (φ = 0 towards -z, π/2 towards +x),
//   u = φ / 2π (along the columns, left to right),  v = θ / π (along the rows, top to bottom),
// so d = (sinθ sinφ, cosθ, -sinθ cosφ). toWorld (a rotation) maps local to world directions.
// Pixel column i sits at u = (i + ½)/W. Pixel row j sits, by the row's EnvironmentRows, at
// v = (j + ½)/H (kCentred: pixel (i, j) covers u ∈ [i/W, (i+1)/W), v ∈ [j/H, (j+1)/H) with its
// value at the centre) or at v = j/(H − 1) (kAtPoles, Mitsuba 3: rows 0 and H − 1 on the poles).
// Radiance is the bilinear interpolation of the pixel values at those points (wrapping in u,
// clamped in v), times `scale`. The importance distribution is piecewise constant over cells:
// W columns u ∈ [i/W, (i+1)/W) by nv = EnvironmentCellRows rows v ∈ [j/nv, (j+1)/nv) (kCentred:
// the pixels; kAtPoles: the bands between two pixel rows), with weight = (mean over the cell of
// the bilinear luminance) × sinθ(cell centre). The mean is a stencil of pixel luminances with
// all weights > 0 over the pixels the cell's interpolant reads ((1/8, 3/4, 1/8) in u; in v the
// same for kCentred, (½, ½) of rows j, j + 1 for kAtPoles), so every cell where the bilinear
// radiance is non-zero has non-zero probability, and light sampling alone stays unbiased.
// The solid-angle pdf is exactly that of the sampled (u, v):
//   pdf(ω) = p(u, v) / (2π² sinθ),  p(u, v) = W·nv · P(cell)  (density on the unit square).

/// 2π²: the Jacobian of (u, v) -> ω divided by sinθ.
inline constexpr float kEnvironmentTwoPiSquared = 19.739208802178716f;

/// The per-emitter parameters of an environment map.
struct EnvironmentMapDesc {
  float scale = 1.0f;  // finite, >= 0; multiplies every pixel
  Frame to_world;      // a rotation (orthonormal axes); translation has no meaning here
  EnvironmentSampling sampling = EnvironmentSampling::kImportance;
  EnvironmentRows rows = EnvironmentRows::kCentred;  // kAtPoles for Mitsuba scenes
};

/// Appends `image` as a new environment-map row of `table` and returns the row.
/// Pixel policy: every channel of every pixel must be finite and >= 0 (-0 counts as 0); a NaN,
/// ±Inf or negative value is an error that names `name` (the file), the first bad pixel (x, y),
/// channel and value, and how many pixels are bad. Nothing is clamped, nothing is appended on
/// error. Also errors: an empty image, a scale that is negative or not finite, and pixel × scale
/// overflowing to Inf. An all-black map is allowed: it emits nothing, is never sampled
/// (Sample returns false) and has Pdf 0 everywhere, for both sampling strategies.
StatusOr<uint32_t> AddEnvironmentMap(const Image& image, const EnvironmentMapDesc& desc,
                                     const std::string& name, EnvironmentMapTable* table);

/// (u, v) ∈ [0,1]² of a local direction (need not be unit length; not zero).
Vec2f EnvironmentDirectionToUv(const Vec3f& d_local);
/// The unit local direction at (u, v) ∈ [0,1]².
Vec3f EnvironmentUvToDirection(const Vec2f& uv);

/// Rows of the importance distribution's cells: height for kCentred rows, max(height − 1, 1)
/// for kAtPoles rows.
int EnvironmentCellRows(const EnvironmentMapTable& table, uint32_t row);

/// The pixel-row coordinate of v for row `row` is v · *scale + *offset (kCentred: H, −½;
/// kAtPoles: H − 1, 0); the lookup (and its SIMD twin) interpolates rows ⌊y⌋ and ⌊y⌋ + 1.
void EnvironmentRowCoordinate(const EnvironmentMapTable& table, uint32_t row, float* scale,
                              float* offset);

/// The importance distribution of row `row` (meaningful only for kImportance rows).
Distribution2DView EnvironmentDistribution(const EnvironmentMapTable& table, uint32_t row);

/// Radiance arriving from world direction w (unit, pointing away from the scene): the
/// bilinearly interpolated, scaled map value. What an escaping ray sees.
Color3f EnvironmentRadiance(const EnvironmentMapTable& table, uint32_t row, const Vec3f& w_world);

/// EnvironmentRadiance (into *radiance) and EnvironmentPdf of one direction, bit for bit, with
/// the direction mapped to (u, v) once for both: what MIS weighs an escaping ray with.
float EnvironmentRadianceAndPdf(const EnvironmentMapTable& table, uint32_t row,
                                const Vec3f& w_world, Color3f* radiance);

/// Samples a world direction with the row's strategy. Returns false (out untouched) only for a
/// black map. A sample never lies exactly on a pole (its pdf is always finite and > 0).
bool SampleEnvironment(const EnvironmentMapTable& table, uint32_t row, const Vec2f& u,
                       EnvironmentSample* out);

/// Solid-angle density with which SampleEnvironment produces world direction w (unit): 1/(4π)
/// for uniform rows, p(u, v)/(2π² sinθ) for importance rows, 0 at the exact poles and for a
/// black map.
float EnvironmentPdf(const EnvironmentMapTable& table, uint32_t row, const Vec3f& w_world);

/// The CS184-style probability debug image of an importance row, W × H, values in [0, 1]:
/// R = marginal CDF up to and including the pixel's row, G = conditional CDF up to and including
/// the pixel within its row (CS184's probability_debug.png), B = the pixel's probability divided
/// by the largest pixel probability (the pdf per pixel, normalised for display). All zero for a
/// black map.
Image EnvironmentPdfDebugImage(const EnvironmentMapTable& table, uint32_t row);

/// `ptlab envmap-pdf`: reads the map at map_path (EXR, HDR, ...; pixel policy as in
/// AddEnvironmentMap), builds its importance distribution and returns EnvironmentPdfDebugImage.
/// `for_png`: the values are pre-curved so a PNG stores each channel byte as round(255 · value)
/// (no sRGB curve, as CS184 writes it); otherwise (.exr, .pfm) they are as they are.
StatusOr<Image> EnvironmentPdfImage(const std::string& map_path, bool for_png);

}  // namespace ptlab
