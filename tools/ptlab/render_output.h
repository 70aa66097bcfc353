// Outputs of `ptlab render`: progress on stderr, the EXR and PNG, --tile-times, --strategies
// images and the --stats lines.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/status.h"
#include "engine/image/image.h"
#include "engine/render/render.h"
#include "engine/scene/scene.h"
#include "simd/render_setup.h"

namespace ptlab {

/// "12.3s", "4m05s" or "1h02m".
std::string FormatDuration(double s);

// A bar with ETA and rays/s on a terminal; a plain line every 10 % otherwise.
class ProgressReporter {
 public:
  ProgressReporter() : tty_(isatty(STDERR_FILENO)) {}
  void Update(const RenderProgress& p) {
    const double frac = p.samples_total ? double(p.samples_done) / double(p.samples_total) : 1.0;
    const double eta = frac > 0 ? p.seconds * (1.0 - frac) / frac : 0.0;
    const double mrays = p.seconds > 0 ? double(p.rays) / p.seconds * 1e-6 : 0.0;
    if (tty_) {
      constexpr int kWidth = 30;
      const int filled = int(frac * kWidth);
      std::string bar(size_t(filled), '#');
      bar.resize(kWidth, '.');
      std::fprintf(stderr, "\r[%s] %5.1f%%  ETA %-8s %7.2f Mrays/s", bar.c_str(), 100 * frac,
                   FormatDuration(eta).c_str(), mrays);
      std::fflush(stderr);
    } else {
      const int decile = int(frac * 10);
      if (decile > last_decile_) {
        last_decile_ = decile;
        std::fprintf(stderr, "progress %3d%%  elapsed %s  ETA %s  %.2f Mrays/s\n", decile * 10,
                     FormatDuration(p.seconds).c_str(), FormatDuration(eta).c_str(), mrays);
      }
    }
  }
  void Finish() {
    if (tty_) std::fprintf(stderr, "\n");
  }

 private:
  bool tty_;
  int last_decile_ = 0;
};

// --tile-times: pass, tile and wall seconds of every tile (input of benchmarks/mpi_model).
Status WriteTileTimes(const std::string& path, const RenderResult& r);

// The EXR, then (once it is written) the PNG, each atomically. With more than one thread the
// PNG is encoded on a second thread while the EXR is: each takes about 0.1 s at 800 x 600
// (deflate), serial time that every render would pay after its passes.
Status WriteImages(const std::string& exr, const std::string& png, const Image& image,
                   const std::vector<std::pair<std::string, std::string>>& header, int threads);

// --strategies DIR: each strategy's image, DIR/s<S>_t<T>.exr (each written atomically).
Status WriteStrategyImages(const std::string& dir, const Scene& scene, const RenderSetup& setup,
                           uint32_t spp, uint64_t seed,
                           std::vector<std::pair<std::string, std::string>> header);

// Every file WriteStrategyImages may write into `dir` (s<S>_t<T>.exr for the strategies of up
// to kStrategyImageBounces bounces, longer.exr, figure.png), for the output guard.
std::vector<std::string> StrategyOutputPaths(const std::string& dir);

// --stats: where the thread time of the wavefront went, and how full its packets were.
void PrintStats(const RenderResult& r, int threads);

// --stats: the heap bytes of the scene's tables, the BVHs, the wavefronts and the film
// (capacity × element size of their containers), and the process's peak resident set so far
// (which also holds what loading and the BVH builds freed, the allocator's slack, code and
// stacks).
void PrintMemory(const Scene& scene, const RenderSetup& setup, const RenderResult& r,
                 int threads, uint64_t peak_loaded);

}  // namespace ptlab
