// `ptlab converge`: error against time of rendering strategies (variants) on scenes.
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace ptlab {

struct ConvergeArgs {
  std::vector<std::string> scenes;
  std::vector<std::string> refs;      // one per scene, or the single word "auto"
  std::vector<std::string> variants;  // specs (see tools/converge/variant.h); none: the scene
  int spp = 0;                        // per run (default: the scene's sampleCount)
  double time = 0;                    // > 0: per run, instead of spp
  int threads = 0;
  int seeds = 1;
  uint64_t seed = 1;  // first seed; runs use seed, seed + 1, ...
  std::string out_dir;
  std::string lookat = "nori";  // or nori2015 (the eth2015 references' camera frame)
  int width = 0;                // > 0: image width (height keeps the aspect); with --ref auto
  bool no_plots = false;
  std::vector<std::string> defines;  // -D name=value (Mitsuba scene parameters)
};

/// Registers the `converge` subcommand on app, filling *args (in command_line.cpp).
CLI::App* AddConvergeCommand(CLI::App* app, ConvergeArgs* args);

/// Runs it. Exit status: 0 done, 1 a render or an output failed, 2 bad arguments or inputs
/// (unknown variant key, unreadable reference, reference of another size or with NaN/Inf),
/// 130 interrupted (what was measured so far is written).
int RunConverge(const ConvergeArgs& args, const std::atomic<bool>* interrupted);

}  // namespace ptlab
