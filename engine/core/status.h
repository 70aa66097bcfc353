// Status and StatusOr<T>: how loaders, parsers, file I/O and tools report errors.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "engine/core/check.h"

namespace ptlab {

/// Ok, or an error message that names the file, the line and what was expected.
class Status {
 public:
  Status() = default;
  static Status Ok() { return Status(); }
  static Status Error(std::string message) {
    Status s;
    s.ok_ = false;
    s.message_ = std::move(message);
    return s;
  }
  bool ok() const { return ok_; }
  const std::string& message() const { return message_; }

 private:
  bool ok_ = true;
  std::string message_;
};

/// A value or the Status that explains why there is none.
template <typename T>
class StatusOr {
 public:
  StatusOr(T value) : value_(std::move(value)) {}
  StatusOr(Status status) : status_(std::move(status)) { PTLAB_CHECK(!status_.ok()); }

  bool ok() const { return status_.ok(); }
  const Status& status() const { return status_; }
  T& value() { PTLAB_CHECK(ok()); return *value_; }
  const T& value() const { PTLAB_CHECK(ok()); return *value_; }
  T& operator*() { return value(); }
  const T& operator*() const { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

 private:
  Status status_;
  std::optional<T> value_;
};

}  // namespace ptlab

/// Returns early from the enclosing function with the error of `expr`, if any.
#define PTLAB_RETURN_IF_ERROR(expr)              \
  do {                                           \
    ::ptlab::Status ptlab_status_ = (expr);      \
    if (!ptlab_status_.ok()) return ptlab_status_; \
  } while (0)
