// Integration of a chi-square subject's pdf over the cells of its grid: adaptive Simpson per
// cell, one point at a time or with a batch pdf (tools/chi2/chi2_integration.cpp).
#pragma once

#include "tools/chi2/chi2.h"

namespace ptlab::chi2_internal {

/// A batch-pdf replay pass (defined in chi2_integration.cpp).
struct ReplayPass;

// Integrates `pdf` over every cell into r->expected (samples x probability) and returns the
// integral over the domain. `replay` is null, or a batch replay pass: then cells whose integral
// needs points not evaluated yet come out NaN.
double IntegrateCells(const Chi2Subject& subject, const Chi2PdfFn& pdf, const Chi2Options& options,
                      Chi2Result* r, ReplayPass* replay);

// The adaptive integration with a batch pdf: each pass runs IntegrateCells on the values known
// so far (an unknown point is collected and reads NaN, which ends the refinement that depends on
// it), then evaluates the collected points in one batch call; cells that needed no new point are
// skipped from then on. Once no cell needs one, a last pass over every cell is exactly the
// one-point-at-a-time run. Batch calls ~ outer x inner refinement depth.
double IntegrateWithBatchPdf(const Chi2Subject& subject, const Chi2Options& options,
                             Chi2Result* r);

}  // namespace ptlab::chi2_internal
