// Zoomed equal-area map of the sphere onto the unit disk around a lobe's axis (a χ² domain).
#pragma once

#include "engine/core/vec.h"
#include "tools/chi2/chi2.h"

namespace ptlab {

/// Re-parametrises unit directions on Chi2Domain::Disk() so that a narrow lobe around `axis`
/// spreads over many histogram cells. The (φ, cosθ) grid of Chi2Domain::Sphere() cannot
/// resolve a lobe narrower than a cell (at the default 51 rows a lobe at the pole with
/// 1 − cosθ < 0.04, i.e. θ < 16°, falls in one row), and float cosθ near 1 cannot even
/// represent angles below ~3e-4 rad; the disk coordinates below keep full precision there.
///
/// Two steps, in double: Lambert's azimuthal equal-area projection around the axis (radius
/// ρ = 2 sin(γ/2) ∈ [0, 2] for the angle γ to the axis; area = solid angle), then the radial
/// zoom r = c ρ / (ρ + k), c = (2 + k)/2, which sends ρ = k (γ ≈ k) to r = c/2 ≈ 1/2 and the
/// antipode (ρ = 2) to the rim r = 1. The whole sphere maps onto the disk (one-to-one except
/// at the antipode), so no sample falls outside; a lobe's tail is compressed towards the rim.
/// Density on the disk: p_A = p_ω dω/dA, dω/dA = ρ dρ / (r dr) = (ρ + k)³ / (c² k): smooth,
/// (k/c)² at the centre. Precision: the lab's points are float, and near the rim one float step
/// of r is dρ = 2⁻²⁴ (ρ + k)² / (c k) (up to 6e-4 rad for k = 1e-4), so a wide part of the
/// distribution far from the axis is integrated as a fine staircase — still consistent with
/// the binning, but it costs the Simpson integration effort; pure lobes are 0 there.
class LobeDisk {
 public:
  /// axis: the lobe's centre direction (normalised here); k > 0: the angle to the axis, in
  /// radians, that lands at r ≈ 1/2 (about the lobe's width).
  LobeDisk(const Vec3f& axis, double k);

  /// Disk point (x, y, 0), |(x, y)| <= 1, of a unit direction.
  Chi2Point ToDisk(const Vec3f& w) const;
  /// Unit direction at disk point p (|p| <= 1) and dω/dA there (*domega_da may not be null).
  Vec3f FromDisk(const Chi2Point& p, double* domega_da) const;

  double k() const { return k_; }

 private:
  double axis_[3], s_[3], t_[3];  // orthonormal frame, axis_ = local z
  double k_, c_;
};

/// The same subject on Chi2Domain::Disk() through `zoom`: its samples are mapped by ToDisk and
/// its pdf becomes pdf(FromDisk(p)) dω/dA. subject.domain must be spherical; a sample outside
/// it (not unit, or below a hemisphere's horizon) is reported at (2, 2), outside the disk, so
/// the lab still rejects it; non-finite samples stay non-finite. Appends "zoom k=..." to params.
Chi2Subject OnLobeDisk(Chi2Subject subject, const LobeDisk& zoom);

/// Relative level below which FlushLobeTail zeroes a lobe's pdf: 1e-12 of its peak.
inline constexpr double kChi2LobeTailFloor = 1e-12;

/// The pdf with values in [0, kChi2LobeTailFloor × peak) set to 0 (negative and NaN values pass
/// through, for the lab to report). Why: in a lobe's far tail the float pdf is exp of a large
/// rounded argument, then denormal, then 0, with relative noise far above the adaptive
/// Simpson's per-interval tolerance, which then refines every cell the tail crosses (~170 on a
/// LobeDisk) to the evaluation budget: 3–18 s per subject instead of 0.2–1 s. Zero is exact
/// for it. Why it is harmless: a Beckmann lobe falls off as exp(−tan²θh/α²) times slowly
/// varying factors (cosθo / (wo·h) ≥ 1.7e-3 for reflection up to θo = 89.9°), so the zeroed
/// region lies beyond tan²θh/α² ≈ 21–28 and holds at most ~1e-9 of the mass, and the samplers
/// (u ≤ 1 − 2⁻²⁴) never go beyond tan²θh/α² = 16.6. A sampler that does put samples there is
/// rejected (samples in cells of zero expected mass): the flush makes the test stricter, never
/// looser. Only for pure lobes: a mixture with a diffuse part would lose that part where it is
/// small (near the horizon).
Chi2PdfFn FlushLobeTail(Chi2PdfFn pdf, double peak);

}  // namespace ptlab
