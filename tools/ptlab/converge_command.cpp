// `ptlab converge`: renders every variant of every scene progressively, measures the error of
// each pass against a reference, and writes CSV, JSON, a Markdown summary and gnuplot plots.
#include "tools/ptlab/converge_command.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <thread>

#include <unistd.h>

#include "engine/bvh/bvh.h"
#include "engine/image/image_io.h"
#include "engine/render/render.h"
#include "engine/render/setup_checks.h"
#include "engine/wavefront/wavefront.h"
#include "engine/io/scene_file.h"
#include "engine/io/xml_loader.h"
#include "engine/scene/scene_limits.h"
#include "simd/render_setup.h"
#include "tools/common/exit_codes.h"
#include "tools/common/output_guard.h"
#include "tools/converge/convergence.h"
#include "tools/converge/peer_variant.h"
#include "tools/converge/variant.h"
#include "tools/imgdiff/imgdiff.h"

namespace ptlab {
namespace {

/// --ref auto: the reference gets this many times a run's samples (or time).
constexpr int kAutoReferenceFactor = 16;
constexpr uint64_t kAutoReferenceSeed = 0x5eed0fef;

// A scene with what every run of it shares: BVHs and the two kernel tables.
struct LoadedScene {
  std::string path, stem;
  Scene scene;
  // BVHs and both tables; path=scalar or PTLAB_FORCE_SCALAR=1 picks the oracle's
  // (RenderSetup::KernelsFor, as `ptlab render --scalar`).
  std::optional<RenderSetup> setup;
  Image reference;
  std::string reference_note;
};

Status CheckReference(const Image& ref, const Scene& scene, const std::string& what) {
  if (ref.width != scene.camera.width || ref.height != scene.camera.height)
    return Status::Error(what + " is " + std::to_string(ref.width) + "x" +
                         std::to_string(ref.height) + " but the scene renders " +
                         std::to_string(scene.camera.width) + "x" +
                         std::to_string(scene.camera.height));
  for (size_t i = 0; i < ref.rgb.size(); ++i) {
    if (!std::isfinite(ref.rgb[i])) {
      const size_t px = i / 3;
      return Status::Error(what + " has a NaN/Inf value at pixel " +
                           std::to_string(px % size_t(ref.width)) + "," +
                           std::to_string(px / size_t(ref.width)) +
                           "; a reference must be finite");
    }
  }
  return Status::Ok();
}

// One progressive run; appends a point per completed pass.
bool RunOne(const LoadedScene& ls, const Variant& variant, const ConvergeArgs& args,
            uint64_t seed, const std::atomic<bool>* interrupted,
            std::vector<ConvergencePoint>* points, std::string* error) {
  Scene scene = ls.scene;  // the variant edits a copy
  VariantTarget target(&scene);
  if (const Status st = ApplyVariant(variant, &target); !st.ok()) {
    *error = ls.path + ": " + st.message();
    return false;
  }
  RenderOptions options;
  options.spp = args.time > 0 ? (1u << 20) : uint32_t(args.spp > 0 ? args.spp : scene.sampler.sample_count);
  options.time_budget = args.time;
  options.threads = args.threads;
  options.seed = seed;
  options.cancel = interrupted;
  options.kernels = &ls.setup->KernelsFor(target.scalar);
  options.adaptive = target.adaptive;
  const int w = scene.camera.width, h = scene.camera.height;
  FilmBlock halves[2] = {FilmBlock(0, 0, w, h), FilmBlock(0, 0, w, h)};
  ImageDiffOptions diff_options;
  options.on_pass = [&](const RenderPass& pass) {
    // Even passes into one half, odd into the other: two independent estimates.
    for (const FilmBlock& b : *pass.blocks) halves[pass.index % 2].Merge(b);
    const Image image = pass.film->Resolve();
    const ImageDiff d = CompareImages(image, ls.reference, diff_options);
    ConvergencePoint p;
    p.scene = ls.stem;
    p.variant = variant.name;
    p.seed = seed;
    p.pass = pass.index;
    p.spp = pass.spp_done;
    p.mean_spp = pass.spp_done;
    if (pass.pixels != nullptr) {
      double taken = 0;
      for (const PixelMoments& m : *pass.pixels) taken += m.taken;
      p.mean_spp = taken / double(pass.pixels->size());
    }
    p.seconds = pass.seconds;
    p.cpu_seconds = pass.cpu_seconds;
    p.rel_mse = d.rel_mse_all, p.rmse = d.rmse_all, p.mae = d.mae_all;
    p.bias = d.mean_rel_diff;
    p.parity_share = d.blocks.share;
    // With adaptive sampling the two halves hold different pixels' samples: no estimate.
    p.estimated_rel_mse = pass.index % 2 == 1 && pass.pixels == nullptr
                              ? EstimateRelMseFromHalves(halves[0].Resolve(), halves[1].Resolve())
                              : std::nan("");
    points->push_back(p);
  };
  const RenderResult r = Render(scene, ls.setup->bvh(), options);
  if (!r.pixel_samples.empty()) {
    // The sample-rate image: samples per pixel as EXR (exact counts) and PNG (count / spp).
    std::string name = ls.stem + "_" + variant.name + "_seed" + std::to_string(seed) + "_samples";
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '_';
    Image counts(w, h), rate(w, h);
    for (size_t i = 0; i < r.pixel_samples.size(); ++i) {
      const float n = float(r.pixel_samples[i]);
      const float f = r.spp_done > 0 ? n / float(r.spp_done) : 0.0f;
      counts.rgb[3 * i] = counts.rgb[3 * i + 1] = counts.rgb[3 * i + 2] = n;
      // Blue (few samples) to red (all of them), as CS184's rate image.
      rate.rgb[3 * i] = f, rate.rgb[3 * i + 1] = 0.0f, rate.rgb[3 * i + 2] = 1.0f - f;
    }
    const std::string base = (std::filesystem::path(args.out_dir) / name).string();
    Status st = WriteExr(base + ".exr", counts,
                         {{"ptlab:samples_taken", std::to_string(r.samples_taken)}});
    if (st.ok()) st = WritePng(base + ".png", rate);
    if (!st.ok()) {
      *error = st.message();
      return false;
    }
  }
  return !r.interrupted;
}

// One progressive run of a peer renderer: its passes measured as RunOne's.
Status RunPeerOne(const LoadedScene& ls, const Variant& variant, const PeerVariant& peer,
                  const ConvergeArgs& args, uint64_t seed, const std::atomic<bool>* interrupted,
                  std::vector<ConvergencePoint>* points, std::string* setup_note,
                  bool* stopped) {
  namespace fs = std::filesystem;
  const Scene& scene = ls.scene;
  PeerRunOptions o;
  o.scene_path = ls.path;
  o.scene = &scene;
  o.lookat = args.lookat;
  o.spp = args.time > 0 ? (1u << 20)
                        : uint32_t(args.spp > 0 ? args.spp : scene.sampler.sample_count);
  o.time = args.time;
  o.seed = seed;
  o.threads = args.threads;
  o.cancel = interrupted;
  o.work_dir = (fs::path(args.out_dir) / ("peer_passes_" + std::to_string(::getpid()))).string();
  PeerFilm film(scene.camera.width, scene.camera.height);
  ImageDiffOptions diff_options;
  auto on_pass = [&](const PeerPass& pass) {
    film.Add(pass);
    const ImageDiff d = CompareImages(film.Resolve(), ls.reference, diff_options);
    ConvergencePoint p;
    p.scene = ls.stem;
    p.variant = variant.name;
    p.seed = seed;
    p.pass = pass.index;
    p.spp = pass.spp_done;
    p.mean_spp = pass.spp_done;
    p.seconds = pass.seconds;
    p.cpu_seconds = pass.cpu_seconds;
    p.rel_mse = d.rel_mse_all, p.rmse = d.rmse_all, p.mae = d.mae_all;
    p.bias = d.mean_rel_diff;
    p.parity_share = d.blocks.share;
    p.estimated_rel_mse = pass.index % 2 == 1
                              ? EstimateRelMseFromHalves(film.ResolveHalf(0), film.ResolveHalf(1))
                              : std::nan("");
    points->push_back(p);
  };
  PeerSetup setup;
  const Status st = RunPeer(peer, o, on_pass, &setup, stopped);
  std::error_code ec;
  fs::remove_all(o.work_dir, ec);
  if (st.ok()) {
    char note[256];
    std::snprintf(note, sizeof note,
                  "%s, %s, seed %llu: %s; not in the times: scene load %.3g s, first render "
                  "(kernel compilation or cache load, and one pass) %.3g s",
                  ls.stem.c_str(), variant.name.c_str(), static_cast<unsigned long long>(seed),
                  setup.version.c_str(), setup.load_seconds, setup.warmup_seconds);
    *setup_note = note;
    // The last image, to look at.
    std::string name = ls.stem + "_" + variant.name + "_seed" + std::to_string(seed);
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '_';
    return WriteExr((fs::path(args.out_dir) / (name + ".exr")).string(), film.Resolve(),
                    {{"ptlab:note", *setup_note}});
  }
  return st;
}

}  // namespace

int RunConverge(const ConvergeArgs& args, const std::atomic<bool>* interrupted) {
  namespace fs = std::filesystem;
  if (args.time > 0 && args.spp > 0) {
    std::fprintf(stderr, "error: give --spp or --time, not both\n");
    return kExitUsage;
  }
  const bool auto_ref = args.refs.size() == 1 && args.refs[0] == "auto";
  if (!auto_ref && args.refs.size() != args.scenes.size()) {
    std::fprintf(stderr, "error: %zu scenes but %zu --ref; give one reference per scene, or "
                 "--ref auto\n", args.scenes.size(), args.refs.size());
    return kExitUsage;
  }
  std::vector<Variant> variants;
  std::vector<std::optional<PeerVariant>> peers;  // per variant: set for renderer=...
  for (const std::string& spec : args.variants.empty() ? std::vector<std::string>{""}
                                                       : args.variants) {
    if (IsPeerSpec(spec)) {
      StatusOr<PeerVariant> peer = ParsePeerVariant(spec);
      if (!peer.ok()) {
        std::fprintf(stderr, "error: %s\n", peer.status().message().c_str());
        return kExitUsage;
      }
      variants.push_back(Variant{spec, {}});
      peers.push_back(*peer);
      continue;
    }
    peers.push_back(std::nullopt);
    StatusOr<Variant> v = ParseVariant(spec);
    if (!v.ok()) {
      std::fprintf(stderr, "error: %s\n", v.status().message().c_str());
      return kExitUsage;
    }
    variants.push_back(*v);
  }
  // The folder is created and probed before anything is loaded or rendered.
  if (std::string error; const int code = PrepareOutputFolder(args.out_dir, &error)) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return code;
  }
  ConvergeArgs run_args = args;
  if (run_args.threads <= 0) run_args.threads = std::max(1, int(std::thread::hardware_concurrency()));

  std::vector<std::unique_ptr<LoadedScene>> scenes;
  for (size_t i = 0; i < args.scenes.size(); ++i) {
    auto ls = std::make_unique<LoadedScene>();
    ls->path = args.scenes[i];
    ls->stem = fs::path(ls->path).stem().string();
    LoadOptions load_options;
    if (args.lookat == "nori2015") load_options.lookat = LookatConvention::kNori2015;
    load_options.defines = args.defines;
    StatusOr<Scene> loaded = LoadSceneFile(ls->path, load_options);
    if (!loaded.ok()) {
      std::fprintf(stderr, "error: %s\n", loaded.status().message().c_str());
      return kExitUsage;
    }
    ls->scene = std::move(*loaded);
    if (args.width > 0) {
      CameraDesc& cam = ls->scene.camera;
      // The film-size check of render's --width: a tall film's height may be past the limits.
      const double height = std::round(double(args.width) * cam.height / cam.width);
      const std::string size = FilmSizeError(args.width, int64_t(std::min(height, 1e15)));
      if (!size.empty()) {
        std::fprintf(stderr, "error: %s: --width: %s\n", ls->path.c_str(), size.c_str());
        return kExitUsage;
      }
      cam.height = int(height);
      cam.width = args.width;
    }
    if (const Status sane = CheckRenderSetup(ls->scene); !sane.ok()) {  // as render does
      std::fprintf(stderr, "error: %s: %s\n", ls->path.c_str(), sane.message().c_str());
      return kExitUsage;
    }
    // Every variant must apply before anything renders (peers take no ptlab keys).
    for (const Variant& v : variants) {
      Scene copy = ls->scene;
      VariantTarget t(&copy);
      if (const Status st = ApplyVariant(v, &t); !st.ok()) {
        std::fprintf(stderr, "error: %s: %s\n", ls->path.c_str(), st.message().c_str());
        return kExitUsage;
      }
    }
    ls->setup.emplace(ls->scene, KernelChoice::kSimd);
    if (!auto_ref) {
      StatusOr<Image> ref = ReadImage(args.refs[i]);
      Status st = ref.ok() ? CheckReference(*ref, ls->scene, "reference " + args.refs[i])
                           : ref.status();
      if (!st.ok()) {
        std::fprintf(stderr, "error: %s\n", st.message().c_str());
        return kExitUsage;
      }
      ls->reference = std::move(*ref);
      ls->reference_note = args.refs[i];
    }
    scenes.push_back(std::move(ls));
  }

  // No output may be a scene, a file a scene reads, or a reference (tools/common/output_guard.h).
  OutputGuard guard;
  for (const auto& ls : scenes) guard.AddInputs(ls->scene.input_files, "input of " + ls->stem);
  if (!auto_ref) guard.AddInputs(args.refs, "--ref");
  for (const char* name : {"converge.csv", "converge.json", "summary.md"})
    guard.AddOutput((fs::path(args.out_dir) / name).string(), "output");
  for (const auto& ls : scenes) {
    if (auto_ref)
      guard.AddOutput((fs::path(args.out_dir) / (ls->stem + "_reference.exr")).string(),
                      "--ref auto output");
    if (!args.no_plots)
      guard.AddOutput((fs::path(args.out_dir) / (ls->stem + ".dat")).string(), "plot data");
  }
  if (std::string error; const int code = guard.Check(&error)) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return code;
  }

  // --ref auto renders with ptlab's first variant (the scene as loaded if all are peers).
  size_t ref_variant = 0;
  while (ref_variant < variants.size() && peers[ref_variant]) ++ref_variant;
  const Variant ref_spec =
      ref_variant < variants.size() ? variants[ref_variant] : Variant{"scene", {}};
  for (auto& ls : scenes) {
    if (!auto_ref) continue;
    // The reference: ptlab's first variant with kAutoReferenceFactor times the budget.
    Scene scene = ls->scene;
    VariantTarget t(&scene);
    (void)ApplyVariant(ref_spec, &t);
    RenderOptions o;
    const uint32_t spp = uint32_t(args.spp > 0 ? args.spp : scene.sampler.sample_count);
    o.spp = args.time > 0 ? (1u << 20) : spp * kAutoReferenceFactor;
    o.time_budget = args.time * kAutoReferenceFactor;
    o.threads = run_args.threads;
    o.seed = kAutoReferenceSeed;
    o.cancel = interrupted;
    o.kernels = &ls->setup->KernelsFor(t.scalar);
    std::fprintf(stderr, "converge: %s: rendering the reference (variant %s, %dx the budget)\n",
                 ls->stem.c_str(), ref_spec.name.c_str(), kAutoReferenceFactor);
    RenderResult r = Render(scene, ls->setup->bvh(), o);
    if (r.interrupted) return kExitInterrupted;
    ls->reference = std::move(r.image);
    ls->reference_note = "auto: rendered by ptlab with variant " + ref_spec.name + " at " +
                         std::to_string(r.spp_done) + " spp (seed " +
                         std::to_string(kAutoReferenceSeed) + ")";
    const std::string ref_path = (fs::path(args.out_dir) / (ls->stem + "_reference.exr")).string();
    if (const Status st = WriteExr(ref_path, ls->reference, {{"ptlab:note", ls->reference_note}});
        !st.ok()) {
      std::fprintf(stderr, "error: %s\n", st.message().c_str());
      return kExitRunFailed;
    }
  }

  // Runs interleaved: seed by seed, every scene and variant, so that machine noise over time
  // falls on all variants alike.
  std::vector<ConvergencePoint> points;
  std::vector<std::string> peer_notes, peer_errors;
  std::set<std::pair<std::string, size_t>> peer_failed;  // (scene, variant): not run again
  bool stopped = false;
  for (int k = 0; k < args.seeds && !stopped; ++k) {
    for (auto& ls : scenes) {
      for (size_t vi = 0; vi < variants.size(); ++vi) {
        const Variant& v = variants[vi];
        std::string error;
        if (peers[vi] && peer_failed.count({ls->path, vi})) continue;
        std::fprintf(stderr, "converge: %s  %s  seed %llu\n", ls->stem.c_str(), v.name.c_str(),
                     static_cast<unsigned long long>(args.seed + uint64_t(k)));
        if (peers[vi]) {
          // A peer that fails (not installed, cannot read the scene) costs only its own rows.
          std::string note;
          const Status st = RunPeerOne(*ls, v, *peers[vi], run_args, args.seed + uint64_t(k),
                                       interrupted, &points, &note, &stopped);
          if (!st.ok()) {
            std::fprintf(stderr, "error: %s: %s\n", ls->path.c_str(), st.message().c_str());
            peer_errors.push_back(ls->stem + ", " + v.name + ": " + st.message());
            peer_failed.insert({ls->path, vi});
          } else if (!note.empty()) {
            peer_notes.push_back(note);
          }
          if (stopped) break;
          continue;
        }
        if (!RunOne(*ls, v, run_args, args.seed + uint64_t(k), interrupted, &points, &error)) {
          if (!error.empty()) {  // variants were checked before: an output failed
            std::fprintf(stderr, "error: %s\n", error.c_str());
            return kExitRunFailed;
          }
          stopped = true;
          break;
        }
      }
      if (stopped) break;
    }
  }

  const std::vector<VariantSummary> summary = Summarize(points);
  std::vector<std::string> notes;
  for (const auto& ls : scenes) notes.push_back(ls->stem + ": " + ls->reference_note);
  const std::string dir = args.out_dir;
  Status st = WriteConvergeCsv((fs::path(dir) / "converge.csv").string(), points);
  if (st.ok()) st = WriteConvergeJson((fs::path(dir) / "converge.json").string(), notes, points, summary);
  std::string table = SummaryTable(summary);
  std::string md = "References:\n\n";
  for (const std::string& n : notes) md += "- " + n + "\n";
  md += "\n" + table;
  if (!peer_notes.empty() || !peer_errors.empty()) {
    md += "\nPeer renderers (times are of the passes' renders only):\n\n";
    for (const std::string& n : peer_notes) md += "- " + n + "\n";
    for (const std::string& e : peer_errors) md += "- FAILED: " + e + "\n";
  }
  if (st.ok()) st = WriteFileAtomically((fs::path(dir) / "summary.md").string(), md);
  if (st.ok() && !args.no_plots) {
    for (const auto& ls : scenes) {
      std::vector<VariantSummary> mine;
      for (const VariantSummary& s : summary)
        if (s.scene == ls->stem) mine.push_back(s);
      st = PlotConvergence(dir, ls->stem, mine);
      if (!st.ok()) break;
    }
  }
  std::printf("%s", md.c_str());
  if (!st.ok()) {
    std::fprintf(stderr, "error: %s\n", st.message().c_str());
    return kExitRunFailed;
  }
  std::printf("wrote %s/converge.csv, converge.json, summary.md%s\n", dir.c_str(),
              args.no_plots ? "" : " and plots");
  if (stopped) return kExitInterrupted;
  if (!peer_errors.empty()) {
    std::fprintf(stderr, "error: %zu peer run(s) failed (the other variants' results are "
                 "written):\n", peer_errors.size());
    for (const std::string& e : peer_errors) std::fprintf(stderr, "  %s\n", e.c_str());
    return kExitUsage;
  }
  return kExitOk;
}

}  // namespace ptlab
