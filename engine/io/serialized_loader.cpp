// Mitsuba .serialized mesh loading through zlib (see serialized_loader.h for the format).
#include "engine/io/serialized_loader.h"

#include <zlib.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "engine/core/input_file.h"

namespace ptlab {
namespace {

static_assert(std::endian::native == std::endian::little, "the format is little endian");
static_assert(sizeof(Vec3f) == 12 && sizeof(Vec2f) == 8, "positions are read in place");

constexpr uint16_t kMagic = 0x041C;
constexpr uint32_t kHasNormals = 0x0001, kHasUvs = 0x0002, kHasColors = 0x0008,
                   kFaceNormals = 0x0010, kDoublePrecision = 0x2000;
// Deflate's largest expansion: 1032 output bytes per input byte (zlib's technical notes).
constexpr uint64_t kMaxInflateRatio = 1032;

// Inflates a zlib stream that starts at file byte `start`, exactly n bytes at a time.
class Inflater {
 public:
  Inflater(const std::string& bytes, size_t start, std::string where)
      : start_(start), where_(std::move(where)) {
    zs_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data() + start));
    zs_.avail_in = uInt(bytes.size() - start);
    ok_ = inflateInit(&zs_) == Z_OK;
  }
  ~Inflater() {
    if (ok_) inflateEnd(&zs_);
  }
  Inflater(const Inflater&) = delete;
  Inflater& operator=(const Inflater&) = delete;

  Status Read(void* dst, uint64_t n, const std::string& what) {
    if (!ok_) return Status::Error(where_ + ": zlib could not start");
    auto* out = static_cast<Bytef*>(dst);
    while (n > 0) {
      const uInt chunk = uInt(std::min<uint64_t>(n, uint64_t(1) << 30));
      zs_.next_out = out;
      zs_.avail_out = chunk;
      while (zs_.avail_out > 0) {
        const uint64_t before_out = zs_.total_out;
        const int ret = inflate(&zs_, Z_NO_FLUSH);
        if (ret == Z_STREAM_END && zs_.avail_out > 0) return Ended(what);
        if (ret == Z_DATA_ERROR || ret == Z_NEED_DICT || ret == Z_MEM_ERROR)
          return Status::Error(Where() + ": corrupt compressed data (" +
                               (zs_.msg != nullptr ? zs_.msg : "zlib error") + ") in " + what);
        if (ret == Z_BUF_ERROR || (zs_.avail_in == 0 && zs_.total_out == before_out))
          return Ended(what);
      }
      out += chunk;
      n -= chunk;
    }
    return Status::Ok();
  }
  /// Compressed bytes not yet consumed.
  uint64_t compressed_left() const { return zs_.avail_in; }
  std::string Where() const {
    return where_ + " (file byte " + std::to_string(start_ + zs_.total_in) +
           ", decompressed byte " + std::to_string(zs_.total_out) + ")";
  }

 private:
  Status Ended(const std::string& what) const {
    return Status::Error(Where() + ": the compressed stream ends inside " + what);
  }
  z_stream zs_{};
  size_t start_;
  std::string where_;
  bool ok_ = false;
};

template <class T>
T LoadLe(const std::string& bytes, size_t offset) {
  T v;
  std::memcpy(&v, bytes.data() + offset, sizeof(T));
  return v;
}

// Reads n·dim reals (float or double) into floats.
Status ReadReals(Inflater* in, bool doubles, float* dst, uint64_t count, const std::string& what) {
  if (!doubles) return in->Read(dst, count * 4, what);
  std::vector<double> tmp(size_t(std::min<uint64_t>(count, 1 << 16)));
  for (uint64_t done = 0; done < count;) {
    const uint64_t n = std::min<uint64_t>(count - done, tmp.size());
    const Status s = in->Read(tmp.data(), n * 8, what);
    if (!s.ok()) return s;
    for (uint64_t i = 0; i < n; ++i) dst[done + i] = float(tmp[i]);
    done += n;
  }
  return Status::Ok();
}

}  // namespace

StatusOr<MeshData> LoadSerializedFromBytes(const std::string& bytes, uint32_t shape_index,
                                           const std::string& display_name) {
  const std::string& name = display_name;
  const auto header_at = [&](uint64_t offset, uint16_t* version) -> Status {
    if (bytes.size() < 4 || offset > bytes.size() - 4)
      return Status::Error(name + ": byte " + std::to_string(offset) +
                           ": expected a 4-byte shape header, found the end of the file");
    const uint16_t magic = LoadLe<uint16_t>(bytes, size_t(offset));
    *version = LoadLe<uint16_t>(bytes, size_t(offset) + 2);
    if (magic != kMagic)
      return Status::Error(name + ": byte " + std::to_string(offset) +
                           ": expected the "
                           ".serialized identifier 0x041C, found 0x" +
                           [&] {
                             char b[8];
                             std::snprintf(b, sizeof b, "%04X", magic);
                             return std::string(b);
                           }());
    if (*version != 3 && *version != 4)
      return Status::Error(name + ": byte " + std::to_string(offset + 2) + ": format version " +
                           std::to_string(*version) + "; expected 3 or 4");
    return Status::Ok();
  };
  uint16_t version = 0;
  Status s = header_at(0, &version);
  if (!s.ok()) return s;
  uint64_t offset = 0;
  if (shape_index > 0) {
    // The dictionary at the end: the offset of every shape, then their count.
    if (bytes.size() < 8)
      return Status::Error(name + ": too short for a shape dictionary (shape_index " +
                           std::to_string(shape_index) + ")");
    const uint32_t count = LoadLe<uint32_t>(bytes, bytes.size() - 4);
    if (shape_index >= count)
      return Status::Error(name + ": shape_index " + std::to_string(shape_index) +
                           " out of range; the file's dictionary lists " + std::to_string(count) +
                           " shapes (0 to " + std::to_string(int64_t(count) - 1) + ")");
    const uint64_t entry = version == 4 ? 8 : 4;
    const uint64_t back = entry * (uint64_t(count) - shape_index) + 4;
    if (back > bytes.size())
      return Status::Error(name + ": the shape dictionary (" + std::to_string(count) +
                           " shapes) is larger than the file");
    const size_t at = size_t(bytes.size() - back);
    offset = version == 4 ? LoadLe<uint64_t>(bytes, at) : LoadLe<uint32_t>(bytes, at);
    uint16_t v = 0;
    s = header_at(offset, &v);
    if (!s.ok())
      return Status::Error(s.message() + " (shape " + std::to_string(shape_index) +
                           "'s offset, read at file byte " + std::to_string(at) + ")");
    if (v != version)
      return Status::Error(name + ": byte " + std::to_string(offset) + ": shape " +
                           std::to_string(shape_index) + " has version " + std::to_string(v) +
                           ", the file's first shape " + std::to_string(version));
  }
  Inflater in(bytes, size_t(offset) + 4, name + ": shape " + std::to_string(shape_index));
  uint32_t flags = 0;
  s = in.Read(&flags, 4, "the flags");
  if (!s.ok()) return s;
  if (version == 4) {  // the shape's name, NUL-terminated
    for (int n = 0;; ++n) {
      char c = 0;
      s = in.Read(&c, 1, "the shape name");
      if (!s.ok()) return s;
      if (c == 0) break;
      if (n >= (1 << 16)) return Status::Error(in.Where() + ": shape name longer than 65536 bytes");
    }
  }
  uint64_t counts[2] = {0, 0};
  s = in.Read(counts, 16, "the vertex and triangle counts");
  if (!s.ok()) return s;
  const uint64_t v = counts[0], f = counts[1];
  if (v == 0 || f == 0 || v > std::numeric_limits<uint32_t>::max() ||
      f > std::numeric_limits<uint32_t>::max() / 3)
    return Status::Error(in.Where() + ": " + std::to_string(v) + " vertices and " +
                         std::to_string(f) +
                         " triangles; expected 1 to 4294967295 vertices and 1 to 1431655765 "
                         "triangles");
  const bool doubles = flags & kDoublePrecision;
  const uint64_t real = doubles ? 8 : 4;
  const uint64_t per_vertex =
      3 + (flags & kHasNormals ? 3 : 0) + (flags & kHasUvs ? 2 : 0) + (flags & kHasColors ? 3 : 0);
  const uint64_t needed = v * per_vertex * real + f * 12;
  if (needed / kMaxInflateRatio > in.compressed_left())
    return Status::Error(in.Where() + ": " + std::to_string(v) + " vertices and " +
                         std::to_string(f) + " triangles need " + std::to_string(needed) +
                         " bytes, more than the " + std::to_string(in.compressed_left()) +
                         " compressed bytes left can hold");
  MeshData mesh;
  mesh.positions.resize(size_t(v));
  s = ReadReals(&in, doubles, &mesh.positions[0].x, v * 3, "the positions");
  if (!s.ok()) return s;
  if (flags & kHasNormals) {
    mesh.normals.resize(size_t(v));
    s = ReadReals(&in, doubles, &mesh.normals[0].x, v * 3, "the normals");
    if (!s.ok()) return s;
  }
  if (flags & kHasUvs) {
    mesh.uvs.resize(size_t(v));
    s = ReadReals(&in, doubles, &mesh.uvs[0].x, v * 2, "the uvs");
    if (!s.ok()) return s;
  }
  if (flags & kHasColors) {
    std::vector<float> colors(size_t(v) * 3);
    s = ReadReals(&in, doubles, colors.data(), v * 3, "the vertex colours");
    if (!s.ok()) return s;
  }
  mesh.indices.resize(size_t(f) * 3);
  s = in.Read(mesh.indices.data(), f * 12, "the triangle indices");
  if (!s.ok()) return s;
  const std::string where = name + ": shape " + std::to_string(shape_index);
  for (size_t i = 0; i < mesh.indices.size(); ++i)
    if (mesh.indices[i] >= v)
      return Status::Error(where + ": triangle " + std::to_string(i / 3) + ": vertex index " +
                           std::to_string(mesh.indices[i]) + " out of range; expected 0 to " +
                           std::to_string(v - 1));
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3f& p = mesh.positions[i];
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)))
      return Status::Error(where + ": vertex " + std::to_string(i) + ": position is not finite");
  }
  for (size_t i = 0; i < mesh.normals.size(); ++i) {
    const Vec3f& n = mesh.normals[i];
    if (!(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z)) ||
        (n.x == 0 && n.y == 0 && n.z == 0))
      return Status::Error(where + ": vertex " + std::to_string(i) +
                           ": normal is zero or not finite; expected a non-zero finite vector");
  }
  for (size_t i = 0; i < mesh.uvs.size(); ++i)
    if (!(std::isfinite(mesh.uvs[i].x) && std::isfinite(mesh.uvs[i].y)))
      return Status::Error(where + ": vertex " + std::to_string(i) + ": uv is not finite");
  // Mitsuba stores uvs in its own convention, v = 0 at the image's top row (its obj plugin
  // flips an OBJ file's v into it); MeshData keeps an OBJ file's convention (LoadObj's).
  for (Vec2f& uv : mesh.uvs) uv.y = 1.0f - uv.y;
  if (flags & kFaceNormals) mesh.normals.clear();
  return mesh;
}

StatusOr<MeshData> LoadSerialized(const std::string& path, uint32_t shape_index) {
  std::string bytes;
  const Status read = ReadInputFile(path, "serialized mesh", &bytes);
  if (!read.ok()) return read;
  return LoadSerializedFromBytes(bytes, shape_index, path);
}

}  // namespace ptlab
