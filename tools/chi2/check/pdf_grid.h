// A pdf tabulated on a grid of the domain's parameter rectangle, interpolated bilinearly.
#pragma once

#include <string>

#include "ptlab/chi2.h"

namespace ptlab {

/// Reads a tabulated pdf for `chi2 check --pdf-grid`. Text: '#' lines are comments; the first
/// line is "NX NY" (each >= 2); then NY rows of NX densities (spaces or commas). Row j, column
/// i is the density at the grid node (x0 + i (x1 − x0)/(NX − 1), y0 + j (y1 − y0)/(NY − 1)) of
/// the parameter rectangle: the box itself; [−1, 1]² for the disk; (φ, cos θ) in
/// [0, 2π] × [−1, 1] on the sphere and [0, 2π] × [0, 1] on the hemisphere. Between nodes the
/// pdf is bilinear, so it is off a smooth true pdf by at most (hx² max|∂²p/∂x²| +
/// hy² max|∂²p/∂y²|) / 8 for node spacings hx, hy. Errors name the file, the line and what
/// was expected (negative or non-finite densities included).
chi2::Status ReadPdfGrid(const std::string& path, const chi2::Domain& domain, chi2::PdfFn* pdf);

}  // namespace ptlab
