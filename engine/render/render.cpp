// The render driver: passes of samples over tiles on worker threads, deterministic film merge.
#include "engine/render/render.h"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "engine/core/check.h"
#include "engine/render/camera.h"
#include "engine/render/film.h"
#include "engine/render/integrator.h"
#include "engine/render/light_film.h"
#include "engine/render/packet_render.h"
#include "engine/wavefront/wavefront.h"

namespace ptlab {
namespace {

constexpr int kTileSize = 32;

struct Tile {
  int x0, y0, x1, y1;
};

using TileStats = TileSampleStats;

}  // namespace

uint32_t SamplesPerPass(uint32_t spp) { return std::min<uint32_t>(spp, 16); }

uint32_t PassSamples(const RenderOptions& options) {
  const uint32_t spp = std::max<uint32_t>(1, options.spp);
  if (options.adaptive.batch > 0 && options.distribution == nullptr)
    return std::min(options.adaptive.batch, spp);
  if (options.pass_spp > 0) return std::min(options.pass_spp, spp);
  return std::max<uint32_t>(1, SamplesPerPass(spp));
}

bool PixelConverged(const PixelMoments& m, float tolerance) {
  if (m.n < kAdaptiveMinSamples) return false;
  const double n = double(m.n), mean = m.sum / n;
  if (!(mean > 0)) return false;  // nothing seen yet: an all-black batch is not converged
  const double variance = std::max(0.0, (m.sum2 - n * mean * mean) / (n - 1));
  return 1.96 * std::sqrt(variance / n) <= double(tolerance) * mean;
}

namespace {

// CPU time of the whole process (every thread) in seconds: what a render costs however busy the
// machine is with other work, unlike wall time.
double ProcessCpuSeconds() {
  timespec t{};
  if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t) != 0) return 0.0;
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

}  // namespace

RenderResult Render(const Scene& scene, const Bvh& bvh, const RenderOptions& options) {
  // A Bvh built without the scene's spheres (BuildBvh(triangles) alone) would drop them.
  PTLAB_CHECK(bvh.spheres.size() == scene.spheres.size());
  PTLAB_CHECK(bvh.sdf_grids.size() == scene.sdf_grids.size());  // BuildSceneBvh copies them
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const double cpu_start = ProcessCpuSeconds();
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
  // The blocks' accumulators in one arena (huge pages, see FilmBlock::Reset): tile i's at
  // block_first[i] floats.
  std::vector<size_t> block_first(tiles.size() + 1, 0);
  for (size_t i = 0; i < tiles.size(); ++i) {
    const Tile& t = tiles[i];
    block_first[i + 1] =
        block_first[i] + size_t(t.x1 - t.x0 + 2 * border) * size_t(t.y1 - t.y0 + 2 * border) * 4;
  }
  AlignedVector<float> block_sums(block_first.back());
  std::vector<TileStats> stats(tiles.size());
  RenderResult result;
  // bdpt and ptracer: the light films (this pass's and the completed passes'), the film the
  // caller sees (camera + light), and the splats of tiles done ahead of their turn.
  const bool bidirectional = IsBidirectional(scene.integrator.type);
  std::optional<BidirectionalSetup> bidirectional_setup;
  std::optional<LightFilm> light_pass, light_total;
  FilmBlock composed;
  std::vector<std::vector<LightSplat>> tile_splats;
  if (bidirectional) {
    if (options.adaptive.batch > 0 || options.distribution != nullptr) {
      result.error = std::string(IntegratorTypeName(scene.integrator.type)) +
                     " does not run with adaptive sampling or under mpirun yet";
      return result;
    }
    bidirectional_setup.emplace(scene);
    light_pass.emplace(filter, width, height);
    light_total.emplace(filter, width, height);
    tile_splats.resize(tiles.size());
  }
  const WavefrontKernels* kernels = bidirectional ? nullptr : options.kernels;
  RenderProgress progress;
  progress.samples_total = uint64_t(width) * uint64_t(height) * options.spp;

  const int threads = std::max(1, options.threads);
  // One wavefront per worker slot, kept over the tiles and passes that slot renders.
  std::vector<WavefrontWorkspace> workspaces(kernels != nullptr ? size_t(threads) : 0);
  const bool adaptive = options.adaptive.batch > 0 && options.distribution == nullptr;
  const uint32_t per_pass = PassSamples(options);
  // Adaptive sampling: which pixels go on, and their moments (those of the completed passes
  // in `moments_done`: an interrupted pass leaves them as they were).
  std::vector<uint8_t> active;
  std::vector<PixelMoments> moments, moments_done;
  PixelSampling pixel_sampling;
  if (adaptive) {
    active.assign(size_t(width) * size_t(height), 1);
    moments.assign(active.size(), PixelMoments{});
    moments_done = moments;
    pixel_sampling = {uint64_t(width), active.data(), moments.data()};
  }
  const PixelSampling* pixels = adaptive ? &pixel_sampling : nullptr;
  std::atomic<bool> start_failed{false};  // a worker thread could not be started
  auto cancelled = [&] {
    return start_failed.load() || (options.cancel && options.cancel->load());
  };

  const RenderDistribution* dist = options.distribution;
  double on_pass_seconds = 0;  // time spent in options.on_pass, left out of RenderPass::seconds
  double on_pass_cpu_seconds = 0;  // the same as CPU time, left out of RenderPass::cpu_seconds
  auto reset_block = [&](size_t i) {
    const Tile& t = tiles[i];
    blocks[i].Reset(
        t.x0 - border, t.y0 - border, t.x1 - t.x0 + 2 * border, t.y1 - t.y0 + 2 * border,
        std::span<float>(block_sums).subspan(block_first[i], block_first[i + 1] - block_first[i]));
    stats[i] = TileStats{};
  };
  // With a distribution every process enters every pass, so that all agree in finish_pass
  // whether it completed; a cancelled process takes no tiles.
  bool budget_spent = false;
  bool all_converged = false;  // adaptive sampling stopped every pixel
  auto over_budget = [&] {
    budget_spent = dist == nullptr && options.time_budget > 0 &&
                   std::chrono::duration<double>(Clock::now() - start).count() - on_pass_seconds >=
                       options.time_budget;
    return budget_spent;
  };
  for (uint32_t s0 = 0; s0 < options.spp && (dist != nullptr || !cancelled()) && !over_budget();
       s0 += per_pass) {
    const uint32_t s1 = std::min(options.spp, s0 + per_pass);
    const uint32_t pass = s0 / per_pass;
    std::atomic<size_t> next_tile{0};
    std::atomic<int> workers_running{threads};
    std::vector<uint8_t> rendered(tiles.size(), 0);
    std::mutex mutex;
    std::condition_variable worker_stopped;
    size_t tiles_done = 0;
    size_t next_splat_tile = 0;  // bidirectional: the tile whose splats go in next
    std::vector<uint8_t> splats_ready(bidirectional ? tiles.size() : 0, 0);
    if (bidirectional) light_pass->Clear();
    auto take_tile = [&] {
      return dist != nullptr ? dist->next_tile(pass, tiles.size()) : next_tile.fetch_add(1);
    };
    auto worker = [&](int slot) {
      for (;;) {
        if (cancelled()) break;
        const size_t i = take_tile();
        if (i >= tiles.size()) break;
        const Tile& t = tiles[i];
        const auto tile_start = Clock::now();
        reset_block(i);
        if (bidirectional) tile_splats[i].clear();
        // The tile's counters live on this thread's stack while it renders: stats[i] and the
        // stats of the tile another thread renders beside it share cache lines, and the
        // wavefront adds to them for every packet.
        TileStats tile_stats;
        tile_stats.time_stages = options.time_stages;
        if (bidirectional && options.kernels != nullptr) {
          // Batches of samples whose rays go through the table's packet traversal.
          RenderTileBidirectional(ctx, options.kernels, camera, filter, t.x0, t.y0, t.x1, t.y1,
                                  s0, s1, options.seed, &blocks[i], &tile_stats,
                                  *bidirectional_setup, &tile_splats[i]);
        } else if (kernels != nullptr) {
          RenderTilePacket8(ctx, *kernels, camera, filter, t.x0, t.y0, t.x1, t.y1, s0, s1,
                            options.seed, &blocks[i], &tile_stats, pixels,
                            &workspaces[size_t(slot)]);
        } else {
          RenderTileScalar(ctx, camera, filter, t.x0, t.y0, t.x1, t.y1, s0, s1, options.seed,
                           &blocks[i], &tile_stats, pixels,
                           bidirectional ? &*bidirectional_setup : nullptr,
                           bidirectional ? &tile_splats[i] : nullptr);
        }
        tile_stats.wall_seconds = std::chrono::duration<double>(Clock::now() - tile_start).count();
        stats[i] = tile_stats;
        std::lock_guard<std::mutex> lock(mutex);
        if (bidirectional) {
          // Splats join the light film in tile order, whatever order the tiles finish in.
          splats_ready[i] = 1;
          for (; next_splat_tile < tiles.size() && splats_ready[next_splat_tile];
               ++next_splat_tile) {
            std::vector<LightSplat>& list = tile_splats[next_splat_tile];
            for (const LightSplat& s : list) light_pass->Splat(s.sx, s.sy, s.value);
            std::vector<LightSplat>().swap(list);
          }
        }
        rendered[i] = 1;
        ++tiles_done;
        progress.samples_done += uint64_t(t.x1 - t.x0) * uint64_t(t.y1 - t.y0) * (s1 - s0);
        progress.rays += stats[i].rays;
        // No wake-up per tile: the coordinating thread reports progress every 200 ms and is
        // woken when the workers stop. A wake-up per tile cost a context switch per tile when
        // it shares the worker's CPU (taskset -c 0: 20 ms of a 1.8 s table render, 475 tiles).
      }
      std::lock_guard<std::mutex> lock(mutex);
      --workers_running;
      worker_stopped.notify_one();
    };
    std::vector<std::thread> pool;
    try {
      for (int i = 0; i < threads; ++i) pool.emplace_back(worker, i);
    } catch (const std::system_error& e) {
      // Out of memory for stacks or a process limit: stop the workers that did start.
      start_failed.store(true);
      result.error = "cannot start worker thread " + std::to_string(pool.size() + 1) + " of " +
                     std::to_string(threads) + " (" + e.what() + "); expected a thread count " +
                     "the system can run (--threads)";
      std::lock_guard<std::mutex> lock(mutex);
      workers_running -= threads - int(pool.size());  // those never ran
    }
    {
      // The coordinating thread reports progress while the workers run.
      std::unique_lock<std::mutex> lock(mutex);
      size_t reported = 0;
      // With a distribution this process renders only some tiles: wait for its workers.
      while (dist != nullptr ? workers_running > 0 : tiles_done < tiles.size()) {
        worker_stopped.wait_for(lock, std::chrono::milliseconds(200));
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
    if (dist != nullptr) {
      // Interrupted anywhere: the pass is incomplete everywhere, drop it.
      if (dist->keeps_film)
        for (size_t i = 0; i < tiles.size(); ++i)
          if (!rendered[i]) reset_block(i);  // filled by finish_pass from another process
      if (!dist->finish_pass(pass, !cancelled(), rendered, &blocks, &stats)) break;
      tiles_done = tiles.size();
      progress.samples_done = uint64_t(width) * uint64_t(height) * s1;
    }
    if (tiles_done < tiles.size()) break;  // interrupted: this pass is incomplete, drop it
    for (size_t i = 0; i < tiles.size() && (dist == nullptr || dist->keeps_film); ++i) {
      film.Merge(blocks[i]);
      result.rays += stats[i].rays;
      result.packets += stats[i].packets;
      result.stage_seconds += stats[i].seconds;
      result.tile_seconds.push_back(float(stats[i].wall_seconds));
      if (stats[i].nonfinite > 0 && result.nonfinite_samples == 0)
        result.first_nonfinite_x = stats[i].first_x, result.first_nonfinite_y = stats[i].first_y;
      result.nonfinite_samples += stats[i].nonfinite;
    }
    result.spp_done = s1;
    if (bidirectional) {
      light_total->Add(*light_pass);
      light_total->ComposeInto(film, s1, &composed);
    }
    const FilmBlock& seen = bidirectional ? composed : film;
    if (adaptive) {
      moments_done = moments;
      all_converged = true;
      for (size_t p = 0; p < active.size(); ++p) {
        if (active[p] && PixelConverged(moments[p], options.adaptive.tolerance)) active[p] = 0;
        all_converged &= active[p] == 0;
      }
    } else {
      result.samples_taken = uint64_t(width) * uint64_t(height) * s1;
    }
    if (options.on_pass && (dist == nullptr || dist->keeps_film)) {
      const auto pass_start = Clock::now();
      const double pass_cpu_start = ProcessCpuSeconds();
      RenderPass info;
      info.index = pass;
      info.spp_done = s1;
      info.seconds =
          std::chrono::duration<double>(pass_start - start).count() - on_pass_seconds;
      info.cpu_seconds = pass_cpu_start - cpu_start - on_pass_cpu_seconds;
      info.film = &seen;
      info.blocks = &blocks;
      info.pixels = adaptive ? &moments_done : nullptr;
      options.on_pass(info);
      on_pass_seconds += std::chrono::duration<double>(Clock::now() - pass_start).count();
      on_pass_cpu_seconds += ProcessCpuSeconds() - pass_cpu_start;
    }
    if (options.on_progress) {
      progress.seconds = std::chrono::duration<double>(Clock::now() - start).count();
      options.on_progress(progress);
    }
    if (all_converged) break;  // adaptive sampling: no pixel takes more samples
  }
  if (adaptive) {
    result.pixel_samples.resize(moments_done.size());
    for (size_t p = 0; p < moments_done.size(); ++p) {
      result.pixel_samples[p] = moments_done[p].taken;
      result.samples_taken += moments_done[p].taken;
    }
  }
  result.tile_count = int(tiles.size());
  for (const WavefrontWorkspace& w : workspaces) result.memory.wavefront += w.Bytes();
  result.memory.film = film.Bytes();
  result.memory.film += VectorBytes(block_sums);
  for (const FilmBlock& b : blocks) result.memory.film += b.Bytes();
  result.interrupted = result.spp_done < options.spp && !budget_spent && !all_converged;
  if (bidirectional) {
    // An interrupted pass's splats never joined light_total; the composed film holds the
    // completed passes (the camera's film alone when none completed).
    if (result.spp_done == 0) composed = film;
    result.image = composed.Resolve();
    result.memory.film += composed.Bytes() + 2 * light_total->sums().size() * sizeof(float);
  } else {
    result.image = film.Resolve();
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace ptlab
