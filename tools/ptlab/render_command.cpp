// `ptlab render scene.xml`: the scene and command-line setup, the render, its outputs.
#include "tools/ptlab/render_command.h"

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <memory>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "engine/bvh/bvh.h"
#include "engine/core/memory.h"
#include "engine/core/memory_budget.h"
#include "engine/image/image_io.h"
#include "engine/light/environment_map.h"
#include "engine/light/light_selection.h"
#include "engine/render/bdpt.h"
#include "engine/render/integrator.h"
#include "engine/render/camera.h"
#include "engine/render/render.h"
#include "engine/render/render_memory.h"
#include "engine/render/setup_checks.h"
#include "engine/wavefront/wavefront.h"
#include "engine/io/text_parsing.h"
#include "engine/scene/scene_bytes.h"
#include "engine/scene/scene_limits.h"
#include "engine/io/cs184_camera_file.h"
#include "engine/io/scene_file.h"
#include "engine/io/xml_loader.h"
#include "simd/bvh8.h"
#include "simd/dispatched_target.h"
#include "simd/traverse8.h"
#include "simd/render_setup.h"
#include "engine/render/bdpt.h"
#include "engine/render/bdpt_strategies.h"
#include "tools/chi2/nori_tests.h"
#include "tools/converge/pass_variance.h"
#include "tools/common/exit_codes.h"
#include "tools/common/output_guard.h"
#include "tools/mpi/mpi_render.h"
#include "tools/mpi/mpi_session.h"
#include "tools/ptlab/command_line.h"
#include "tools/ptlab/converge_command.h"
#include "tools/ptlab/effective_options.h"
#include "tools/ptlab/interrupts.h"
#include "tools/ptlab/render_output.h"
#include "tools/ptlab/test_over_ranks.h"

namespace ptlab {
namespace {

// Cores this process may run on (its affinity mask: mpirun binds each rank to its cores).
int UsableCores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1, int(std::thread::hardware_concurrency()));
}

// The CS184 flags that change the scene: -l, -m, -b, -d and -e (an environment-map light,
// added to whatever the scene has; world +y is its zenith).
Status ApplySceneFlags(const RenderArgs& args, Scene* scene) {
  if (args.light_samples > 0) scene->integrator.light_samples = args.light_samples;
  if (args.max_depth >= -1) scene->integrator.max_depth = args.max_depth;
  if (args.lens_radius >= 0) scene->camera.aperture_radius = args.lens_radius;
  if (args.focal_distance > 0) scene->camera.focus_distance = args.focal_distance;
  if (!args.envmap.empty()) {
    StatusOr<Image> image = ReadImage(args.envmap);
    if (!image.ok()) return Status::Error("-e: " + image.status().message());
    StatusOr<uint32_t> row =
        AddEnvironmentMap(*image, EnvironmentMapDesc{}, args.envmap, &scene->environment_maps);
    if (!row.ok()) return Status::Error("-e: " + row.status().message());
    scene->emitters.push_back(EmitterRef::Make(EmitterTag::kEnvironment, *row));
    BuildEmitterSelection(scene);  // the new emitter joins the power-based selection
    scene->input_files.push_back(args.envmap);
  }
  return Status::Ok();
}

// -a batch tolerance: samples per batch (an integer >= 1) and a tolerance (a finite number > 0).
Status ParseAdaptiveFlag(const std::vector<std::string>& values, AdaptiveSampling* adaptive) {
  int batch = 0;
  std::string error = ParseNumber<int>(values[0], 1, 1 << 20, &batch);
  if (!error.empty()) return Status::Error("-a: batch " + error);
  float tolerance = 0;
  error = ParseNumber<float>(values[1], FLT_MIN, FLT_MAX, &tolerance);
  if (!error.empty()) return Status::Error("-a: tolerance " + error);
  adaptive->batch = uint32_t(batch);
  adaptive->tolerance = tolerance;
  return Status::Ok();
}

// Every file `render` writes, against every file it reads (the scene's input_files, which hold
// the scene, its meshes and maps, -c and -e).
OutputGuard RenderOutputGuard(const RenderArgs& args, const std::vector<std::string>& inputs,
                              const std::string& exr, const std::string& png,
                              const std::string& var_exr, const std::string& tile_times) {
  OutputGuard guard;
  for (size_t i = 0; i < inputs.size(); ++i)
    guard.AddInput(inputs[i], i == 0                          ? "scene"
                              : inputs[i] == args.camera_file ? "-c camera file"
                              : inputs[i] == args.envmap      ? "-e map"
                                                              : "a file the scene reads");
  guard.AddOutput(exr, "EXR output");
  guard.AddOutput(png, "PNG output");
  guard.AddOutput(var_exr, "--moments variance output");
  guard.AddOutput(tile_times, "--tile-times");
  // --strategies DIR: every name WriteStrategyImages may write, so none of them replaces an
  // input or another output.
  if (!args.strategies.empty())
    for (const std::string& path : StrategyOutputPaths(args.strategies))
      guard.AddOutput(path, "--strategies image");
  return guard;
}

}  // namespace

int RunRender(const RenderArgs& args, const mpi::Session& mpi) {
  const auto load_start = std::chrono::steady_clock::now();
  if (args.max_memory_gib > 0) SetMemoryBudgetBytes(uint64_t(args.max_memory_gib * double(1 << 30)));
  LoadOptions load_options;
  if (args.lookat == "nori2015") load_options.lookat = LookatConvention::kNori2015;
  load_options.defines = args.defines;
  StatusOr<Scene> loaded = LoadSceneFile(args.scene, load_options);
  // Under mpirun every rank loads the scene; all stop if one cannot, or reads other bytes.
  Status agreed = mpi.Agree(loaded.status());
  if (agreed.ok()) agreed = mpi.CheckSameInputs(loaded->input_files);
  if (!agreed.ok()) {  // bad input: exit 2
    if (mpi.root()) std::fprintf(stderr, "error: %s\n", agreed.message().c_str());
    return kExitUsage;
  }
  Scene& scene = *loaded;
  if (mpi.root())
    for (const std::string& warning : scene.load_warnings)
      std::fprintf(stderr, "warning: %s\n", warning.c_str());
  const std::string unsupported = UnsupportedFeature(scene);
  if (!unsupported.empty()) {
    std::fprintf(stderr, "error: %s: %s\n", args.scene.c_str(), unsupported.c_str());
    return kExitUsage;
  }
  if (!args.sampler.empty()) SamplerTypeFromName(args.sampler, &scene.sampler.type);
  if (!args.integrator.empty()) {
    // The scene's other integrator settings (maxDepth, light selection, ...) stay; bdpt takes
    // its default, the power heuristic (docs/bdpt.md).
    IntegratorTypeFromName(args.integrator, &scene.integrator.type);
    if (scene.integrator.type == IntegratorDesc::Type::kBdpt)
      scene.integrator.power_heuristic = true;
  }
  if (IsBidirectional(scene.integrator.type) &&
      (!args.adaptive.empty() || args.moments || mpi.active())) {
    if (mpi.root())
      std::fprintf(stderr, "error: %s does not run with -a, --moments or under mpirun yet\n",
                   IntegratorTypeName(scene.integrator.type));
    return kExitUsage;
  }
  if (!args.resolution.empty()) {
    const std::string size = FilmSizeError(args.resolution[0], args.resolution[1]);
    if (!size.empty()) {
      std::fprintf(stderr, "error: -r: %s\n", size.c_str());
      return kExitUsage;
    }
    ResizeFilm(&scene.camera, args.resolution[0], args.resolution[1]);
  }
  if (args.width > 0 || args.height > 0) {
    const double aspect = double(scene.camera.width) / double(scene.camera.height);
    const double width = args.width > 0 ? args.width : std::round(args.height * aspect);
    const double height = args.height > 0 ? args.height : std::round(args.width / aspect);
    const std::string size = FilmSizeError(int64_t(std::min(width, 1e15)),
                                           int64_t(std::min(height, 1e15)));
    if (!size.empty()) {
      std::fprintf(stderr, "error: --width/--height: %s\n", size.c_str());
      return kExitUsage;
    }
    ResizeFilm(&scene.camera, int(width), int(height));
  }
  if (!args.camera_file.empty()) {
    // After the film size (the horizontal field follows it), before -b/-d (which win).
    const Status camera = ReadCs184CameraFile(args.camera_file, &scene.camera);
    if (!camera.ok()) {
      if (mpi.root()) std::fprintf(stderr, "error: -c: %s\n", camera.message().c_str());
      return kExitUsage;
    }
    scene.input_files.push_back(args.camera_file);
  }
  const Status overridden = ApplySceneFlags(args, &scene);
  if (!overridden.ok()) {  // e.g. an -e map that cannot be read
    if (mpi.root()) std::fprintf(stderr, "error: %s\n", overridden.message().c_str());
    return kExitUsage;
  }
  if (!args.strategies.empty() && !IsBidirectional(scene.integrator.type)) {
    if (mpi.root())
      std::fprintf(stderr, "error: --strategies: the integrator is %s; expected bdpt or ptracer "
                           "(--integrator bdpt)\n",
                   IntegratorTypeName(scene.integrator.type));
    return kExitUsage;
  }
  // A camera, lens or light that makes a degenerate image is an error, not a black image.
  if (const Status sane = CheckRenderSetup(scene); !sane.ok()) {
    if (mpi.root()) std::fprintf(stderr, "error: %s: %s\n", args.scene.c_str(), sane.message().c_str());
    return kExitUsage;
  }
  AdaptiveSampling adaptive;
  if (!args.adaptive.empty()) {
    const Status parsed = ParseAdaptiveFlag(args.adaptive, &adaptive);
    if (!parsed.ok()) {
      if (mpi.root()) std::fprintf(stderr, "error: %s\n", parsed.message().c_str());
      return kExitUsage;
    }
    if (mpi.active()) {
      if (mpi.root())
        std::fprintf(stderr, "error: -a (adaptive sampling) does not run under mpirun yet\n");
      return kExitUsage;
    }
  }
  // -f names the PNG (the EXR goes beside it) or the EXR; -o names the EXR.
  std::string out = args.output;
  std::string png;
  const bool image_is_png = std::filesystem::path(args.image).extension() == ".png";
  if (!args.image.empty()) {
    out = image_is_png ? std::filesystem::path(args.image).replace_extension(".exr").string()
                       : args.image;
    if (image_is_png) png = args.image;
  }
  if (out.empty()) out = std::filesystem::path(args.scene).stem().string() + ".exr";
  if (png.empty()) png = std::filesystem::path(out).replace_extension(".png").string();
  const std::filesystem::path out_path(out);
  Status output_ok;  // checked where the image is written: by rank 0 under mpirun
  int output_code = kExitUsage;  // a bad name (or one that names an input): bad usage
  if (!mpi.root()) {
  } else if (!args.image.empty() && !image_is_png && out_path.extension() != ".exr") {
    output_ok = Status::Error("-f: output '" + args.image +
                              "' must end in .png (the .exr is written beside it) or .exr");
  } else if (out_path.extension() != ".exr") {
    output_ok = Status::Error("output '" + out + "' must end in .exr (a .png is written beside it)");
  } else if (std::error_code ec; out_path.has_parent_path() &&
             !std::filesystem::is_directory(out_path.parent_path(), ec) &&
             ec != std::errc::filename_too_long) {  // the output guard names a long path
    output_ok = Status::Error("output directory '" + out_path.parent_path().string() +
                              "' does not exist");
    output_code = kExitRunFailed;
  }
  // --moments: NAME_var.exr beside NAME.exr, from two passes on.
  const std::string var_out =
      args.moments ? (out_path.parent_path() / (out_path.stem().string() + "_var.exr")).string()
                   : "";
  if (args.moments && (!args.adaptive.empty() || mpi.active())) {
    if (mpi.root()) std::fprintf(stderr, "error: --moments does not run with -a or under mpirun\n");
    return kExitUsage;
  }
  if (output_ok.ok() && mpi.root() && !args.strategies.empty()) {
    // The --strategies folder is created and probed before the render (a file of that name,
    // or an unwritable folder, failed only after the render and its images were written).
    std::string error;
    output_code = PrepareOutputFolder(args.strategies, &error);
    if (output_code != 0) output_ok = Status::Error("--strategies: " + error);
  }
  if (output_ok.ok() && mpi.root()) {
    std::string error;
    output_code =
        RenderOutputGuard(args, scene.input_files, out, png, var_out, args.tile_times)
            .Check(&error);
    if (output_code != 0) output_ok = Status::Error(error);
  }
  output_ok = mpi.Agree(output_ok);
  if (!output_ok.ok()) {
    if (mpi.root()) std::fprintf(stderr, "error: %s\n", output_ok.message().c_str());
    return output_code;
  }

  const int cores = std::max(1, int(std::thread::hardware_concurrency()));
  if (!mpi.active() && args.threads > cores)
    std::fprintf(stderr, "warning: --threads %d is more than the %d cores of this machine\n",
                 args.threads, cores);
  RenderOptions options;
  options.spp = args.spp > 0 ? uint32_t(args.spp) : scene.sampler.sample_count;
  options.threads = args.threads > 0 ? args.threads : UsableCores();
  options.time_stages = args.stats;
  if (mpi.root() && mpi.active() && options.threads > UsableCores())
    std::fprintf(stderr,
                 "warning: %d threads per rank, but mpirun bound rank 0 to %d core(s); start it "
                 "with --bind-to none or --map-by slot:PE=%d\n",
                 options.threads, UsableCores(), options.threads);
  options.seed = args.seed;
  options.adaptive = adaptive;
  options.cancel = &g_interrupted;
  ProgressReporter reporter;
  const bool quiet = args.quiet || !mpi.root();
  // What the render will take (film, adaptive moments, wavefronts at -l) against --max-memory.
  if (const std::string over = RenderOverMemoryBudget(
          scene, options, double(scene.triangles.size()) * double(kSceneBytesPerTriangle));
      !over.empty()) {
    if (mpi.root()) std::fprintf(stderr, "error: %s\n", over.c_str());
    return kExitUsage;
  }
  if (mpi.active()) {
    // Every rank renders the same image: the same bytes of every input (the scene's files, -c
    // and -e) and the same effective options, or every rank stops naming the one that differs.
    Status same = mpi.CheckSameInputs(scene.input_files);
    if (same.ok())
      same = mpi.CheckSameOptions(EffectiveRenderOptions(args, scene, options.spp, adaptive,
                                                         !args.scalar && !ForceScalar()));
    if (!same.ok()) {
      if (mpi.root()) std::fprintf(stderr, "error: %s\n", same.message().c_str());
      return kExitUsage;
    }
  }
  std::unique_ptr<mpi::RenderShare> share;
  if (mpi.active()) {
    share = std::make_unique<mpi::RenderShare>(
        mpi, (options.spp + SamplesPerPass(options.spp) - 1) / SamplesPerPass(options.spp));
    options.distribution = &share->distribution();
  }
  if (!quiet) options.on_progress = [&](const RenderProgress& p) { reporter.Update(p); };
  std::unique_ptr<PassVariance> moments;
  if (args.moments) {
    moments = std::make_unique<PassVariance>(scene.camera.width, scene.camera.height);
    options.pass_spp = PassVariance::PassSamples(options.spp);
    options.on_pass = [&](const RenderPass& pass) { moments->AddPass(*pass.blocks); };
  }

  if (mpi.root())
    std::fprintf(stderr, "ptlab: %s  %dx%d  %u spp  %d threads%s  %zu triangles%s\n",
                 args.scene.c_str(), scene.camera.width, scene.camera.height, options.spp,
                 options.threads,
                 mpi.active() ? (" x " + std::to_string(mpi.size()) + " ranks").c_str() : "",
                 scene.triangles.size(),
                 scene.spheres.size() > 0
                     ? ("  " + std::to_string(scene.spheres.size()) + " spheres").c_str()
                     : "");
  const uint64_t peak_loaded = PeakResidentBytes();
  // --stats: the scene's files read (parse, meshes, textures, flags' maps) before the builds.
  const double scene_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();
  const RenderSetup setup(scene, ChooseKernels(args.scalar), options.threads);
  const std::string traversal = setup.TraversalName();
  if (mpi.root()) std::fprintf(stderr, "ptlab: traversal: %s\n",
               setup.packets() ? ("8-wide packets, Highway target " +
                                  std::string(simd::DispatchedTargetName())).c_str()
                               : "scalar oracle kernels (one ray at a time)");
  std::signal(SIGINT, OnInterrupt);
  std::signal(SIGTERM, OnInterrupt);
  const RenderResult result = Render(scene, setup, options);
  BlockInterrupts hold_interrupts;
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  const int interrupted_code = g_signal.load() == SIGTERM ? kExitTerminated : kExitInterrupted;
  if (!result.error.empty()) {
    std::fprintf(stderr, "error: %s\n", result.error.c_str());
    return kExitRunFailed;
  }
  if (!quiet) reporter.Finish();
  if (!mpi.root()) return result.interrupted ? interrupted_code : 0;  // rank 0 writes the film
  if (args.stats) {
    PrintStats(result, options.threads * mpi.size());
    PrintMemory(scene, setup, result, options.threads, peak_loaded);
    std::fprintf(stderr,
                 "stats: load %.3f s: scene files %.3f s (parse, meshes, textures), BVH %.3f s, "
                 "BVH8 and triangle rows %.3f s\n",
                 scene_seconds + setup.bvh_seconds() + setup.bvh8_seconds(), scene_seconds,
                 setup.bvh_seconds(), setup.bvh8_seconds());
  }

  if (result.nonfinite_samples > 0)
    std::fprintf(stderr, "warning: dropped %llu NaN/Inf samples (first at pixel %d,%d)\n",
                 (unsigned long long)result.nonfinite_samples, result.first_nonfinite_x,
                 result.first_nonfinite_y);
  // Pixels that end non-finite in the film (sums that overflowed), beside the dropped samples.
  size_t nonfinite_pixels = 0;
  for (size_t i = 0; i < result.image.rgb.size(); i += 3)
    nonfinite_pixels += !(std::isfinite(result.image.rgb[i]) &&
                          std::isfinite(result.image.rgb[i + 1]) &&
                          std::isfinite(result.image.rgb[i + 2]));
  if (nonfinite_pixels > 0)
    std::fprintf(stderr, "warning: %zu pixels of the image are NaN/Inf\n", nonfinite_pixels);
  const std::vector<std::pair<std::string, std::string>> header = {
      {"ptlab:scene", args.scene},
      {"ptlab:spp", std::to_string(result.spp_done)},
      {"ptlab:spp_requested", std::to_string(options.spp)},
      {"ptlab:seed", std::to_string(args.seed)},
      {"ptlab:sampler", SamplerTypeName(scene.sampler.type)},
      {"ptlab:seconds", std::to_string(result.seconds)},
      {"ptlab:interrupted", result.interrupted ? "true" : "false"},
      {"ptlab:nonfinite_samples", std::to_string(result.nonfinite_samples)},
      {"ptlab:nonfinite_pixels", std::to_string(nonfinite_pixels)},
      {"ptlab:traversal", traversal},
      {"ptlab:threads", std::to_string(options.threads)},
      {"ptlab:ranks", std::to_string(mpi.size())},
      // The estimator and camera settings the CS184 flags can change.
      {"ptlab:integrator", IntegratorTypeName(scene.integrator.type)},
      {"ptlab:max_depth", std::to_string(scene.integrator.max_depth)},
      {"ptlab:light_samples", std::to_string(scene.integrator.light_samples)},
      {"ptlab:lens_radius", std::to_string(scene.camera.aperture_radius)},
      {"ptlab:focal_distance", std::to_string(scene.camera.focus_distance)},
      {"ptlab:environment_maps", std::to_string(scene.environment_maps.size())},
      {"ptlab:adaptive", adaptive.batch > 0 ? std::to_string(adaptive.batch) + " " +
                                                  std::to_string(adaptive.tolerance)
                                            : "off"},
      {"ptlab:samples_taken", std::to_string(result.samples_taken)},
  };
  if (result.spp_done == 0) {
    std::fprintf(stderr, "interrupted before the first pass completed: nothing written\n");
    return interrupted_code;
  }
  Status st = WriteImages(out, png, result.image, header, options.threads);
  if (st.ok() && !args.tile_times.empty()) st = WriteTileTimes(args.tile_times, result);
  if (st.ok() && moments) {
    if (moments->passes() < 2)
      std::fprintf(stderr,
                   "warning: --moments: %u pass(es), no variance estimate (NaN); use more than "
                   "16 spp\n",
                   moments->passes());
    std::vector<std::pair<std::string, std::string>> var_header = header;
    var_header.emplace_back("ptlab:variance",
                            "per-sample variance in XYZ from " + std::to_string(moments->passes()) +
                                " passes (batch means), stored through the XYZ->RGB matrix as "
                                "Mitsuba's _var.exr");
    st = WriteExr(var_out, moments->PerSampleVariance(result.spp_done), var_header);
  }
  if (st.ok() && !args.strategies.empty() && !result.interrupted)
    st = WriteStrategyImages(args.strategies, scene, setup, result.spp_done, args.seed, header);
  if (!st.ok()) {
    std::fprintf(stderr, "error: %s\n", st.message().c_str());
    return kExitRunFailed;
  }
  std::printf("%s: %s (%u spp, %.2f s, %.2f Mrays/s)\n",
              result.interrupted ? "interrupted, wrote partial image" : "wrote", out.c_str(),
              result.spp_done, result.seconds,
              result.seconds > 0 ? double(result.rays) / result.seconds * 1e-6 : 0.0);
  return result.interrupted ? interrupted_code : kExitOk;
}

}  // namespace ptlab
