// Every file ptlab reads (scenes, meshes, images, test files) is checked here before a byte is
// read: it must be a regular file (not a directory, FIFO or device such as /dev/zero, which
// would read forever or block) and no larger than kMaxInputFileBytes.
#pragma once

#include <sys/stat.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "engine/core/status.h"

namespace ptlab {

/// Largest input file ptlab reads: 2 GiB (a 10^7-triangle OBJ is about 0.6 GiB).
inline constexpr uint64_t kMaxInputFileBytes = uint64_t(1) << 31;

/// OK when `path` names a regular file of at most kMaxInputFileBytes; else
/// "path: cannot read <what>: <reason>". Stores the size in `*bytes`.
inline Status CheckInputFile(const std::string& path, const char* what, uint64_t* bytes) {
  const std::string prefix = path + ": cannot read " + what + ": ";
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return Status::Error(prefix + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) return Status::Error(prefix + "it is a directory");
  if (!S_ISREG(st.st_mode))
    return Status::Error(prefix + "it is not a regular file (a device, FIFO or socket)");
  if (uint64_t(st.st_size) > kMaxInputFileBytes)
    return Status::Error(prefix + "it holds " + std::to_string(uint64_t(st.st_size)) +
                         " bytes; expected at most " + std::to_string(kMaxInputFileBytes));
  *bytes = uint64_t(st.st_size);
  return Status::Ok();
}

/// Reads a whole regular file checked by CheckInputFile. The file may not grow past the
/// limit while it is read.
inline Status ReadInputFile(const std::string& path, const char* what, std::string* bytes) {
  uint64_t size = 0;
  PTLAB_RETURN_IF_ERROR(CheckInputFile(path, what, &size));
  const std::string prefix = path + ": cannot read " + what + ": ";
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return Status::Error(prefix + std::strerror(errno));
  bytes->clear();
  bytes->reserve(size_t(size));
  char buffer[1 << 16];
  size_t got = 0;
  bool too_big = false;
  while ((got = std::fread(buffer, 1, sizeof(buffer), file)) > 0) {
    if (bytes->size() + got > kMaxInputFileBytes) {
      too_big = true;
      break;
    }
    bytes->append(buffer, got);
  }
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (too_big) return Status::Error(prefix + "it grew past " + std::to_string(kMaxInputFileBytes) + " bytes while being read");
  if (failed) return Status::Error(prefix + "read error");
  return Status::Ok();
}

}  // namespace ptlab
