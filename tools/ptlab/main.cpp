// ptlab command line: `ptlab render scene.xml`, converge, test and envmap-pdf.
#include <csignal>
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

#include "engine/image/image_io.h"
#include "engine/io/text_parsing.h"
#include "engine/light/environment_map.h"
#include "simd/dispatched_target.h"
#include "simd/target_select.h"
#include "tools/chi2/nori_tests.h"
#include "tools/common/exit_codes.h"
#include "tools/common/output_guard.h"
#include "tools/mpi/mpi_session.h"
#include "tools/ptlab/command_line.h"
#include "tools/ptlab/converge_command.h"
#include "tools/ptlab/interrupts.h"
#include "tools/ptlab/render_command.h"
#include "tools/ptlab/test_over_ranks.h"

int main(int argc, char** argv) {
  const ptlab::mpi::Session mpi(&argc, &argv);
  // PTLAB_TARGET=AVX2 (say) pins the SIMD kernels to that Highway target.
  if (const ptlab::Status st = ptlab::simd::SelectTargetFromEnvironment(); !st.ok()) {
    if (mpi.root()) std::fprintf(stderr, "error: %s\n", st.message().c_str());
    return ptlab::kExitUsage;
  }
  ptlab::CommandLine cl;
  CLI::App& app = cl.app;
  ptlab::DefineCommandLine(&cl, std::string("ptlab 0.1 (traversal: Highway ") +
                                    ptlab::simd::DispatchedTargetName() + ")");
  const ptlab::RenderArgs& render = cl.render;
  CLI::App* cmd = cl.render_cmd;
  CLI::App* converge_cmd = cl.converge_cmd;
  CLI::App* test_cmd = cl.test_cmd;
  CLI::App* envmap_cmd = cl.envmap_cmd;
  const std::string& test_file = cl.test_file;
  const bool test_verbose = cl.test_verbose;
  const std::string& envmap_in = cl.envmap_in;
  const std::string& envmap_out = cl.envmap_out;
  const ptlab::ConvergeArgs& converge = cl.converge;

  bool known = false;
  for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    known = known || (argc > 1 && sub->get_name() == argv[1]);
  if (argc > 1 && argv[1][0] != '-' && !known) {
    std::fprintf(stderr, "error: unknown command '%s'; expected one of: render, converge, test, envmap-pdf (see --help)\n",
                 argv[1]);
    return ptlab::kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? ptlab::kExitOk : ptlab::kExitUsage;  // help, version; bad usage
  }
  if (cmd->parsed()) return ptlab::RunRender(render, mpi);
  if (converge_cmd->parsed()) {
    std::signal(SIGINT, ptlab::OnInterrupt);
    std::signal(SIGTERM, ptlab::OnInterrupt);
    return ptlab::RunConverge(converge, &ptlab::g_interrupted);
  }
  if (test_cmd->parsed())
    return mpi.active() ? ptlab::RunNoriTestOverRanks(test_file, test_verbose, mpi)
                        : ptlab::RunNoriTestCommand(test_file, test_verbose);
  if (envmap_cmd->parsed()) {
    ptlab::OutputGuard guard;
    guard.AddInput(envmap_in, "map");
    guard.AddOutput(envmap_out, "-o");
    std::string error;
    if (const int code = guard.Check(&error); code != 0) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return code;
    }
    const ptlab::StatusOr<ptlab::Image> pdf =
        ptlab::EnvironmentPdfImage(envmap_in, ptlab::LowercaseExtension(envmap_out) == ".png");
    if (!pdf.ok()) {  // the map cannot be read or used: bad input
      std::fprintf(stderr, "error: %s\n", pdf.status().message().c_str());
      return ptlab::kExitUsage;
    }
    const ptlab::Status st = ptlab::WriteImage(envmap_out, *pdf);
    if (!st.ok()) {
      std::fprintf(stderr, "error: %s\n", st.message().c_str());
      return ptlab::kExitRunFailed;
    }
    std::printf("wrote %s\n", envmap_out.c_str());
    return ptlab::kExitOk;
  }
  return ptlab::kExitOk;
}
