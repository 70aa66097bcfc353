// ptlab's command line (see command_line.h).
#include "tools/ptlab/command_line.h"

#include "engine/scene/scene_limits.h"
#include "tools/cli_checks.h"
#include "tools/converge/variant.h"

namespace ptlab {

CLI::App* AddConvergeCommand(CLI::App* app, ConvergeArgs* a) {
  CLI::App* cmd = app->add_subcommand(
      "converge",
      "Error against time: render variants of scenes progressively, measure relMSE (and "
      "more) after every pass against a reference; CSV, JSON, summary and plots");
  cmd->add_option("scenes", a->scenes, "Scene files (.xml)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--ref", a->refs,
                  "Reference EXR per scene (in order), or 'auto': rendered by ptlab with the "
                  "first ptlab (not peer) variant at 16x the budget")
      ->required();
  cmd->add_option("--variant", a->variants,
                  "Overrides key=value[,key=value] (keys: " + VariantKeys() +
                      "), or a peer renderer: renderer=mitsuba3[,variant=llvm_ad_rgb|scalar_rgb]"
                      "[,sampler=...][,max_depth=N][,rr_depth=N] (docs/peer.md); repeat for "
                      "each variant; none: the scene as it is");
  cmd->add_option("--spp", a->spp, "Samples per pixel of each run (default: the scene's)")
      ->check(CLI::Range(1, 1 << 20));
  cmd->add_option("--time", a->time, "Seconds of rendering per run (instead of --spp)")
      ->check(FiniteRange(1e-3, 1e6));
  cmd->add_option("--threads", a->threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--seeds", a->seeds, "Runs per variant, with seeds seed, seed+1, ...")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--seed", a->seed, "First seed")->check(UnsignedDecimal());
  cmd->add_option("-o,--output", a->out_dir, "Output folder")->required();
  cmd->add_flag("--no-plots", a->no_plots, "Skip the gnuplot plots");
  cmd->add_option("--width", a->width,
                  "Image width of every scene (height keeps its aspect ratio); with --ref auto, "
                  "or references of that size")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--lookat", a->lookat, "lookat convention, as for render: nori or nori2015")
      ->check(CLI::IsMember({"nori", "nori2015"}));
  cmd->add_option("-D,--define", a->defines, "Mitsuba scene parameter name=value (as render)");
  return cmd;
}

void DefineCommandLine(CommandLine* cl, const std::string& version) {
  CLI::App& app = cl->app;
  app.require_subcommand(1);
  app.set_version_flag("--version", version);

  CLI::App* cmd = cl->render_cmd =
      app.add_subcommand("render", "Render a scene (Nori XML) to EXR + PNG");
  cmd->add_option("scene", cl->render.scene,
                  "Scene file (.xml: Nori/Mitsuba; .dae: COLLADA, CS184)")
      ->required()
      ->check(CLI::ExistingFile);
  const CLI::Validator non_empty_path(
      [](std::string& path) { return path.empty() ? "the output path is empty" : ""; }, "PATH");
  CLI::Option* output_opt =
      cmd->add_option("-o,--output", cl->render.output, "Output EXR (default: <scene stem>.exr)")
          ->check(non_empty_path);
  cmd->add_option("-f,--image", cl->render.image,
                  "CS184 -f: output PNG (the EXR is written beside it), or an .exr")
      ->check(non_empty_path)
      ->excludes(output_opt);
  cmd->add_option("-s,--spp", cl->render.spp,
                  "Samples per pixel (CS184 -s; default: the scene's sampleCount, 1 for .dae)")
      ->check(CLI::Range(1, 1 << 20));
  cmd->add_option("-t,--threads", cl->render.threads,
                  "Worker threads (CS184 -t; default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("-l,--light-samples", cl->render.light_samples,
                  "Emitter samples per shading point (CS184 -l; default: the integrator's "
                  "lightSamples, 1 for .dae)")
      ->check(CLI::Range(1, 1 << 16));
  cmd->add_option("-m,--max-depth", cl->render.max_depth,
                  "Maximum ray depth, 0 = emitted light only, 1 = direct light, -1 = unbounded "
                  "(CS184 -m; default: the integrator's maxDepth, 1 for .dae)")
      ->check(CLI::Range(-1, 1 << 20));
  cmd->add_option("-e,--envmap", cl->render.envmap,
                  "Add an environment-map light (EXR/HDR lat-long, +y up; CS184 -e)")
      ->check(CLI::ExistingFile);
  cmd->add_option("-b,--lens-radius", cl->render.lens_radius,
                  "Thin-lens aperture radius, 0 = pinhole (CS184 -b; default: the scene's)")
      ->check(FloatRange(0, 1e6f));
  cmd->add_option("-d,--focal-distance", cl->render.focal_distance,
                  "Thin-lens focus distance (CS184 -d; default: the scene's, 4.7 for .dae)")
      ->check(FloatRange(1e-6f, kMaxWorldCoordinate));
  CLI::Option* resolution_opt =
      cmd->add_option("-r,--resolution", cl->render.resolution,
                      "Film width and height in pixels (CS184 -r W H; a .dae keeps its vertical "
                      "field of view)")
          ->expected(2)
          ->check(CLI::Range(1, 65536));
  cmd->add_option("-c,--camera-file", cl->render.camera_file,
                  "CS184 camera settings file (-c; what its C key writes): position, view, "
                  "vertical field of view, clip planes and lens")
      ->check(CLI::ExistingFile);
  cmd->add_option("-a,--adaptive", cl->render.adaptive,
                  "Adaptive sampling: samples per batch and tolerance (CS184 -a 64 0.05)")
      ->expected(2);
  cmd->add_option("--seed", cl->render.seed, "Seed of the per-pixel random streams")
      ->check(UnsignedDecimal());
  cmd->add_option("--sampler", cl->render.sampler,
                  "Sampler, overriding the scene's: independent (PCG32) or sobol (Owen-scrambled "
                  "Sobol'; the default of scenes that name none)")
      ->check(CLI::IsMember({"independent", "sobol"}));
  cmd->add_option("--integrator", cl->render.integrator,
                  "Integrator, overriding the scene's (any format): normals, direct_ems, "
                  "direct_mats, direct_mis, whitted, path_mats, path_ems, path_mis, bdpt or "
                  "ptracer (docs/bdpt.md)")
      ->check(CLI::IsMember({"normals", "direct_ems", "direct_mats", "direct_mis", "whitted",
                             "path_mats", "path_ems", "path_mis", "bdpt", "ptracer"}));
  cmd->add_option("--strategies", cl->render.strategies,
                  "bdpt/ptracer: also write each strategy's MIS-weighted contribution as "
                  "DIR/s<S>_t<T>.exr (Veach fig. 10.3; a second, one-thread render with the "
                  "same samples; docs/bdpt.md)");
  cmd->add_option("--width", cl->render.width, "Override the image width")
      ->check(CLI::Range(1, 65536))
      ->excludes(resolution_opt);
  cmd->add_option("--height", cl->render.height, "Override the image height")
      ->check(CLI::Range(1, 65536))
      ->excludes(resolution_opt);
  cmd->add_flag("-q,--quiet", cl->render.quiet, "No progress output");
  cmd->add_option("-D,--define", cl->render.defines,
                  "Mitsuba scene parameter name=value (overrides the scene's <default>)");
  cmd->add_option("--lookat", cl->render.lookat,
                  "lookat convention: nori (current) or nori2015 (the mirrored, unnormalised "
                  "frame of the 2015-16 Nori that rendered the eth2015 references)")
      ->check(CLI::IsMember({"nori", "nori2015"}));
  cmd->add_flag("--scalar", cl->render.scalar,
                "Render with the scalar oracle's kernels, one ray at a time (same as "
                "PTLAB_FORCE_SCALAR=1)");
  cmd->add_flag("--stats", cl->render.stats,
                "Print the fraction of time in traversal, shading and sampling, packet "
                "occupancy, and the memory of the scene, BVHs, wavefronts and film with the "
                "peak RSS");
  cmd->add_option("--max-memory", cl->render.max_memory_gib,
                  "GiB the scene and the render may take; a scene or option set that would "
                  "need more is refused before it is built (default: 3/4 of the RAM)")
      ->check(FiniteRange(0.01, 1e6));
  cmd->add_option("--tile-times", cl->render.tile_times,
                  "Write the wall time of every tile of every pass to this CSV "
                  "(pass,tile,seconds)");
  cmd->add_flag("--moments", cl->render.moments,
                "Also write NAME_var.exr beside NAME.exr: each pixel's per-sample variance in "
                "XYZ, estimated from the passes (16 samples, fewer to make at least 32 passes), "
                "for imgdiff --ztest "
                "(docs/mitsuba-tests.md)");

  CLI::App* test_cmd = cl->test_cmd = app.add_subcommand(
      "test", "Run a Nori statistical test file (<test type=\"ttest|chi2test\">)");
  test_cmd->add_option("file", cl->test_file, "Nori test file (.xml)")->required();
  test_cmd->add_flag("-v,--verbose", cl->test_verbose, "Also print variances and chi-square notes");

  CLI::App* envmap_cmd = cl->envmap_cmd =
      app.add_subcommand("envmap-pdf",
                         "Write the importance-sampling probability image of an environment map "
                         "(R: row marginal CDF, G: conditional CDF, B: pixel probability / max)");
  envmap_cmd->add_option("map", cl->envmap_in, "Lat-long map (.exr or .hdr)")
      ->required()
      ->check(CLI::ExistingFile);
  envmap_cmd->add_option("-o,--output", cl->envmap_out, "Output image (.png, .exr or .pfm)")
      ->required();

  cl->converge_cmd = AddConvergeCommand(&app, &cl->converge);
}

}  // namespace ptlab
