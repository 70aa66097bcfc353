// The render driver: passes of samples over tiles on worker threads, deterministic film merge.
#include "engine/render/render.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "engine/render/camera.h"
#include "engine/render/film.h"
#include "engine/render/integrator.h"
#include "engine/render/packet_render.h"

namespace ptlab {
namespace {

constexpr int kTileSize = 32;

struct Tile {
  int x0, y0, x1, y1;
};

using TileStats = TileSampleStats;

}  // namespace

uint32_t SamplesPerPass(uint32_t spp) { return std::min<uint32_t>(spp, 16); }

RenderResult Render(const Scene& scene, const Bvh& bvh, const RenderOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const Camera camera(scene.camera);
  const PixelFilter filter(scene.filter);
  const RenderContext ctx{scene, bvh};
  const int width = camera.width(), height = camera.height();
  const int border = int(std::ceil(filter.radius()));

  std::vector<Tile> tiles;
  for (int y = 0; y < height; y += kTileSize)
    for (int x = 0; x < width; x += kTileSize)
      tiles.push_back({x, y, std::min(x + kTileSize, width), std::min(y + kTileSize, height)});

  FilmBlock film(0, 0, width, height);
  std::vector<FilmBlock> blocks(tiles.size());
  std::vector<TileStats> stats(tiles.size());
  RenderResult result;
  RenderProgress progress;
  progress.samples_total = uint64_t(width) * uint64_t(height) * options.spp;

  const int threads = std::max(1, options.threads);
  const uint32_t per_pass = std::max<uint32_t>(1, SamplesPerPass(options.spp));
  std::atomic<bool> start_failed{false};  // a worker thread could not be started
  auto cancelled = [&] {
    return start_failed.load() || (options.cancel && options.cancel->load());
  };

  for (uint32_t s0 = 0; s0 < options.spp && !cancelled(); s0 += per_pass) {
    const uint32_t s1 = std::min(options.spp, s0 + per_pass);
    std::atomic<size_t> next_tile{0};
    std::mutex mutex;
    std::condition_variable tile_done;
    size_t tiles_done = 0;
    auto worker = [&] {
      for (;;) {
        if (cancelled()) return;
        const size_t i = next_tile.fetch_add(1);
        if (i >= tiles.size()) return;
        const Tile& t = tiles[i];
        blocks[i].Reset(t.x0 - border, t.y0 - border, t.x1 - t.x0 + 2 * border,
                        t.y1 - t.y0 + 2 * border);
        stats[i] = TileStats{};
        if (options.packets != nullptr) {
          RenderTilePacket8(ctx, *options.packets, camera, filter, t.x0, t.y0, t.x1, t.y1, s0,
                            s1, options.seed, &blocks[i], &stats[i]);
        } else {
          RenderTileScalar(ctx, camera, filter, t.x0, t.y0, t.x1, t.y1, s0, s1, options.seed,
                           &blocks[i], &stats[i]);
        }
        std::lock_guard<std::mutex> lock(mutex);
        ++tiles_done;
        progress.samples_done += uint64_t(t.x1 - t.x0) * uint64_t(t.y1 - t.y0) * (s1 - s0);
        progress.rays += stats[i].rays;
        tile_done.notify_one();
      }
    };
    std::vector<std::thread> pool;
    try {
      for (int i = 0; i < threads; ++i) pool.emplace_back(worker);
    } catch (const std::system_error& e) {
      // Out of memory for stacks or a process limit: stop the workers that did start.
      start_failed.store(true);
      result.error = "cannot start worker thread " + std::to_string(pool.size() + 1) + " of " +
                     std::to_string(threads) + " (" + e.what() + "); expected a thread count " +
                     "the system can run (--threads)";
    }
    {
      // The coordinating thread reports progress while the workers run.
      std::unique_lock<std::mutex> lock(mutex);
      size_t reported = 0;
      while (tiles_done < tiles.size()) {
        tile_done.wait_for(lock, std::chrono::milliseconds(200));
        if (cancelled()) break;
        if (tiles_done != reported && options.on_progress) {
          reported = tiles_done;
          progress.seconds = std::chrono::duration<double>(Clock::now() - start).count();
          const RenderProgress snapshot = progress;
          lock.unlock();
          options.on_progress(snapshot);
          lock.lock();
        }
      }
    }
    for (auto& t : pool) t.join();
    if (tiles_done < tiles.size()) break;  // interrupted: this pass is incomplete, drop it
    for (size_t i = 0; i < tiles.size(); ++i) {
      film.Merge(blocks[i]);
      result.rays += stats[i].rays;
      result.packets += stats[i].packets;
      result.stage_seconds += stats[i].seconds;
      if (stats[i].nonfinite > 0 && result.nonfinite_samples == 0)
        result.first_nonfinite_x = stats[i].first_x, result.first_nonfinite_y = stats[i].first_y;
      result.nonfinite_samples += stats[i].nonfinite;
    }
    result.spp_done = s1;
    if (options.on_progress) {
      progress.seconds = std::chrono::duration<double>(Clock::now() - start).count();
      options.on_progress(progress);
    }
  }
  result.interrupted = result.spp_done < options.spp;
  result.image = film.Resolve();
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace ptlab
