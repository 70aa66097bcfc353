// `ptlab test FILE.xml` under mpirun: the file's cases shared among ranks, printed by rank 0.
#pragma once

#include <string>

#include "tools/mpi/mpi_session.h"

namespace ptlab {

/// As RunNoriTestCommand, with case i run by rank i % ranks; rank 0 prints the same lines in
/// the same order (every case has its own random streams, so verdicts and p-values are those
/// of one process) and returns the run's exit status; the other ranks return 0.
int RunNoriTestOverRanks(const std::string& path, bool verbose, const mpi::Session& mpi);

}  // namespace ptlab
