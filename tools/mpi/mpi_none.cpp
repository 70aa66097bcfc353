// ptlab built without MPI: every session is one process, and a render share hands that process
// every tile, as the driver does on its own.
#include <atomic>
#include <vector>

#include "tools/mpi/mpi_render.h"
#include "tools/mpi/mpi_session.h"

namespace ptlab::mpi {

bool LaunchedByMpi() { return false; }

Session::Session(int*, char***) {}
Session::~Session() = default;
Status Session::Agree(const Status& local) const { return local; }
Status Session::CheckSameInputs(const std::vector<std::string>&) const { return Status::Ok(); }
Status Session::CheckSameOptions(const std::vector<std::pair<std::string, std::string>>&) const {
  return Status::Ok();
}
std::vector<std::string> Session::MapInOrder(size_t count,
                                             const std::function<std::string(size_t)>& run) const {
  std::vector<std::string> out;
  for (size_t i = 0; i < count; ++i) out.push_back(run(i));
  return out;
}

struct RenderShare::Window {
  std::vector<std::atomic<size_t>> counters;
};

RenderShare::RenderShare(const Session&, uint32_t passes) : window_(std::make_unique<Window>()) {
  window_->counters = std::vector<std::atomic<size_t>>(passes);
  Window* w = window_.get();
  distribution_.next_tile = [w](uint32_t pass, size_t) { return w->counters[pass].fetch_add(1); };
  distribution_.finish_pass = [](uint32_t, bool complete, const std::vector<uint8_t>&,
                                 std::vector<FilmBlock>*, std::vector<TileSampleStats>*) {
    return complete;
  };
}

RenderShare::~RenderShare() = default;

}  // namespace ptlab::mpi
