// `ptlab render scene.xml`: loads the scene, applies the command line, renders and writes.
#pragma once

#include "tools/mpi/mpi_session.h"
#include "tools/ptlab/command_line.h"

namespace ptlab {

/// Runs the render command; its exit code (tools/common/exit_codes.h): 2 for bad input or
/// usage, and the output errors, interrupts and failures of the render.
int RunRender(const RenderArgs& args, const mpi::Session& mpi);

}  // namespace ptlab
