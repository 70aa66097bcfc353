// Tiles of every pass shared among MPI ranks (built when CMake finds MPI).
#include "tools/mpi/mpi_render.h"

#include <mpi.h>

#include <cstdio>
#include <mutex>
#include <span>
#include <type_traits>
#include <vector>

namespace ptlab::mpi {
namespace {

constexpr int kTagTiles = 201, kTagSums = 202, kTagStats = 203;
static_assert(std::is_trivially_copyable_v<TileSampleStats>);

}  // namespace

struct RenderShare::Window {
  MPI_Win win = MPI_WIN_NULL;
  int64_t* counters = nullptr;  // one per pass, on rank 0
  // Threads of a rank call MPI one at a time (the session asks for MPI_THREAD_SERIALIZED).
  std::mutex mutex;
};

RenderShare::RenderShare(const Session& session, uint32_t passes)
    : window_(std::make_unique<Window>()) {
  const MPI_Aint bytes = session.root() ? MPI_Aint(passes) * MPI_Aint(sizeof(int64_t)) : 0;
  MPI_Win_allocate(bytes, sizeof(int64_t), MPI_INFO_NULL, MPI_COMM_WORLD, &window_->counters,
                   &window_->win);
  if (session.root())
    for (uint32_t p = 0; p < passes; ++p) window_->counters[p] = 0;
  MPI_Barrier(MPI_COMM_WORLD);  // counters are zero before any rank takes a tile

  Window* w = window_.get();
  distribution_.keeps_film = session.root();
  distribution_.next_tile = [w](uint32_t pass, size_t) {
    const int64_t one = 1;
    int64_t taken = 0;
    std::lock_guard<std::mutex> lock(w->mutex);
    MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, w->win);
    MPI_Fetch_and_op(&one, &taken, MPI_INT64_T, 0, MPI_Aint(pass), MPI_SUM, w->win);
    MPI_Win_unlock(0, w->win);
    return size_t(taken);
  };
  const int ranks = session.size();
  const bool root = session.root();
  distribution_.finish_pass = [ranks, root](uint32_t, bool complete,
                                            const std::vector<uint8_t>& rendered,
                                            std::vector<FilmBlock>* blocks,
                                            std::vector<TileSampleStats>* stats) {
    int ok = complete ? 1 : 0, all_ok = 0;
    MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (!all_ok) return false;
    if (!root) {
      // The tiles this rank rendered, then their sums and stats, each as one message.
      std::vector<uint64_t> tiles;
      std::vector<float> sums;
      std::vector<TileSampleStats> tile_stats;
      for (size_t i = 0; i < rendered.size(); ++i) {
        if (!rendered[i]) continue;
        tiles.push_back(i);
        sums.insert(sums.end(), (*blocks)[i].sums().begin(), (*blocks)[i].sums().end());
        tile_stats.push_back((*stats)[i]);
      }
      MPI_Send(tiles.data(), int(tiles.size()), MPI_UINT64_T, 0, kTagTiles, MPI_COMM_WORLD);
      MPI_Send(sums.data(), int(sums.size()), MPI_FLOAT, 0, kTagSums, MPI_COMM_WORLD);
      MPI_Send(tile_stats.data(), int(tile_stats.size() * sizeof(TileSampleStats)), MPI_BYTE, 0,
               kTagStats, MPI_COMM_WORLD);
      return true;
    }
    for (int r = 1; r < ranks; ++r) {
      MPI_Status status;
      MPI_Probe(r, kTagTiles, MPI_COMM_WORLD, &status);
      int n = 0;
      MPI_Get_count(&status, MPI_UINT64_T, &n);
      std::vector<uint64_t> tiles(size_t(n), 0);
      MPI_Recv(tiles.data(), n, MPI_UINT64_T, r, kTagTiles, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      // Every tile number a rank sends must name one of rank 0's tiles, once, in order: ranks
      // whose film or tiles differ (which the options check should have stopped) end the run
      // here instead of writing outside rank 0's arrays.
      for (size_t k = 0; k < tiles.size(); ++k) {
        if (tiles[k] < blocks->size() && (k == 0 || tiles[k] > tiles[k - 1])) continue;
        std::fprintf(stderr,
                     "error: rank %d sent tile %llu, but rank 0's film has %zu tiles (or it "
                     "repeated a tile); every rank must render the same film and tiles\n",
                     r, static_cast<unsigned long long>(tiles[k]), blocks->size());
        MPI_Abort(MPI_COMM_WORLD, 2);
      }
      size_t floats = 0;
      for (const uint64_t i : tiles) floats += (*blocks)[i].sums().size();
      MPI_Status sums_status;
      MPI_Probe(r, kTagSums, MPI_COMM_WORLD, &sums_status);
      int sent = 0;
      MPI_Get_count(&sums_status, MPI_FLOAT, &sent);
      if (size_t(sent) != floats) {
        std::fprintf(stderr,
                     "error: rank %d sent %d film values for its %zu tiles, rank 0 expects %zu; "
                     "every rank must render the same film\n",
                     r, sent, tiles.size(), floats);
        MPI_Abort(MPI_COMM_WORLD, 2);
      }
      std::vector<float> sums(floats);
      std::vector<TileSampleStats> tile_stats(tiles.size());
      MPI_Recv(sums.data(), int(floats), MPI_FLOAT, r, kTagSums, MPI_COMM_WORLD,
               MPI_STATUS_IGNORE);
      MPI_Recv(tile_stats.data(), int(tile_stats.size() * sizeof(TileSampleStats)), MPI_BYTE, r,
               kTagStats, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      size_t at = 0;
      for (size_t k = 0; k < tiles.size(); ++k) {
        const std::span<float> dst = (*blocks)[tiles[k]].sums();
        std::copy(sums.begin() + long(at), sums.begin() + long(at + dst.size()), dst.begin());
        at += dst.size();
        (*stats)[tiles[k]] = tile_stats[k];
      }
    }
    return true;
  };
}

RenderShare::~RenderShare() {
  if (window_->win != MPI_WIN_NULL) MPI_Win_free(&window_->win);
}

}  // namespace ptlab::mpi
