// Outputs of `ptlab render`: the EXR and PNG, --tile-times, --strategies images, --stats.
#include "tools/ptlab/render_output.h"

#include <filesystem>
#include <sstream>
#include <system_error>
#include <thread>

#include "engine/bvh/bvh.h"
#include "engine/core/memory.h"
#include "engine/image/atomic_file.h"
#include "engine/image/image_io.h"
#include "engine/render/bdpt_strategies.h"
#include "engine/render/strategy_figure.h"
#include "engine/scene/scene_bytes.h"
#include "simd/bvh8.h"
#include "simd/triangle_rows.h"

namespace ptlab {

std::string FormatDuration(double s) {
  char buf[32];
  if (s < 60) std::snprintf(buf, sizeof buf, "%.1fs", s);
  else if (s < 3600) std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
  else std::snprintf(buf, sizeof buf, "%dh%02dm", int(s) / 3600, (int(s) % 3600) / 60);
  return buf;
}

// --tile-times: pass, tile and wall seconds of every tile (input of benchmarks/mpi_model).
Status WriteTileTimes(const std::string& path, const RenderResult& r) {
  std::ostringstream out;
  out << "pass,tile,seconds\n";
  for (size_t k = 0; k < r.tile_seconds.size(); ++k)
    out << k / size_t(r.tile_count) << "," << k % size_t(r.tile_count) << "," << r.tile_seconds[k]
        << "\n";
  return WriteFileAtomically(path, out.str());
}

// The EXR, then (once it is written) the PNG, each atomically. With more than one thread the
// PNG is encoded on a second thread while the EXR is: each takes about 0.1 s at 800 x 600
// (deflate), serial time that every render would pay after its passes.
Status WriteImages(const std::string& exr, const std::string& png, const Image& image,
                   const std::vector<std::pair<std::string, std::string>>& header, int threads) {
  StatusOr<std::string> png_bytes = Status::Error("WritePng: " + png + ": not encoded");
  std::thread png_encoder;
  if (threads > 1) {
    try {
      png_encoder = std::thread([&] { png_bytes = EncodePng(png, image); });
    } catch (const std::system_error&) {
      // No second thread: the PNG is encoded after the EXR.
    }
  }
  const StatusOr<std::string> exr_bytes = EncodeExr(exr, image, header);
  if (png_encoder.joinable()) {
    png_encoder.join();
  } else {
    png_bytes = EncodePng(png, image);
  }
  if (!exr_bytes.ok()) return exr_bytes.status();
  Status st = WriteFileAtomically(exr, *exr_bytes);
  if (!st.ok()) return Status::Error("WriteExr: " + st.message());
  if (!png_bytes.ok()) return png_bytes.status();
  st = WriteFileAtomically(png, *png_bytes);
  if (!st.ok()) return Status::Error("WritePng: " + st.message());
  return Status::Ok();
}

// --strategies DIR: each strategy's image, DIR/s<S>_t<T>.exr (each written atomically).
namespace {

// Paths of up to this many bounces get a --strategies image each; longer ones are summed.
constexpr int kStrategyImageBounces = 4;

std::string StrategyStem(int s, int t) { return "s" + std::to_string(s) + "_t" + std::to_string(t); }

}  // namespace

std::vector<std::string> StrategyOutputPaths(const std::string& dir) {
  const std::filesystem::path d(dir);
  std::vector<std::string> paths;
  for (int s = 0; s <= kStrategyImageBounces + 1; ++s)
    for (int t = 1; s + t - 2 <= kStrategyImageBounces; ++t)
      paths.push_back((d / (StrategyStem(s, t) + ".exr")).string());
  paths.push_back((d / "longer.exr").string());
  paths.push_back((d / "figure.png").string());
  return paths;
}

Status WriteStrategyImages(const std::string& dir, const Scene& scene, const RenderSetup& setup,
                           uint32_t spp, uint64_t seed,
                           std::vector<std::pair<std::string, std::string>> header) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec)
    return Status::Error("--strategies: cannot create directory " + dir + ": " + ec.message());
  std::vector<StrategyImage> images =
      RenderStrategyImages(scene, setup.bvh(), &setup.kernels(), spp, seed);
  // Paths of up to 4 bounces one image each (Veach's figure shows up to 3); longer ones summed
  // into longer.exr, so the files still add up to the image.
  constexpr int kMaxBounces = kStrategyImageBounces;
  // Veach's figure of them, DIR/figure.png (rows: bounces 0-4; columns: light vertices s).
  const Image figure =
      StrategyFigure(images, scene.camera.width, scene.camera.height, kMaxBounces);
  Image longer(scene.camera.width, scene.camera.height);
  size_t n_longer = 0;
  for (const StrategyImage& im : images) {
    if (im.s + im.t - 2 <= kMaxBounces) continue;
    for (size_t i = 0; i < longer.rgb.size(); ++i) longer.rgb[i] += im.image.rgb[i];
    ++n_longer;
  }
  std::erase_if(images, [](const StrategyImage& im) { return im.s + im.t - 2 > kMaxBounces; });
  if (n_longer > 0) images.push_back({-1, -1, std::move(longer)});
  for (const StrategyImage& im : images) {
    const std::string name = im.s < 0 ? std::string("longer") : StrategyStem(im.s, im.t);
    header.emplace_back("ptlab:strategy", name);
    const Status st = WriteExr((std::filesystem::path(dir) / (name + ".exr")).string(), im.image,
                               header);
    header.pop_back();
    if (!st.ok()) return st;
  }
  if (const Status st = WritePng((std::filesystem::path(dir) / "figure.png").string(), figure);
      !st.ok())
    return st;
  std::fprintf(stderr, "wrote %zu strategy images and figure.png to %s (paths of more than %d "
                       "bounces: %zu strategies summed in longer.exr)\n",
               images.size(), dir.c_str(), kMaxBounces, n_longer);
  return Status::Ok();
}

// --stats: where the thread time of the wavefront went, and how full its packets were.
void PrintStats(const RenderResult& r, int threads) {
  const StageSeconds& t = r.stage_seconds;
  const double total = t.total();
  auto pct = [&](double x) { return total > 0 ? 100.0 * x / total : 0.0; };
  std::fprintf(stderr,
               "stats: %.3f s of thread time in stages (%.3f s wall x %d threads): traversal "
               "%.1f %%, shading %.1f %%, sampling %.1f %%, film %.1f %%\n",
               total, r.seconds, threads, pct(t.traversal), pct(t.shading), pct(t.sampling),
               pct(t.film));
  std::fprintf(stderr, "stats: %llu rays in %llu packets (%.2f of 8 lanes active), "
               "%.2f Mrays/s per thread in traversal\n",
               (unsigned long long)r.rays, (unsigned long long)r.packets,
               r.packets > 0 ? double(r.rays) / double(r.packets) : 0.0,
               t.traversal > 0 ? double(r.rays) / t.traversal * 1e-6 : 0.0);
}

// --stats: the heap bytes of the scene's tables, the BVHs, the wavefronts and the film
// (capacity × element size of their containers), and the process's peak resident set so far
// (which also holds what loading and the BVH builds freed, the allocator's slack, code and
// stacks).
void PrintMemory(const Scene& scene, const RenderSetup& setup, const RenderResult& r,
                 int threads, uint64_t peak_loaded) {
  const SceneBytes s = SceneTableBytes(scene);
  const auto mib = [](uint64_t bytes) { return double(bytes) / double(1 << 20); };
  const uint64_t bvh_bytes = BvhBytes(setup.bvh()), bvh8_bytes = simd::Bvh8Bytes(setup.bvh8());
  const uint64_t rows_bytes = simd::TriangleRowsBytes(setup.rows());
  const uint64_t counted =
      s.total() + bvh_bytes + bvh8_bytes + rows_bytes + r.memory.wavefront + r.memory.film;
  std::fprintf(stderr,
               "stats: memory (MiB): scene %.1f (triangles %.1f, shading %.1f, vertices %.1f, "
               "other %.1f), BVH %.1f, BVH8 %.1f, triangle rows %.1f, wavefronts %.1f (%d "
               "threads), film %.1f; sum %.1f; peak RSS %.1f (after loading %.1f, BVH %.1f, "
               "BVH8 %.1f)\n",
               mib(s.total()), mib(s.triangles), mib(s.shading), mib(s.vertices),
               mib(s.spheres + s.materials + s.emitters + s.meshes), mib(bvh_bytes),
               mib(bvh8_bytes), mib(rows_bytes), mib(r.memory.wavefront), threads,
               mib(r.memory.film), mib(counted), mib(PeakResidentBytes()), mib(peak_loaded),
               mib(setup.peak_after_bvh()), mib(setup.peak_after_bvh8()));
}

}  // namespace ptlab
