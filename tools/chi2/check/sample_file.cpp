// Sample files of `chi2 check`: CSV text or raw little-endian float32 rows.
#include "tools/chi2/check/sample_file.h"

#include <bit>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace ptlab {
namespace {

chi2::Status ReadAll(const std::string& path, std::string* bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return chi2::Status::Error(path + ": cannot open the sample file");
  std::stringstream s;
  s << in.rdbuf();
  *bytes = s.str();
  if (bytes->empty())
    return chi2::Status::Error(path + ": the sample file is empty, expected one point per row");
  return chi2::Status::Ok();
}

const char* Columns(int dims) { return dims == 3 ? "x,y,z" : "x,y"; }

chi2::Status ParseText(const std::string& path, const std::string& text, int dims,
                       std::vector<chi2::Point>* points) {
  std::istringstream lines(text);
  std::string line;
  int64_t number = 0;
  bool first = true;
  while (std::getline(lines, line)) {
    ++number;
    size_t start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line[start] == '#') continue;
    const char c = line[start];
    const bool numeric = std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' ||
                         c == '.' || std::strncmp(line.c_str() + start, "nan", 3) == 0 ||
                         std::strncmp(line.c_str() + start, "inf", 3) == 0;
    if (first && !numeric) {
      first = false;
      continue;  // a header
    }
    first = false;
    float v[3] = {0, 0, 0};
    int count = 0;
    const char* s = line.c_str() + start;
    while (*s != '\0') {
      while (*s == ' ' || *s == '\t' || *s == ',' || *s == '\r') ++s;
      if (*s == '\0') break;
      char* end = nullptr;
      const double x = std::strtod(s, &end);
      if (end == s)
        return chi2::Status::Error(path + ":" + std::to_string(number) + ": \"" +
                                   std::string(s).substr(0, 30) + "\" is not a number; expected " +
                                   std::to_string(dims) + " numbers per line (" + Columns(dims) +
                                   ")");
      if (count < 3) v[count] = float(x);
      ++count;
      s = end;
    }
    if (count != dims)
      return chi2::Status::Error(path + ":" + std::to_string(number) + ": " +
                                 std::to_string(count) + " numbers, expected " +
                                 std::to_string(dims) + " per line (" + Columns(dims) + ")");
    points->push_back({v[0], v[1], v[2]});
  }
  if (points->empty())
    return chi2::Status::Error(path + ": no samples in the file, expected one point per line (" +
                               std::string(Columns(dims)) + ")");
  return chi2::Status::Ok();
}

chi2::Status ParseRaw(const std::string& path, const std::string& bytes, int dims,
                      std::vector<chi2::Point>* points) {
  const size_t row = 4 * size_t(dims);
  if (bytes.size() % row != 0)
    return chi2::Status::Error(path + ": " + std::to_string(bytes.size()) +
                               " bytes is not a whole number of rows of " + std::to_string(dims) +
                               " little-endian float32 (" + std::to_string(row) +
                               " bytes each); check --dims");
  static_assert(std::endian::native == std::endian::little, "raw samples are little-endian");
  const size_t n = bytes.size() / row;
  points->resize(n);
  for (size_t i = 0; i < n; ++i) {
    float v[3] = {0, 0, 0};
    std::memcpy(v, bytes.data() + i * row, row);
    (*points)[i] = {v[0], v[1], v[2]};
  }
  return chi2::Status::Ok();
}

}  // namespace

chi2::Status ReadSampleFile(const std::string& path, bool raw, int dims,
                            std::vector<chi2::Point>* points) {
  points->clear();
  std::string bytes;
  chi2::Status st = ReadAll(path, &bytes);
  if (!st.ok()) return st;
  return raw ? ParseRaw(path, bytes, dims, points) : ParseText(path, bytes, dims, points);
}

}  // namespace ptlab
