// Stanford PLY header: the format line, the elements and their properties, and the scalar types
// of the body's values.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/status.h"

namespace ptlab::ply {

enum class PlyType { kInt8, kUInt8, kInt16, kUInt16, kInt32, kUInt32, kFloat32, kFloat64 };

/// Bytes of one value of type t in a binary body.
size_t TypeSize(PlyType t);
inline bool IsInteger(PlyType t) { return t != PlyType::kFloat32 && t != PlyType::kFloat64; }
/// Largest value of an integer type (the divisor of Mitsuba's normalised integer properties).
double TypeMax(PlyType t);
/// The type's name as PLY spells it (for messages).
const char* TypeName(PlyType t);

struct Property {
  std::string name;
  PlyType type = PlyType::kFloat32;
  bool list = false;
  PlyType count_type = PlyType::kUInt8;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;
  int line = 0;
};

struct Header {
  enum class Format { kAscii, kBinaryLittle, kBinaryBig } format = Format::kAscii;
  std::vector<Element> elements;
  size_t body_offset = 0;  // first byte after the end_header line
  int body_line = 1;       // line number of that byte
};

/// Parses the header of a PLY file's bytes (`name` names it in messages): "ply", the format
/// line (ascii, binary_little_endian or binary_big_endian 1.0), the elements and properties,
/// up to end_header.
StatusOr<Header> ParseHeader(const std::string& bytes, const std::string& name);

}  // namespace ptlab::ply
