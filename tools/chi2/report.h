// Chi-square lab reports: observed / expected / difference heat maps and the per-cell table.
#pragma once

#include <string>

#include "engine/core/status.h"
#include "engine/image/image.h"
#include "tools/chi2/chi2.h"

namespace ptlab {

/// Three panels side by side on a dark background, y (cosθ) growing upwards: observed counts
/// and expected counts (one shared viridis scale from 0 to the larger maximum), then the signed
/// difference as the Pearson residual (o - e) / sqrt(e): white 0, blue < 0 < red, full colour at
/// ±4 (so the noise of a passing test stays pale); cells with samples but zero expected mass
/// are magenta. Linear RGB (for WritePng).
Image Chi2Heatmaps(const Chi2Result& result);

/// File-name stem of a test: its name with every character outside [A-Za-z0-9._-] as '_'.
std::string Chi2FileStem(const std::string& name);

/// Writes <dir>/<stem>.png (Chi2Heatmaps) and <dir>/<stem>.csv (ix, iy, cell bounds in the
/// parameter rectangle, observed, expected), creating dir if needed. Both files are atomic.
Status WriteChi2Report(const std::string& dir, const Chi2Result& result);

}  // namespace ptlab
