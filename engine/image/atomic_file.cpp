// Atomic output files (engine/image/atomic_file.h).
#include "engine/image/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace ptlab {
namespace {

namespace fs = std::filesystem;

void RemoveTemporary(const std::string& tmp) {
  std::error_code ec;
  // Only a regular file (ours); never a directory or something else that happens to be there.
  if (fs::is_regular_file(fs::symlink_status(tmp, ec))) fs::remove(tmp, ec);
}

Status WriteTemporary(const std::string& tmp, std::string_view bytes) {
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) return Status::Error("cannot create " + tmp + ": " + std::strerror(errno));
  const size_t written = std::fwrite(bytes.data(), 1, bytes.size(), f);
  const int write_errno = errno;
  const bool flushed = std::fflush(f) == 0;
  const int flush_errno = errno;
  const bool closed = std::fclose(f) == 0;
  if (written != bytes.size()) {
    return Status::Error("cannot write " + tmp + ": " + std::strerror(write_errno));
  }
  if (!flushed || !closed) {
    return Status::Error("cannot write " + tmp + ": " +
                         std::strerror(flush_errno ? flush_errno : errno));
  }
  return Status::Ok();
}

}  // namespace

Status WriteFileAtomically(const std::string& path, std::string_view bytes) {
  if (path.empty()) return Status::Error("WriteFileAtomically: empty output path");
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  Status s = WriteTemporary(tmp, bytes);
  if (!s.ok()) {
    RemoveTemporary(tmp);
    return Status::Error(path + ": " + s.message());
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    RemoveTemporary(tmp);
    return Status::Error(path + ": cannot rename " + tmp + " into place: " + ec.message());
  }
  return Status::Ok();
}

namespace {
// The pid of a temporary "<name>.tmp-<pid>" of `name`, or 0.
pid_t TemporaryPid(const std::string& file, const std::string& name) {
  const std::string prefix = name + ".tmp-";
  if (file.rfind(prefix, 0) != 0 || file.size() == prefix.size()) return 0;
  long pid = 0;
  for (size_t i = prefix.size(); i < file.size(); ++i) {
    if (!std::isdigit(uint8_t(file[i])) || pid > 1000000000L) return 0;
    pid = pid * 10 + (file[i] - '0');
  }
  return pid_t(pid);
}
}  // namespace

Status PrepareOutputFile(const std::string& path) {
  if (path.empty()) return Status::Error("output path is empty; expected a file name");
  const fs::path p(path);
  if (!p.has_filename()) return Status::Error(path + ": output path names a directory; expected a file");
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    return Status::Error(path + ": output directory '" + dir.string() + "' does not exist");
  if (fs::is_directory(p, ec)) return Status::Error(path + ": output path is a directory");
  const std::string name = p.filename().string();
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const pid_t pid = TemporaryPid(it->path().filename().string(), name);
    if (pid > 0 && pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH)
      RemoveTemporary(it->path().string());  // a stale temporary of a dead process
  }
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  std::FILE* f = std::fopen(tmp.c_str(), "wbx");
  if (f == nullptr)
    return Status::Error(path + ": cannot write beside the output (" + std::strerror(errno) +
                         "); expected a writable directory");
  std::fclose(f);
  RemoveTemporary(tmp);
  return Status::Ok();
}
}  // namespace ptlab
