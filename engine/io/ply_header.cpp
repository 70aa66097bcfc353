// Stanford PLY header parsing and scalar types (ply_header.h).
#include "engine/io/ply_header.h"

#include <charconv>
#include <utility>

#include "engine/core/input_file.h"

namespace ptlab::ply {
namespace {

bool ParsePlyType(std::string_view s, PlyType* t) {
  static constexpr std::pair<std::string_view, PlyType> kNames[] = {
      {"char", PlyType::kInt8},      {"int8", PlyType::kInt8},       {"uchar", PlyType::kUInt8},
      {"uint8", PlyType::kUInt8},    {"short", PlyType::kInt16},     {"int16", PlyType::kInt16},
      {"ushort", PlyType::kUInt16},  {"uint16", PlyType::kUInt16},   {"int", PlyType::kInt32},
      {"int32", PlyType::kInt32},    {"uint", PlyType::kUInt32},     {"uint32", PlyType::kUInt32},
      {"float", PlyType::kFloat32},  {"float32", PlyType::kFloat32}, {"double", PlyType::kFloat64},
      {"float64", PlyType::kFloat64}};
  for (const auto& [name, type] : kNames) {
    if (s == name) {
      *t = type;
      return true;
    }
  }
  return false;
}

std::vector<std::string_view> Tokens(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

}  // namespace

size_t TypeSize(PlyType t) {
  switch (t) {
    case PlyType::kInt8:
    case PlyType::kUInt8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUInt16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUInt32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 8;
}


// Largest value of an integer type (the divisor of Mitsuba's normalised integer properties).
double TypeMax(PlyType t) {
  switch (t) {
    case PlyType::kInt8:
      return 127.0;
    case PlyType::kUInt8:
      return 255.0;
    case PlyType::kInt16:
      return 32767.0;
    case PlyType::kUInt16:
      return 65535.0;
    case PlyType::kInt32:
      return 2147483647.0;
    case PlyType::kUInt32:
      return 4294967295.0;
    case PlyType::kFloat32:
    case PlyType::kFloat64:
      return 1.0;
  }
  return 1.0;
}

const char* TypeName(PlyType t) {
  switch (t) {
    case PlyType::kInt8:
      return "char";
    case PlyType::kUInt8:
      return "uchar";
    case PlyType::kInt16:
      return "short";
    case PlyType::kUInt16:
      return "ushort";
    case PlyType::kInt32:
      return "int";
    case PlyType::kUInt32:
      return "uint";
    case PlyType::kFloat32:
      return "float";
    case PlyType::kFloat64:
      return "double";
  }
  return "?";
}

StatusOr<Header> ParseHeader(const std::string& bytes, const std::string& name) {
  Header h;
  size_t pos = 0;
  int line_no = 0;
  bool have_format = false;
  while (true) {
    ++line_no;
    const std::string where = name + ":" + std::to_string(line_no) + ": ";
    if (pos >= bytes.size())
      return Status::Error(where + "expected 'end_header', found the end of the file");
    const size_t eol = bytes.find('\n', pos);
    if (eol == std::string::npos)
      return Status::Error(where + "expected 'end_header', found the end of the file");
    const std::string_view line(bytes.data() + pos, eol - pos);
    pos = eol + 1;
    const std::vector<std::string_view> t = Tokens(line);
    if (line_no == 1) {
      if (t.size() != 1 || t[0] != "ply")
        return Status::Error(where + "expected 'ply' (the PLY magic line)");
      continue;
    }
    if (t.empty()) return Status::Error(where + "expected a header line, found an empty line");
    const std::string_view key = t[0];
    if (key == "comment" || key == "obj_info") continue;
    if (key == "format") {
      if (have_format) return Status::Error(where + "a second 'format' line");
      if (t.size() != 3 || t[2] != "1.0")
        return Status::Error(where +
                             "expected 'format ascii|binary_little_endian|"
                             "binary_big_endian 1.0'");
      if (t[1] == "ascii")
        h.format = Header::Format::kAscii;
      else if (t[1] == "binary_little_endian")
        h.format = Header::Format::kBinaryLittle;
      else if (t[1] == "binary_big_endian")
        h.format = Header::Format::kBinaryBig;
      else
        return Status::Error(where + "unknown format '" + std::string(t[1]) +
                             "'; expected ascii, binary_little_endian or binary_big_endian");
      have_format = true;
    } else if (key == "element") {
      uint64_t count = 0;
      if (t.size() != 3 || std::from_chars(t[2].data(), t[2].data() + t[2].size(), count).ptr !=
                               t[2].data() + t[2].size())
        return Status::Error(where + "expected 'element NAME COUNT' with COUNT an integer >= 0");
      for (const Element& e : h.elements)
        if (e.name == t[1])
          return Status::Error(where + "a second element '" + std::string(t[1]) + "'");
      h.elements.push_back(Element{std::string(t[1]), count, {}, line_no});
    } else if (key == "property") {
      if (h.elements.empty()) return Status::Error(where + "'property' before any 'element'");
      Property p;
      if (t.size() == 5 && t[1] == "list") {
        p.list = true;
        if (!ParsePlyType(t[2], &p.count_type) || !IsInteger(p.count_type))
          return Status::Error(where + "list count type '" + std::string(t[2]) +
                               "': expected an integer type (uchar, int, ...)");
        if (!ParsePlyType(t[3], &p.type))
          return Status::Error(where + "unknown type '" + std::string(t[3]) + "'");
        p.name = std::string(t[4]);
      } else if (t.size() == 3 && t[1] != "list") {
        if (!ParsePlyType(t[1], &p.type))
          return Status::Error(where + "unknown type '" + std::string(t[1]) +
                               "'; expected char, uchar, short, ushort, int, uint, float, double "
                               "(or int8 ... float64)");
        p.name = std::string(t[2]);
      } else {
        return Status::Error(where +
                             "expected 'property TYPE NAME' or 'property list "
                             "COUNT_TYPE TYPE NAME'");
      }
      for (const Property& q : h.elements.back().props)
        if (q.name == p.name)
          return Status::Error(where + "a second property '" + p.name + "' in element '" +
                               h.elements.back().name + "'");
      h.elements.back().props.push_back(std::move(p));
    } else if (key == "end_header") {
      if (t.size() != 1) return Status::Error(where + "expected 'end_header' alone on its line");
      if (!have_format) return Status::Error(where + "'end_header' before any 'format' line");
      h.body_offset = pos;
      h.body_line = line_no + 1;
      return h;
    } else {
      return Status::Error(where + "unknown header keyword '" + std::string(key) +
                           "'; expected format, element, property, comment, obj_info or "
                           "end_header");
    }
  }
}

}  // namespace ptlab::ply
