// ptlab's command line: the subcommands, their options and checks (CLI11), apart from what
// runs them, so tests/fuzz/fuzz_cli.cpp parses exactly what `ptlab` parses.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "tools/ptlab/converge_command.h"

namespace ptlab {

struct RenderArgs {
  std::string scene;
  std::string output;
  int spp = 0, threads = 0, width = 0, height = 0;
  // CS184 pathtracer flags (0 / negative / empty: not given, the scene's value stays).
  int light_samples = 0, max_depth = -2;
  std::string envmap;
  float lens_radius = -1, focal_distance = -1;
  std::vector<int> resolution;        // -r W H
  std::string camera_file;            // -c FILE (CS184 camera settings)
  std::string image;                  // -f out.png (or .exr)
  std::vector<std::string> adaptive;  // -a batch tolerance
  uint64_t seed = 0;
  bool quiet = false;
  std::string lookat = "nori";
  bool scalar = false;
  bool stats = false;
  std::string tile_times;
  bool moments = false;  // --moments: NAME_var.exr beside NAME.exr
  std::string sampler;  // empty: the scene's
  std::string integrator;  // --integrator NAME; empty: the scene's
  std::string strategies;  // --strategies DIR: bdpt's per-(s, t) images (docs/bdpt.md)
  double max_memory_gib = 0;  // --max-memory; 0: the default (engine/core/memory_budget.h)
  std::vector<std::string> defines;  // -D name=value (Mitsuba scene parameters)
};

/// Every option of every subcommand, filled by CLI::App::parse.
struct CommandLine {
  CLI::App app{"ptlab: a CPU path tracer and rendering test lab"};
  RenderArgs render;
  std::string test_file;
  bool test_verbose = false;
  std::string envmap_in, envmap_out;
  ConvergeArgs converge;
  CLI::App* render_cmd = nullptr;
  CLI::App* test_cmd = nullptr;
  CLI::App* envmap_cmd = nullptr;
  CLI::App* converge_cmd = nullptr;
};

/// Registers the subcommands render, test, envmap-pdf and converge on cl->app; `version` is
/// what --version prints.
void DefineCommandLine(CommandLine* cl, const std::string& version);

}  // namespace ptlab
