// The output guard of ptlab's tools (see output_guard.h).
#include "tools/common/output_guard.h"

#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "engine/image/image_io.h"
#include "tools/common/exit_codes.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;

// Room for the ".tmp-<pid>" suffix of WriteFileAtomically's temporary (pid < 2^22 on Linux,
// but any 32-bit pid fits 10 digits).
constexpr size_t kTemporarySuffixBytes = 5 + 10;

// How a path is identified: its device and inode when it exists, and its resolved path
// (symbolic links and "..", "." removed, as far as they exist).
struct FileId {
  bool exists = false;
  dev_t dev = 0;
  ino_t ino = 0;
  std::string resolved;
};

FileId Identify(const std::string& path) {
  FileId id;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    id.exists = true;
    id.dev = st.st_dev;
    id.ino = st.st_ino;
  }
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(fs::path(path), ec);
  id.resolved = ec ? fs::absolute(fs::path(path), ec).lexically_normal().string()
                   : resolved.string();
  return id;
}

bool SameFile(const FileId& a, const FileId& b) {
  if (a.exists && b.exists) return a.dev == b.dev && a.ino == b.ino;
  return !a.resolved.empty() && a.resolved == b.resolved;
}

std::string Named(const std::string& path, const std::string& role) {
  return "'" + path + "' (" + role + ")";
}

}  // namespace

void OutputGuard::AddInput(const std::string& path, const std::string& role) {
  if (!path.empty()) inputs_.push_back({path, role});
}

void OutputGuard::AddInputs(const std::vector<std::string>& paths, const std::string& role) {
  for (const std::string& p : paths) AddInput(p, role);
}

void OutputGuard::AddOutput(const std::string& path, const std::string& role) {
  if (!path.empty()) outputs_.push_back({path, role});
}

Status OutputGuard::CheckPaths() const {
  // Names first: std::filesystem and the temporary's fopen fail on names past the limits.
  for (const Entry& out : outputs_) {
    const size_t slash = out.path.find_last_of('/');
    const size_t name = slash == std::string::npos ? out.path.size() : out.path.size() - slash - 1;
    if (name == 0)
      return Status::Error("output " + Named(out.path, out.role) +
                           " names a directory; expected a file name");
    if (name + kTemporarySuffixBytes > NAME_MAX)
      return Status::Error("output " + Named(out.path.substr(0, 80) + "...", out.role) +
                           ": its file name has " + std::to_string(name) +
                           " bytes; expected at most " +
                           std::to_string(NAME_MAX - kTemporarySuffixBytes) + " (NAME_MAX " +
                           std::to_string(NAME_MAX) + " less the temporary's suffix)");
    if (out.path.size() + kTemporarySuffixBytes >= PATH_MAX)
      return Status::Error("output " + Named(out.path.substr(0, 80) + "...", out.role) +
                           ": the path has " + std::to_string(out.path.size()) +
                           " bytes; expected fewer than " +
                           std::to_string(PATH_MAX - kTemporarySuffixBytes) + " (PATH_MAX " +
                           std::to_string(PATH_MAX) + " less the temporary's suffix)");
  }
  std::vector<FileId> in_ids, out_ids;
  for (const Entry& in : inputs_) in_ids.push_back(Identify(in.path));
  for (const Entry& out : outputs_) out_ids.push_back(Identify(out.path));
  for (size_t o = 0; o < outputs_.size(); ++o) {
    struct stat st {};
    if (::stat(outputs_[o].path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
      return Status::Error("output " + Named(outputs_[o].path, outputs_[o].role) +
                           " is a directory; expected a file name");
    for (size_t i = 0; i < inputs_.size(); ++i)
      if (SameFile(out_ids[o], in_ids[i]))
        return Status::Error("output " + Named(outputs_[o].path, outputs_[o].role) +
                             " is the same file as the input " +
                             Named(inputs_[i].path, inputs_[i].role) +
                             "; refusing to overwrite an input: choose another output name");
    for (size_t p = 0; p < o; ++p)
      if (SameFile(out_ids[o], out_ids[p]))
        return Status::Error("outputs " + Named(outputs_[p].path, outputs_[p].role) + " and " +
                             Named(outputs_[o].path, outputs_[o].role) +
                             " are the same file; expected a different name for each");
  }
  return Status::Ok();
}

Status OutputGuard::ProbeOutputs() const {
  for (const Entry& out : outputs_) {
    const Status st = PrepareOutputFile(out.path);
    if (!st.ok()) return Status::Error(out.role + ": " + st.message());
  }
  return Status::Ok();
}

int OutputGuard::Check(std::string* error) const {
  Status st = CheckPaths();
  if (!st.ok()) {
    *error = st.message();
    return kExitUsage;
  }
  st = ProbeOutputs();
  if (!st.ok()) {
    *error = st.message();
    return kExitRunFailed;
  }
  return kExitOk;
}

int PrepareOutputFolder(const std::string& folder, std::string* error) {
  if (folder.empty()) {
    *error = "the output folder is empty; expected a folder name";
    return kExitUsage;
  }
  if (folder.size() + 64 >= PATH_MAX) {
    *error = "output folder '" + folder.substr(0, 80) + "...' has " +
             std::to_string(folder.size()) + " bytes; expected fewer than " +
             std::to_string(PATH_MAX - 64) + " (PATH_MAX " + std::to_string(PATH_MAX) +
             " less room for the files in it)";
    return kExitUsage;
  }
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec || !fs::is_directory(folder, ec)) {
    *error = "cannot create the output folder '" + folder + "'" +
             (ec ? ": " + ec.message() : std::string());
    return kExitRunFailed;
  }
  const std::string probe = (fs::path(folder) / ".ptlab-probe").string();
  const Status st = PrepareOutputFile(probe);
  if (!st.ok()) {
    *error = "output folder '" + folder + "': " + st.message();
    return kExitRunFailed;
  }
  return kExitOk;
}

}  // namespace ptlab
