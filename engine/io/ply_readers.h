// Readers of a PLY body's values: whitespace-separated ASCII numbers (tracking the line) and
// packed binary values in either byte order, both range-checked against the property's type.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "engine/io/ply_header.h"

namespace ptlab::ply {

// Reads whitespace-separated numbers, tracking the line.
class AsciiReader {
 public:
  AsciiReader(const std::string& bytes, size_t pos, int line, const std::string& name)
      : s_(bytes), pos_(pos), line_(line), name_(name) {}
  bool Read(PlyType t, double* v) {
    while (pos_ < s_.size() &&
           (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\r' || s_[pos_] == '\n')) {
      if (s_[pos_] == '\n') ++line_;
      ++pos_;
    }
    const size_t start = pos_;
    while (pos_ < s_.size() && s_[pos_] != ' ' && s_[pos_] != '\t' && s_[pos_] != '\r' &&
           s_[pos_] != '\n')
      ++pos_;
    token_ = std::string_view(s_.data() + start, pos_ - start);
    if (token_.empty()) return false;
    std::string_view tok = token_;
    if (tok[0] == '+') tok.remove_prefix(1);
    const char* end = tok.data() + tok.size();
    if (IsInteger(t)) {
      int64_t i = 0;
      if (std::from_chars(tok.data(), end, i).ptr != end || tok.empty()) return false;
      const double lo = (t == PlyType::kInt8 || t == PlyType::kInt16 || t == PlyType::kInt32)
                            ? -TypeMax(t) - 1.0
                            : 0.0;
      if (double(i) < lo || double(i) > TypeMax(t)) return false;
      *v = double(i);
      return true;
    }
    double d = 0;
    if (std::from_chars(tok.data(), end, d).ptr != end || tok.empty() || !std::isfinite(d))
      return false;
    if (t == PlyType::kFloat32) d = double(float(d));
    *v = d;
    return true;
  }
  uint64_t Remaining() const { return s_.size() - pos_; }
  // A row of k values takes at least 2k - 1 bytes ("1 2 3").
  uint64_t MinRowBytes(const Element& e) const { return e.props.size(); }
  std::string Where() const { return name_ + ":" + std::to_string(line_); }
  std::string Found() const {
    return token_.empty() ? "found the end of the file"
                          : "found '" + std::string(token_.substr(0, 40)) + "'";
  }
  bool AtEnd() {
    while (pos_ < s_.size() &&
           (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\r' || s_[pos_] == '\n')) {
      if (s_[pos_] == '\n') ++line_;
      ++pos_;
    }
    return pos_ == s_.size();
  }

 private:
  const std::string& s_;
  size_t pos_;
  int line_;
  const std::string& name_;
  std::string_view token_;
};

// Reads packed binary values in either byte order.
class BinaryReader {
 public:
  BinaryReader(const std::string& bytes, size_t pos, bool big_endian, const std::string& name)
      : s_(bytes), pos_(pos), big_(big_endian), name_(name) {}
  bool Read(PlyType t, double* v) {
    const size_t n = TypeSize(t);
    last_ = pos_;
    if (s_.size() - pos_ < n) return false;
    unsigned char b[8];
    std::memcpy(b, s_.data() + pos_, n);
    pos_ += n;
    if (big_) {
      for (size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    }
    switch (t) {
      case PlyType::kInt8: {
        int8_t x;
        std::memcpy(&x, b, 1);
        *v = x;
        break;
      }
      case PlyType::kUInt8:
        *v = b[0];
        break;
      case PlyType::kInt16: {
        int16_t x;
        std::memcpy(&x, b, 2);
        *v = x;
        break;
      }
      case PlyType::kUInt16: {
        uint16_t x;
        std::memcpy(&x, b, 2);
        *v = x;
        break;
      }
      case PlyType::kInt32: {
        int32_t x;
        std::memcpy(&x, b, 4);
        *v = x;
        break;
      }
      case PlyType::kUInt32: {
        uint32_t x;
        std::memcpy(&x, b, 4);
        *v = x;
        break;
      }
      case PlyType::kFloat32: {
        float x;
        std::memcpy(&x, b, 4);
        *v = x;
        break;
      }
      case PlyType::kFloat64: {
        double x;
        std::memcpy(&x, b, 8);
        *v = x;
        break;
      }
    }
    return true;
  }
  uint64_t Remaining() const { return s_.size() - pos_; }
  uint64_t MinRowBytes(const Element& e) const {
    uint64_t n = 0;
    for (const Property& p : e.props) n += TypeSize(p.list ? p.count_type : p.type);
    return n;
  }
  std::string Where() const { return name_ + ": byte " + std::to_string(last_); }
  std::string Found() const { return "found the end of the file"; }
  bool AtEnd() const { return pos_ == s_.size(); }

 private:
  const std::string& s_;
  size_t pos_, last_ = 0;
  bool big_;
  const std::string& name_;
};

}  // namespace ptlab::ply
