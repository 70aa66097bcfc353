// Mitsuba .vol grid files: header checks, then the float32 values.
#include "engine/io/vol_grid.h"

#include <cmath>
#include <cstring>

#include "engine/core/input_file.h"

namespace ptlab {
namespace {

int32_t ReadI32(const std::string& b, size_t at) {
  int32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

}  // namespace

StatusOr<VolGrid> ParseVolGrid(const std::string& bytes, const std::string& name) {
  constexpr size_t kHeader = 3 + 1 + 4 * 5 + 4 * 6;
  const auto error = [&](const std::string& what) { return Status::Error(name + ": " + what); };
  if (bytes.size() < kHeader || bytes.compare(0, 3, "VOL") != 0)
    return error("not a Mitsuba volume file (expected the bytes \"VOL\" and a 48-byte header)");
  if (uint8_t(bytes[3]) != 3)
    return error("volume file version " + std::to_string(int(uint8_t(bytes[3]))) +
                 "; expected 3");
  const int32_t encoding = ReadI32(bytes, 4);
  if (encoding != 1)
    return error("volume data encoding " + std::to_string(encoding) +
                 "; expected 1 (float32)");
  const int32_t sx = ReadI32(bytes, 8), sy = ReadI32(bytes, 12), sz = ReadI32(bytes, 16);
  const int32_t ch = ReadI32(bytes, 20);
  if (sx < 1 || sy < 1 || sz < 1 || sx > 4096 || sy > 4096 || sz > 4096)
    return error("volume size " + std::to_string(sx) + " x " + std::to_string(sy) + " x " +
                 std::to_string(sz) + "; expected each in [1, 4096]");
  if (ch < 1 || ch > 4)
    return error("volume channel count " + std::to_string(ch) + "; expected 1 to 4");
  const uint64_t count = uint64_t(sx) * uint64_t(sy) * uint64_t(sz) * uint64_t(ch);
  if (bytes.size() - kHeader != count * 4)
    return error("holds " + std::to_string(bytes.size() - kHeader) + " data bytes; the header's " +
                 "sizes need " + std::to_string(count * 4));
  VolGrid g;
  g.nx = uint32_t(sx), g.ny = uint32_t(sy), g.nz = uint32_t(sz), g.channels = uint32_t(ch);
  g.values.resize(count);
  std::memcpy(g.values.data(), bytes.data() + kHeader, count * 4);
  for (uint64_t i = 0; i < count; ++i)
    if (!std::isfinite(g.values[i]))
      return error("value " + std::to_string(i) + " is not finite");
  return g;
}

StatusOr<VolGrid> LoadVolGrid(const std::string& path) {
  std::string bytes;
  if (Status s = ReadInputFile(path, "volume grid", &bytes); !s.ok()) return s;
  return ParseVolGrid(bytes, path);
}

}  // namespace ptlab
