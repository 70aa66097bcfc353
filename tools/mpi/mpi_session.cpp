// MPI session of ptlab's processes (built when CMake finds MPI).
#include "tools/mpi/mpi_session.h"

#include <mpi.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string_view>

namespace ptlab::mpi {
namespace {

constexpr int kTagText = 101;

// Byte hash of a file's content (std::hash of the bytes: every rank runs the same binary).
bool HashFile(const std::string& path, uint64_t* hash) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  *hash = std::hash<std::string_view>{}(bytes) ^ (uint64_t(bytes.size()) * 0x9e3779b97f4a7c15ULL);
  return true;
}

void SendText(const std::string& text, int to) {
  MPI_Send(text.data(), int(text.size()), MPI_CHAR, to, kTagText, MPI_COMM_WORLD);
}

std::string ReceiveText(int from) {
  MPI_Status status;
  MPI_Probe(from, kTagText, MPI_COMM_WORLD, &status);
  int count = 0;
  MPI_Get_count(&status, MPI_CHAR, &count);
  std::string text(size_t(count), '\0');
  MPI_Recv(text.data(), count, MPI_CHAR, from, kTagText, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return text;
}

// Root's copy of text to every rank.
std::string Broadcast(std::string text) {
  uint64_t n = text.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  text.resize(n);
  MPI_Bcast(text.data(), int(n), MPI_CHAR, 0, MPI_COMM_WORLD);
  return text;
}

}  // namespace

bool LaunchedByMpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr ||
         std::getenv("PMI_RANK") != nullptr;
}

Session::Session(int* argc, char*** argv) {
  if (!LaunchedByMpi()) return;
  int provided = 0;
  // Worker threads take tiles through one-sided calls, one thread at a time (mpi_render.cpp).
  MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided);
  active_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  if (provided < MPI_THREAD_SERIALIZED) {
    if (root()) std::fprintf(stderr, "error: this MPI does not support MPI_THREAD_SERIALIZED\n");
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
}

Session::~Session() {
  if (active_) MPI_Finalize();
}

Status Session::Agree(const Status& local) const {
  if (!active_) return local;
  int ok = local.ok() ? 1 : 0, all_ok = 0;
  MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (all_ok) return Status::Ok();
  // Every rank learns who failed and why, so that each exits with the same message.
  std::string report;
  if (root()) {
    if (!ok) report += "rank 0: " + local.message();
    for (int r = 1; r < size_; ++r) {
      const std::string m = ReceiveText(r);
      if (m.empty()) continue;
      if (!report.empty()) report += "\n";
      report += "rank " + std::to_string(r) + ": " + m;
    }
  } else {
    SendText(ok ? std::string() : local.message(), 0);
  }
  return Status::Error(Broadcast(report));
}

Status Session::CheckSameInputs(const std::vector<std::string>& files) const {
  if (!active_) return Status::Ok();
  std::string mine;  // "hash path\n" per file
  Status local;
  for (const std::string& f : files) {
    uint64_t h = 0;
    if (!HashFile(f, &h) && local.ok())
      local = Status::Error(f + ": cannot read it to compare its bytes");
    mine += std::to_string(h) + " " + f + "\n";
  }
  const std::string roots = Broadcast(root() ? mine : std::string());
  if (local.ok() && roots != mine) {
    // Name the first file whose line differs.
    size_t a = 0, b = 0;
    std::string which = "the list of input files differs from rank 0's";
    while (a < roots.size() && b < mine.size()) {
      const size_t ea = roots.find('\n', a), eb = mine.find('\n', b);
      const std::string la = roots.substr(a, ea - a), lb = mine.substr(b, eb - b);
      if (la != lb) {
        which = lb.substr(lb.find(' ') + 1) + ": its bytes differ from rank 0's copy (" +
                la.substr(la.find(' ') + 1) + "); every rank must read the same scene files";
        break;
      }
      a = ea + 1, b = eb + 1;
    }
    local = Status::Error(which);
  }
  return Agree(local);
}

Status Session::CheckSameOptions(
    const std::vector<std::pair<std::string, std::string>>& options) const {
  if (!active_) return Status::Ok();
  // "name\tvalue\n" per option; values keep their bytes (a tab or newline in one changes the
  // text and so is a difference too).
  std::string mine;
  for (const auto& [name, value] : options) mine += name + "\t" + value + "\n";
  const std::string roots = Broadcast(root() ? mine : std::string());
  Status local;
  if (roots != mine) {
    std::string which = "its list of options differs from rank 0's";
    for (const auto& [name, value] : options) {
      const std::string key = name + "\t";
      size_t at = roots.find("\n" + key);
      at = roots.compare(0, key.size(), key) == 0 ? 0 : (at == std::string::npos ? at : at + 1);
      const std::string theirs =
          at == std::string::npos
              ? std::string("(none)")
              : roots.substr(at + key.size(), roots.find('\n', at) - at - key.size());
      if (theirs != value) {
        which = "option " + name + " is '" + value + "' here but '" + theirs +
                "' on rank 0; every rank must run with the same options";
        break;
      }
    }
    local = Status::Error(which);
  }
  return Agree(local);
}

std::vector<std::string> Session::MapInOrder(size_t count,
                                             const std::function<std::string(size_t)>& run) const {
  std::vector<std::string> out;
  if (!active_) {
    for (size_t i = 0; i < count; ++i) out.push_back(run(i));
    return out;
  }
  std::vector<std::string> mine;
  for (size_t i = size_t(rank_); i < count; i += size_t(size_)) mine.push_back(run(i));
  if (!root()) {
    for (const std::string& text : mine) SendText(text, 0);
    return out;
  }
  out.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const int owner = int(i % size_t(size_));
    out[i] = owner == 0 ? std::move(mine[i / size_t(size_)]) : ReceiveText(owner);
  }
  return out;
}

}  // namespace ptlab::mpi
