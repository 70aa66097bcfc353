// Header checks of untrusted image files (engine/image/image_header_checks.h).
#include "engine/image/image_header_checks.h"

#include <OpenEXR/ImfHeader.h>

#include <cstdint>
#include <cstring>
#include <mutex>
#include <string>

namespace ptlab {
namespace {

// The largest image side OpenEXR is allowed to read (see ExrHeaderError).
constexpr int kMaxImageSide = 1 << 20;

// The body of `HdrBodyError` from byte `pos`.
std::string HdrRunsError(const std::string& bytes, size_t pos, int64_t w, int64_t h) {
  const uint64_t size = bytes.size();
  auto flat_error = [&](uint64_t from, int64_t pixels) -> std::string {
    if (from + uint64_t(pixels) * 4 <= size) return "";
    return "truncated: " + std::to_string(pixels) + " flat pixels need " +
           std::to_string(uint64_t(pixels) * 4) + " bytes from offset " + std::to_string(from) +
           ", the file has " + std::to_string(size - std::min(size, from));
  };
  if (w < 8 || w >= 32768) return flat_error(pos, w * h);
  auto byte = [&](uint64_t at) { return uint8_t(bytes[size_t(at)]); };
  for (int64_t y = 0; y < h; ++y) {
    if (pos + 4 > size) return "truncated at scanline " + std::to_string(y) + " of " + std::to_string(h);
    if (byte(pos) != 2 || byte(pos + 1) != 2 || (byte(pos + 2) & 0x80)) {
      return flat_error(pos + 4, w * h - 1);  // stb decodes the whole image flat from here
    }
    pos += 4;
    for (int c = 0; c < 4; ++c) {
      for (int64_t x = 0; x < w;) {
        if (pos >= size)
          return "truncated in the run-length data of scanline " + std::to_string(y) + " of " +
                 std::to_string(h);
        const int count = byte(pos++);
        if (count > 128) {
          x += count - 128;
          pos += 1;
        } else {
          x += count;
          pos += uint64_t(count);
        }
      }
    }
    if (pos > size)
      return "truncated in the run-length data of scanline " + std::to_string(y) + " of " +
             std::to_string(h);
  }
  return "";
}

}  // namespace

// Empty when a w x h image fits in `file_bytes` of a format decoding at most
// `pixels_per_byte`; else the reason.
std::string ClaimedSizeError(int64_t w, int64_t h, size_t file_bytes, int64_t pixels_per_byte) {
  if (w * h <= int64_t(file_bytes) * pixels_per_byte) return "";
  return "header claims " + std::to_string(w) + "x" + std::to_string(h) + " pixels, more than " +
         std::to_string(int64_t(file_bytes) * pixels_per_byte) + " that a file of " +
         std::to_string(file_bytes) + " bytes can hold (truncated or corrupt)";
}

// Radiance HDR bodies are checked before stb_image decodes them: stb reads a missing byte as 0,
// so a truncated file either decodes as black or, in a run-length scanline, loops forever on
// zero-length runs. This walks the body with stb's own rules (flat pixels when the width is
// outside [8, 32768) or a scanline lacks the 2,2 RLE marker, which makes stb re-read the whole
// image flat from that point) and says whether every byte stb will read is there.
std::string HdrBodyError(const std::string& bytes, int64_t w, int64_t h) {
  // The header is lines up to an empty one, then the resolution line; the body follows.
  size_t pos = 0;
  bool header_done = false;
  for (int line = 0; pos < bytes.size(); ++line) {
    const size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) break;
    const bool empty = end == pos;
    pos = end + 1;
    if (header_done) return HdrRunsError(bytes, pos, w, h);
    if (line > 0 && empty) header_done = true;
  }
  return "truncated header (no resolution line)";
}

// OpenEXR allocates every header attribute at the size its header field claims (an unknown type
// becomes an opaque blob of that size) before it reads the value. This walks the header(s)
// first and refuses a size that the rest of the file cannot hold, so a corrupt field costs
// nothing. Layout: magic, version flags, then attributes "name\0type\0<int32 size><value>"
// ending in an empty name; a multi-part file repeats headers until an empty one.
std::string ExrHeaderError(const std::string& bytes) {
  // OpenEXR sizes its line/tile offset tables from the data window before anything checks it:
  // cap the sides it accepts (the pixel budget is checked after the header is read).
  static std::once_flag limits;
  std::call_once(limits, [] {
    Imf::Header::setMaxImageSize(kMaxImageSide, kMaxImageSide);
    Imf::Header::setMaxTileSize(kMaxImageSide, kMaxImageSide);
  });
  const uint64_t size = bytes.size();
  if (size < 8) return "truncated (no version field)";
  auto u32_at = [&](uint64_t at) {  // little endian, as EXR stores every integer
    uint32_t v = 0;
    for (int k = 3; k >= 0; --k) v = v << 8 | uint8_t(bytes[size_t(at) + size_t(k)]);
    return v;
  };
  const uint32_t flags = u32_at(4);
  const bool multipart = flags & 0x1000;
  const uint64_t max_name = (flags & 0x400) ? 255 : 31;
  uint64_t pos = 8;
  auto read_name = [&](std::string* name) {
    const size_t end = bytes.find('\0', size_t(pos));
    if (end == std::string::npos || end - pos > max_name) return false;
    *name = bytes.substr(size_t(pos), end - size_t(pos));
    pos = end + 1;
    return true;
  };
  for (int header = 0;; ++header) {
    for (int attribute = 0;; ++attribute) {
      std::string name, type;
      if (!read_name(&name)) return "truncated or corrupt header (attribute name)";
      if (name.empty()) {
        if (attribute == 0 && multipart && header > 0) return "";  // the empty header ends them
        break;
      }
      if (!read_name(&type)) return "corrupt header: attribute '" + name + "' has no type name";
      if (pos + 4 > size) return "truncated header at attribute '" + name + "'";
      const int32_t value_size = int32_t(u32_at(pos));
      pos += 4;
      if (value_size < 0 || uint64_t(value_size) > size - pos) {
        return "corrupt header: attribute '" + name + "' (" + type + ") claims " +
               std::to_string(value_size) + " bytes, " + std::to_string(size - pos) +
               " remain in the file";
      }
      pos += uint64_t(value_size);
    }
    if (!multipart) return "";
  }
}

}  // namespace ptlab
