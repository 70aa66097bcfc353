// Reads a text input file line by line without loading it whole: the file is checked first
// (a regular file within kMaxInputFileBytes: no FIFO, device or directory), and a line longer
// than a cap is an error instead of a buffer that grows until memory runs out.
#pragma once

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>

#include "engine/core/input_file.h"
#include "engine/core/status.h"

namespace ptlab {

class LineReader {
 public:
  /// Longest line accepted by default, in bytes (without its '\n').
  static constexpr size_t kDefaultMaxLineBytes = 1 << 16;

  LineReader() = default;
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;
  ~LineReader() {
    if (file_ != nullptr) std::fclose(file_);
  }

  /// Opens `path` after CheckInputFile; `what` names the file's role in messages.
  Status Open(const std::string& path, const char* what,
              size_t max_line_bytes = kDefaultMaxLineBytes) {
    path_ = path;
    what_ = what;
    max_line_bytes_ = max_line_bytes;
    uint64_t bytes = 0;
    PTLAB_RETURN_IF_ERROR(CheckInputFile(path, what, &bytes));
    file_ = std::fopen(path.c_str(), "rb");
    if (file_ == nullptr)
      return Status::Error(path + ": cannot read " + what + ": " + std::strerror(errno));
    return Status::Ok();
  }

  /// The next line (without '\n'; a "\r\n" ending loses its '\r' too) in *line; false at the
  /// end of the file or on an error (then status() says which). line_number() is its number.
  bool Next(std::string_view* line) {
    if (file_ == nullptr || !status_.ok()) return false;
    line_.clear();
    bool any = false;
    while (true) {
      if (pos_ == end_) {
        end_ = std::fread(buffer_, 1, sizeof buffer_, file_);
        pos_ = 0;
        if (end_ == 0) {
          if (std::ferror(file_)) status_ = Status::Error(path_ + ": cannot read " + what_ + ": read error");
          if (!any) return false;
          break;
        }
        total_ += end_;
        if (total_ > kMaxInputFileBytes) {
          status_ = Status::Error(path_ + ": cannot read " + what_ + ": it grew past " +
                                  std::to_string(kMaxInputFileBytes) + " bytes while being read");
          return false;
        }
      }
      any = true;
      const char* start = buffer_ + pos_;
      const void* nl = std::memchr(start, '\n', end_ - pos_);
      const size_t take = nl ? size_t(static_cast<const char*>(nl) - start) : end_ - pos_;
      if (line_.size() + take > max_line_bytes_) {
        status_ = Status::Error(path_ + ":" + std::to_string(line_number_ + 1) + ": line longer than " +
                                std::to_string(max_line_bytes_) + " bytes in " + what_);
        return false;
      }
      line_.append(start, take);
      pos_ += take;
      if (nl) {
        ++pos_;
        break;
      }
    }
    ++line_number_;
    if (!line_.empty() && line_.back() == '\r') line_.pop_back();
    *line = line_;
    return true;
  }

  /// Reads up to `bytes` raw bytes into `out` (for binary files); returns how many it read.
  size_t Read(char* out, size_t bytes) {
    size_t got = 0;
    while (got < bytes && file_ != nullptr) {
      if (pos_ == end_) {
        end_ = std::fread(buffer_, 1, sizeof buffer_, file_);
        pos_ = 0;
        if (end_ == 0) break;
        total_ += end_;
        if (total_ > kMaxInputFileBytes) {
          status_ = Status::Error(path_ + ": cannot read " + what_ + ": it grew past " +
                                  std::to_string(kMaxInputFileBytes) + " bytes while being read");
          break;
        }
      }
      const size_t take = std::min(bytes - got, end_ - pos_);
      std::memcpy(out + got, buffer_ + pos_, take);
      pos_ += take;
      got += take;
    }
    return got;
  }

  int64_t line_number() const { return line_number_; }
  /// Bytes read from the file so far.
  uint64_t bytes_read() const { return total_; }
  const Status& status() const { return status_; }
  const std::string& path() const { return path_; }

 private:
  std::FILE* file_ = nullptr;
  std::string path_, what_;
  size_t max_line_bytes_ = kDefaultMaxLineBytes;
  char buffer_[1 << 16];
  size_t pos_ = 0, end_ = 0;
  uint64_t total_ = 0;
  int64_t line_number_ = 0;
  std::string line_;
  Status status_;
};

}  // namespace ptlab
