// One process among several started by mpirun: rank, size and the collective checks ptlab needs.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/status.h"

namespace ptlab::mpi {

/// True when ptlab was built with MPI and this process was started by an MPI launcher (mpirun
/// sets OMPI_COMM_WORLD_SIZE / PMIX_RANK); otherwise ptlab runs as one process without MPI.
bool LaunchedByMpi();

/// MPI for the lifetime of main(): initialised (threads serialised) only when launched by
/// mpirun, finalised on destruction; otherwise a session of one process.
class Session {
 public:
  Session(int* argc, char*** argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  bool active() const { return active_; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }

  /// Collective: OK on every process when every local status is OK; otherwise the same error on
  /// every process, naming each failing rank and its message.
  Status Agree(const Status& local) const;

  /// Collective: the root broadcasts the byte hash of each of its input files; a process whose
  /// list or bytes differ fails, and Agree() names it and the file.
  Status CheckSameInputs(const std::vector<std::string>& files) const;

  /// Collective: the root broadcasts its (option, value) pairs, the whole effective set of a
  /// run; a process whose pairs differ fails naming the first option whose value differs (its
  /// own value and rank 0's), and Agree() names the rank. Ranks that disagree on -s, -r, the
  /// seed or the sampler would render different passes and tiles (and hang or blend).
  Status CheckSameOptions(const std::vector<std::pair<std::string, std::string>>& options) const;

  /// Collective: runs items i with i % size == rank through `run` and returns, on the root, every
  /// item's text in item order (empty elsewhere).
  std::vector<std::string> MapInOrder(size_t count,
                                      const std::function<std::string(size_t)>& run) const;

 private:
  bool active_ = false;
  int rank_ = 0, size_ = 1;
};

}  // namespace ptlab::mpi
