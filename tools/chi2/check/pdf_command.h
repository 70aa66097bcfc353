// A pdf answered by another program: points to its stdin, densities from its stdout.
#pragma once

#include <string>

#include "ptlab/chi2.h"

namespace ptlab {

/// A pdf that runs `command` with /bin/sh -c once per batch of points. Protocol: ptlab writes
/// one point per line, its dims() coordinates separated by spaces ("x y" on planar domains,
/// "x y z" on spherical ones; 17 significant digits, so a double parses the float exactly),
/// then closes the program's stdin; the program prints one density per line (any whitespace
/// between numbers is accepted) and exits with status 0. Errors name the command: it could not
/// start, exited non-zero or by a signal, printed something that is not a number, printed too
/// few or too many densities, or did not finish within timeout_seconds of the batch's start
/// (its process group is then killed).
chi2::PdfFn PdfCommand(const std::string& command, const chi2::Domain& domain,
                       double timeout_seconds);

}  // namespace ptlab
