// Image file I/O: EXR via OpenEXR, PNG and HDR via stb_image, PFM by hand (writes through
// engine/image/atomic_file.h, header checks in engine/image/image_header_checks.h).
#include "engine/image/image_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

#include "engine/core/input_file.h"
#include "engine/core/parse_number.h"
#include "engine/image/image_header_checks.h"
#include "engine/image/srgb.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;

// Refuse images larger than this many pixels: a garbage header must not trigger a huge allocation.
constexpr int64_t kMaxPixels = int64_t(1) << 28;

Status ReadError(const std::string& path, const std::string& what) {
  return Status::Error("ReadImage: " + path + ": " + what);
}

StatusOr<std::string> ReadFileBytes(const std::string& path) {
  std::string bytes;
  const Status read = ReadInputFile(path, "image file", &bytes);
  if (!read.ok()) return Status::Error("ReadImage: " + read.message());
  if (bytes.empty()) return ReadError(path, "file is empty");
  return bytes;
}

std::string HexPrefix(const std::string& bytes) {
  std::string out;
  char buf[4];
  for (size_t i = 0; i < std::min<size_t>(bytes.size(), 8); ++i) {
    std::snprintf(buf, sizeof(buf), "%s%02x", i ? " " : "", unsigned(uint8_t(bytes[i])));
    out += buf;
  }
  return out;
}

bool SizeOk(int64_t w, int64_t h) { return w > 0 && h > 0 && w * h <= kMaxPixels; }

// An Imf::IStream over bytes already in memory, so the file is read exactly once.
class MemoryIStream : public Imf::IStream {
 public:
  MemoryIStream(const std::string& name, const std::string& bytes)
      : Imf::IStream(name.c_str()), bytes_(bytes) {}
  bool read(char c[], int n) override {
    if (n < 0 || pos_ > bytes_.size() || bytes_.size() - pos_ < uint64_t(n)) {
      throw std::runtime_error("unexpected end of file (truncated)");
    }
    std::memcpy(c, bytes_.data() + pos_, size_t(n));
    pos_ += uint64_t(n);
    return pos_ < bytes_.size();
  }
  uint64_t tellg() override { return pos_; }
  void seekg(uint64_t pos) override { pos_ = pos; }
  void clear() override {}

 private:
  const std::string& bytes_;
  uint64_t pos_ = 0;
};

// An Imf::OStream into memory; OpenEXR seeks back to fill in the line offset table.
class MemoryOStream : public Imf::OStream {
 public:
  explicit MemoryOStream(const std::string& name) : Imf::OStream(name.c_str()) {}
  void write(const char c[], int n) override {
    if (pos_ + uint64_t(n) > bytes_.size()) bytes_.resize(size_t(pos_) + size_t(n));
    std::memcpy(bytes_.data() + pos_, c, size_t(n));
    pos_ += uint64_t(n);
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = pos; }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
  uint64_t pos_ = 0;
};

StatusOr<Image> ReadExrBytes(const std::string& path, const std::string& bytes) {
  if (const std::string e = ExrHeaderError(bytes); !e.empty())
    return ReadError(path, "bad EXR: " + e);
  try {
    MemoryIStream stream(path, bytes);
    Imf::InputFile file(stream);
    const Imath::Box2i dw = file.header().dataWindow();
    const int64_t w = int64_t(dw.max.x) - dw.min.x + 1, h = int64_t(dw.max.y) - dw.min.y + 1;
    if (!SizeOk(w, h)) {
      return ReadError(path, "bad EXR header: data window " + std::to_string(w) + "x" +
                                 std::to_string(h) + " is empty or too large");
    }
    if (const std::string e = ClaimedSizeError(w, h, bytes.size(), kMaxExrPixelsPerByte);
        !e.empty())
      return ReadError(path, "bad EXR header: " + e);
    const Imf::ChannelList& channels = file.header().channels();
    const bool has_rgb =
        channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
    const bool has_y = channels.findChannel("Y") != nullptr;
    if (!has_rgb && !has_y) {
      std::string names;
      for (auto it = channels.begin(); it != channels.end(); ++it) {
        names += (names.empty() ? "" : ", ") + std::string(it.name());
      }
      return ReadError(path, "EXR has neither R,G,B nor Y channels (found: " +
                                 (names.empty() ? std::string("none") : names) + ")");
    }
    for (const char* name :
         has_rgb ? std::vector<const char*>{"R", "G", "B"} : std::vector<const char*>{"Y"}) {
      const Imf::Channel* c = channels.findChannel(name);
      if (c->xSampling != 1 || c->ySampling != 1) {
        return ReadError(path, std::string("EXR channel ") + name + " is subsampled (unsupported)");
      }
    }
    Image image(static_cast<int>(w), static_cast<int>(h));
    std::vector<float> luminance;
    Imf::FrameBuffer fb;
    if (has_rgb) {
      const size_t xs = 3 * sizeof(float), ys = xs * size_t(w);
      float* base = image.rgb.data();
      fb.insert("R", Imf::Slice::Make(Imf::FLOAT, base + 0, dw, xs, ys));
      fb.insert("G", Imf::Slice::Make(Imf::FLOAT, base + 1, dw, xs, ys));
      fb.insert("B", Imf::Slice::Make(Imf::FLOAT, base + 2, dw, xs, ys));
    } else {
      luminance.assign(size_t(w * h), 0.0f);
      fb.insert("Y", Imf::Slice::Make(Imf::FLOAT, luminance.data(), dw, sizeof(float),
                                      sizeof(float) * size_t(w)));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    if (!has_rgb) {
      for (size_t i = 0; i < luminance.size(); ++i) {
        image.rgb[3 * i] = image.rgb[3 * i + 1] = image.rgb[3 * i + 2] = luminance[i];
      }
    }
    return image;
  } catch (const std::exception& e) {
    return ReadError(path, std::string("bad or truncated EXR: ") + e.what());
  }
}

StatusOr<Image> ReadStbBytes(const std::string& path, const std::string& bytes, bool hdr) {
  if (bytes.size() > size_t(std::numeric_limits<int>::max())) {
    return ReadError(path, "file too large for stb_image");
  }
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int len = int(bytes.size());
  const char* kind = hdr ? "Radiance HDR" : "PNG";
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(data, len, &w, &h, &comp)) {
    return ReadError(path, std::string("bad ") + kind + " header: " + stbi_failure_reason());
  }
  if (!SizeOk(w, h)) {
    return ReadError(path, std::string("bad ") + kind + " header: size " + std::to_string(w) + "x" +
                               std::to_string(h) + " is empty or too large");
  }
  if (const std::string e = ClaimedSizeError(
          w, h, bytes.size(), hdr ? kMaxHdrPixelsPerByte : kMaxPngPixelsPerByte);
      !e.empty())
    return ReadError(path, std::string("bad ") + kind + " header: " + e);
  if (hdr) {
    if (const std::string e = HdrBodyError(bytes, w, h); !e.empty())
      return ReadError(path, "bad Radiance HDR: " + e);
  }
  Image image(w, h);
  const size_t n = image.rgb.size();
  if (hdr) {
    float* pixels = stbi_loadf_from_memory(data, len, &w, &h, &comp, 3);
    if (!pixels)
      return ReadError(path, std::string("bad or truncated HDR: ") + stbi_failure_reason());
    std::copy(pixels, pixels + n, image.rgb.begin());
    stbi_image_free(pixels);
  } else if (stbi_is_16_bit_from_memory(data, len)) {
    stbi_us* pixels = stbi_load_16_from_memory(data, len, &w, &h, &comp, 3);
    if (!pixels)
      return ReadError(path, std::string("bad or truncated PNG: ") + stbi_failure_reason());
    for (size_t i = 0; i < n; ++i) image.rgb[i] = SrgbToLinear(float(pixels[i] / 65535.0));
    stbi_image_free(pixels);
  } else {
    stbi_uc* pixels = stbi_load_from_memory(data, len, &w, &h, &comp, 3);
    if (!pixels)
      return ReadError(path, std::string("bad or truncated PNG: ") + stbi_failure_reason());
    float table[256];
    for (int v = 0; v < 256; ++v) table[v] = SrgbToLinear(float(v / 255.0));
    for (size_t i = 0; i < n; ++i) image.rgb[i] = table[pixels[i]];
    stbi_image_free(pixels);
  }
  return image;
}

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// PFM: "PF" (RGB) or "Pf" (grey), whitespace, width, height, scale, ONE whitespace byte, floats.
StatusOr<Image> ReadPfmBytes(const std::string& path, const std::string& bytes) {
  const int channels = bytes[1] == 'F' ? 3 : 1;
  size_t pos = 2;
  auto next_token = [&](const char* what) -> StatusOr<std::string> {
    if (pos >= bytes.size() || !IsSpace(bytes[pos])) {
      return ReadError(path, std::string("bad PFM header: expected whitespace before the ") + what);
    }
    while (pos < bytes.size() && IsSpace(bytes[pos])) ++pos;
    const size_t start = pos;
    while (pos < bytes.size() && !IsSpace(bytes[pos]) && pos - start < 64) ++pos;
    if (pos == start) return ReadError(path, std::string("bad PFM header: missing ") + what);
    return bytes.substr(start, pos - start);
  };
  auto parse_int = [&](const std::string& s, int64_t* out) {
    if (s.empty() || s.size() > 10) return false;
    for (char c : s) {
      if (!std::isdigit(uint8_t(c))) return false;
    }
    return ParseNumberQuietly<int64_t>(s, 0, int64_t(1) << 40, out) == NumberError::kOk;
  };
  StatusOr<std::string> ws = next_token("width");
  if (!ws.ok()) return ws.status();
  StatusOr<std::string> hs = next_token("height");
  if (!hs.ok()) return hs.status();
  StatusOr<std::string> ss = next_token("scale");
  if (!ss.ok()) return ss.status();
  int64_t w = 0, h = 0;
  if (!parse_int(*ws, &w) || !parse_int(*hs, &h) || !SizeOk(w, h)) {
    return ReadError(path, "bad PFM header: size '" + *ws + " " + *hs +
                               "' is not two positive integers of a sane size");
  }
  double scale = 0;
  if (ParseNumberQuietly<double>(*ss, -HUGE_VAL, HUGE_VAL, &scale) != NumberError::kOk ||
      scale == 0) {
    return ReadError(path, "bad PFM header: scale '" + *ss + "' is not a non-zero number");
  }
  if (pos >= bytes.size()) return ReadError(path, "truncated PFM: no pixel data after the header");
  ++pos;  // The single whitespace byte that ends the header.
  const size_t count = size_t(w * h) * size_t(channels);
  const size_t needed = count * sizeof(float);
  const size_t available = bytes.size() - pos;
  if (available < needed) {
    return ReadError(path, "truncated PFM: expected " + std::to_string(needed) +
                               " bytes of pixel data, found " + std::to_string(available));
  }
  const bool file_little = scale < 0;
  const bool swap = file_little != (std::endian::native == std::endian::little);
  Image image(static_cast<int>(w), static_cast<int>(h));
  for (int64_t y = 0; y < h; ++y) {
    const int64_t file_row = h - 1 - y;  // PFM rows run bottom to top.
    for (int64_t x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) {
        const int fc = channels == 3 ? c : 0;
        uint32_t u;
        std::memcpy(&u, bytes.data() + pos + ((file_row * w + x) * channels + fc) * 4, 4);
        if (swap) u = __builtin_bswap32(u);
        image.rgb[size_t((y * w + x) * 3 + c)] = std::bit_cast<float>(u);
      }
    }
  }
  return image;
}

Status ValidateForWrite(const char* fn, const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0) {
    return Status::Error(std::string(fn) + ": " + path + ": image is empty (" +
                         std::to_string(image.width) + "x" + std::to_string(image.height) + ")");
  }
  if (image.rgb.size() != size_t(image.width) * size_t(image.height) * 3) {
    return Status::Error(std::string(fn) + ": " + path + ": image holds " +
                         std::to_string(image.rgb.size()) + " floats, expected 3*" +
                         std::to_string(image.width) + "*" + std::to_string(image.height));
  }
  return Status::Ok();
}

}  // namespace

const char* ImageFormatName(ImageFormat format) {
  switch (format) {
    case ImageFormat::kExr:
      return "EXR";
    case ImageFormat::kPng:
      return "PNG";
    case ImageFormat::kHdr:
      return "HDR";
    case ImageFormat::kPfm:
      return "PFM";
    case ImageFormat::kUnknown:
      break;
  }
  return "unknown";
}

ImageFormat DetectImageFormat(const unsigned char* b, size_t n) {
  auto starts = [&](const char* magic, size_t len) {
    return n >= len && std::memcmp(b, magic, len) == 0;
  };
  if (starts("\x76\x2f\x31\x01", 4)) return ImageFormat::kExr;
  if (starts("\x89PNG\r\n\x1a\n", 8)) return ImageFormat::kPng;
  if (starts("#?RADIANCE", 10) || starts("#?RGBE", 6)) return ImageFormat::kHdr;
  if (n >= 3 && b[0] == 'P' && (b[1] == 'F' || b[1] == 'f') && IsSpace(char(b[2]))) {
    return ImageFormat::kPfm;
  }
  return ImageFormat::kUnknown;
}

StatusOr<Image> ReadImage(const std::string& path) {
  StatusOr<std::string> bytes = ReadFileBytes(path);
  if (!bytes.ok()) return bytes.status();
  return DecodeImage(path, *bytes);
}

StatusOr<Image> DecodeImage(const std::string& path, const std::string& b) {
  if (b.empty()) return ReadError(path, "file is empty");
  switch (DetectImageFormat(reinterpret_cast<const unsigned char*>(b.data()), b.size())) {
    case ImageFormat::kExr:
      return ReadExrBytes(path, b);
    case ImageFormat::kPng:
      return ReadStbBytes(path, b, /*hdr=*/false);
    case ImageFormat::kHdr:
      return ReadStbBytes(path, b, /*hdr=*/true);
    case ImageFormat::kPfm:
      return ReadPfmBytes(path, b);
    case ImageFormat::kUnknown:
      break;
  }
  return ReadError(path, "unknown image format (first bytes: " + HexPrefix(b) +
                             "); expected EXR, PNG, Radiance HDR or PFM");
}

StatusOr<std::vector<std::pair<std::string, std::string>>> ReadExrStringAttributes(
    const std::string& path) {
  StatusOr<std::string> bytes = ReadFileBytes(path);
  if (!bytes.ok()) return bytes.status();
  const auto* b = reinterpret_cast<const unsigned char*>(bytes->data());
  if (DetectImageFormat(b, bytes->size()) != ImageFormat::kExr) {
    return ReadError(path, "not an EXR file (first bytes: " + HexPrefix(*bytes) + ")");
  }
  if (const std::string e = ExrHeaderError(*bytes); !e.empty())
    return ReadError(path, "bad EXR: " + e);
  try {
    MemoryIStream stream(path, *bytes);
    Imf::InputFile file(stream);
    std::vector<std::pair<std::string, std::string>> out;
    for (auto it = file.header().begin(); it != file.header().end(); ++it) {
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) {
        out.emplace_back(it.name(), s->value());
      }
    }
    std::sort(out.begin(), out.end());
    return out;
  } catch (const std::exception& e) {
    return ReadError(path, std::string("bad EXR header: ") + e.what());
  }
}

StatusOr<std::string> EncodeExr(
    const std::string& path, const Image& image,
    const std::vector<std::pair<std::string, std::string>>& header_attributes) {
  PTLAB_RETURN_IF_ERROR(ValidateForWrite("WriteExr", path, image));
  std::string bytes;
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.channels().insert("R", Imf::Channel(Imf::FLOAT));
    header.channels().insert("G", Imf::Channel(Imf::FLOAT));
    header.channels().insert("B", Imf::Channel(Imf::FLOAT));
    // Names OpenEXR gives meaning to in single- or multi-part files.
    static const std::set<std::string> kReserved = {"type",  "name", "version",  "chunkCount",
                                                    "tiles", "view", "multiView"};
    std::set<std::string> seen;
    for (const auto& [name, value] : header_attributes) {
      if (name.empty()) return Status::Error("WriteExr: " + path + ": empty attribute name");
      if (!seen.insert(name).second) {
        return Status::Error("WriteExr: " + path + ": duplicate attribute '" + name + "'");
      }
      if (header.find(name) != header.end() || kReserved.count(name)) {
        return Status::Error("WriteExr: " + path + ": attribute '" + name +
                             "' is a standard EXR attribute");
      }
      header.insert(name, Imf::StringAttribute(value));
    }
    MemoryOStream stream(path);
    {
      Imf::OutputFile file(stream, header);
      Imf::FrameBuffer fb;
      const size_t xs = 3 * sizeof(float), ys = xs * size_t(image.width);
      // OpenEXR only reads through the slice pointers when writing.
      char* base = reinterpret_cast<char*>(const_cast<float*>(image.rgb.data()));
      fb.insert("R", Imf::Slice(Imf::FLOAT, base + 0 * sizeof(float), xs, ys));
      fb.insert("G", Imf::Slice(Imf::FLOAT, base + 1 * sizeof(float), xs, ys));
      fb.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xs, ys));
      file.setFrameBuffer(fb);
      file.writePixels(image.height);
    }  // The destructor writes the line offset table.
    bytes = stream.bytes();
  } catch (const std::exception& e) {
    return Status::Error("WriteExr: " + path + ": OpenEXR: " + e.what());
  }
  return bytes;
}

Status WriteExr(const std::string& path, const Image& image,
                const std::vector<std::pair<std::string, std::string>>& header_attributes) {
  StatusOr<std::string> bytes = EncodeExr(path, image, header_attributes);
  if (!bytes.ok()) return bytes.status();
  Status s = WriteFileAtomically(path, *bytes);
  if (!s.ok()) return Status::Error("WriteExr: " + s.message());
  return Status::Ok();
}

StatusOr<std::string> EncodePng(const std::string& path, const Image& image) {
  PTLAB_RETURN_IF_ERROR(ValidateForWrite("WritePng", path, image));
  std::vector<unsigned char> pixels(image.rgb.size());
  for (size_t i = 0; i < pixels.size(); ++i) {
    const float v = image.rgb[i];
    // NaN fails both comparisons below and maps to 0.
    const float e = v > 0 ? std::min(LinearToSrgb(v), 1.0f) : 0.0f;
    pixels[i] = static_cast<unsigned char>(std::lround(e * 255.0f));
  }
  std::string bytes;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
  };
  if (!stbi_write_png_to_func(append, &bytes, image.width, image.height, 3, pixels.data(),
                              image.width * 3)) {
    return Status::Error("WritePng: " + path + ": stb_image_write failed to encode the PNG");
  }
  return bytes;
}

Status WritePng(const std::string& path, const Image& image) {
  StatusOr<std::string> bytes = EncodePng(path, image);
  if (!bytes.ok()) return bytes.status();
  Status s = WriteFileAtomically(path, *bytes);
  if (!s.ok()) return Status::Error("WritePng: " + s.message());
  return Status::Ok();
}

Status WritePfm(const std::string& path, const Image& image) {
  PTLAB_RETURN_IF_ERROR(ValidateForWrite("WritePfm", path, image));
  std::string bytes =
      "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
  const size_t header = bytes.size();
  const size_t row_floats = size_t(image.width) * 3;
  bytes.resize(header + image.rgb.size() * sizeof(float));
  for (int y = 0; y < image.height; ++y) {
    const size_t file_row = size_t(image.height - 1 - y);  // PFM rows run bottom to top.
    for (size_t i = 0; i < row_floats; ++i) {
      uint32_t u = std::bit_cast<uint32_t>(image.rgb[size_t(y) * row_floats + i]);
      if constexpr (std::endian::native == std::endian::big) u = __builtin_bswap32(u);
      std::memcpy(bytes.data() + header + (file_row * row_floats + i) * 4, &u, 4);
    }
  }
  Status s = WriteFileAtomically(path, bytes);
  if (!s.ok()) return Status::Error("WritePfm: " + s.message());
  return Status::Ok();
}

std::string LowercaseExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

Status WriteImage(const std::string& path, const Image& image) {
  const std::string ext = LowercaseExtension(path);
  if (ext == ".exr") return WriteExr(path, image);
  if (ext == ".png") return WritePng(path, image);
  if (ext == ".pfm") return WritePfm(path, image);
  return Status::Error("WriteImage: " + path + ": unknown extension '" + ext +
                       "'; expected .exr, .png or .pfm");
}

}  // namespace ptlab
