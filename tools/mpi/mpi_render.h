// Tiles of every pass shared among MPI ranks: a global tile counter per pass, blocks to rank 0.
#pragma once

#include <cstdint>
#include <memory>

#include "engine/render/render.h"
#include "tools/mpi/mpi_session.h"

namespace ptlab::mpi {

/// The RenderDistribution of a render over all ranks of `session`: workers of every rank take
/// tiles from one counter per pass that lives on rank 0 (MPI one-sided fetch-and-add, so a slow
/// tile never idles another rank), and after each pass every rank sends the blocks it rendered
/// to rank 0, which merges all of them in tile order: the image is bit-identical to a
/// one-process render of the same seed for any number of ranks and threads.
class RenderShare {
 public:
  RenderShare(const Session& session, uint32_t passes);
  ~RenderShare();
  RenderShare(const RenderShare&) = delete;
  RenderShare& operator=(const RenderShare&) = delete;

  const RenderDistribution& distribution() const { return distribution_; }

 private:
  struct Window;
  std::unique_ptr<Window> window_;
  RenderDistribution distribution_;
};

}  // namespace ptlab::mpi
