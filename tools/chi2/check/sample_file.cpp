// Sample files of `chi2 check`: CSV text or raw little-endian float32 rows, streamed (the file
// is never held whole: a 1 GB text file costs its points, 12 bytes each, not its bytes).
#include "tools/chi2/check/sample_file.h"

#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>

#include "engine/core/line_reader.h"
#include "engine/core/parse_number.h"

namespace ptlab {
namespace {

const char* Columns(int dims) { return dims == 3 ? "x,y,z" : "x,y"; }

// Most samples a file may hold: 2^26 points take 768 MiB (12 bytes each, allocated once, for
// the exact count found by a first pass over the file), 64 times the default test's.
constexpr int64_t kMaxSamples = int64_t(1) << 26;

chi2::Status TooManySamples(const std::string& path, int64_t count) {
  return chi2::Status::Error(path + ": holds " + std::to_string(count) +
                             "+ samples; expected at most " + std::to_string(kMaxSamples) +
                             " (a chi-square test needs far fewer; sub-sample the file)");
}

// A coordinate: any decimal number, NaN and Inf included (reported below with their line),
// and magnitudes past float range (then ±Inf, also reported).
bool ParseCoordinate(std::string_view token, double* x) { return ParseDoubleOrNonFinite(token, x); }

// Splits a line at commas, spaces and tabs.
template <typename F>
bool ForEachField(std::string_view line, F&& f) {
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == ',')) ++i;
    if (i == line.size()) break;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != ',') ++j;
    if (!f(line.substr(i, j - i))) return false;
    i = j;
  }
  return true;
}

// A header is a first line whose first field is not a number of any kind (NaN and Inf count as
// numbers: a sample of NaN is a failing sample, not a header).
bool IsHeader(std::string_view line) {
  bool header = false;
  ForEachField(line, [&](std::string_view field) {
    double x = 0;
    header = !ParseCoordinate(field, &x);
    return false;
  });
  return header;
}

// The next sample line of a text sample file: blank lines, '#' comments and a header (the first
// line that is not a comment, when IsHeader) are passed over. Every reader of the text format
// goes through it, so they agree on which line is sample k.
bool NextSampleLine(LineReader& in, bool* first, std::string_view* line) {
  while (in.Next(line)) {
    const size_t start = line->find_first_not_of(" \t");
    if (start == std::string_view::npos || (*line)[start] == '#') continue;
    const bool header = *first && IsHeader(*line);
    *first = false;
    if (!header) return true;
  }
  return false;
}

// The count of sample lines (those ParseText takes), or -1 past kMaxSamples.
int64_t CountTextSamples(const std::string& path) {
  LineReader in;
  if (!in.Open(path, "the sample file").ok()) return 0;
  std::string_view line;
  bool first = true;
  int64_t count = 0;
  while (NextSampleLine(in, &first, &line)) {
    if (++count > kMaxSamples) return -1;
  }
  return count;
}

chi2::Status ParseText(LineReader& in, int dims, std::vector<chi2::Point>* points) {
  const std::string& path = in.path();
  const int64_t count = CountTextSamples(path);
  if (count < 0) return TooManySamples(path, kMaxSamples + 1);
  points->reserve(size_t(count));
  std::string_view line;
  bool first = true;
  while (NextSampleLine(in, &first, &line)) {
    float v[3] = {0, 0, 0};
    int count = 0;
    std::string bad;
    ForEachField(line, [&](std::string_view field) {
      double x = 0;
      if (!ParseCoordinate(field, &x)) {
        bad = QuoteForMessage(field);
        return false;
      }
      if (count < 3) v[count] = float(x);
      ++count;
      return true;
    });
    const std::string where = path + ":" + std::to_string(in.line_number()) + ": ";
    if (!bad.empty())
      return chi2::Status::Error(where + bad + " is not a number; expected " +
                                 std::to_string(dims) + " numbers per line (" + Columns(dims) +
                                 ")");
    if (count != dims)
      return chi2::Status::Error(where + std::to_string(count) + " numbers, expected " +
                                 std::to_string(dims) + " per line (" + Columns(dims) + ")");
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || (dims == 3 && !std::isfinite(v[2])))
      return chi2::Status::Error(where + "the sample is not finite (NaN, Inf or beyond float "
                                 "range); expected finite numbers (" + std::string(Columns(dims)) +
                                 ")");
    points->push_back({v[0], v[1], v[2]});
  }
  if (!in.status().ok()) return chi2::Status::Error(in.status().message());
  if (points->empty())
    return chi2::Status::Error(path + ": no samples in the file, expected one point per line (" +
                               std::string(Columns(dims)) + ")");
  return chi2::Status::Ok();
}

chi2::Status ParseRaw(LineReader& in, uint64_t bytes, int dims, std::vector<chi2::Point>* points) {
  const std::string& path = in.path();
  const size_t row = 4 * size_t(dims);
  if (bytes % row != 0)
    return chi2::Status::Error(path + ": " + std::to_string(bytes) +
                               " bytes is not a whole number of rows of " + std::to_string(dims) +
                               " little-endian float32 (" + std::to_string(row) +
                               " bytes each); check --dims");
  static_assert(std::endian::native == std::endian::little, "raw samples are little-endian");
  if (bytes / row > uint64_t(kMaxSamples)) return TooManySamples(path, int64_t(bytes / row));
  points->reserve(size_t(bytes / row));
  float v[3] = {0, 0, 0};
  while (in.Read(reinterpret_cast<char*>(v), row) == row) {
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || (dims == 3 && !std::isfinite(v[2])))
      return chi2::Status::Error(path + ": row " + std::to_string(points->size()) +
                                 " (byte " + std::to_string(points->size() * row) +
                                 ") is not finite; expected finite float32 coordinates");
    points->push_back({v[0], v[1], v[2]});
  }
  if (!in.status().ok()) return chi2::Status::Error(in.status().message());
  if (points->empty())
    return chi2::Status::Error(path + ": the sample file is empty, expected one point per row");
  return chi2::Status::Ok();
}

}  // namespace

std::string SampleLocation(const std::string& path, bool raw, int dims, int64_t index) {
  if (raw) {
    const int64_t row = 4 * int64_t(dims);
    return path + ": row " + std::to_string(index) + " (byte " + std::to_string(index * row) + ")";
  }
  LineReader in;
  if (!in.Open(path, "the sample file").ok()) return path;
  std::string_view line;
  bool first = true;
  int64_t samples = 0;
  while (NextSampleLine(in, &first, &line)) {  // the lines ParseText takes as samples
    if (samples++ == index) return path + ":" + std::to_string(in.line_number());
  }
  return path;
}

chi2::Status ReadSampleFile(const std::string& path, bool raw, int dims,
                            std::vector<chi2::Point>* points) {
  points->clear();
  LineReader in;
  const Status open = in.Open(path, "the sample file");
  if (!open.ok()) return chi2::Status::Error(open.message());
  uint64_t bytes = 0;
  const Status checked = CheckInputFile(path, "the sample file", &bytes);
  if (!checked.ok()) return chi2::Status::Error(checked.message());
  if (bytes == 0)
    return chi2::Status::Error(path + ": the sample file is empty, expected one point per " +
                               (raw ? "row" : "line"));
  return raw ? ParseRaw(in, bytes, dims, points) : ParseText(in, dims, points);
}

}  // namespace ptlab
