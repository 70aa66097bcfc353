// OBJ loading: a validation pass with exact line numbers, tinyobjloader, then fan triangulation
// and vertex deduplication into MeshData.
#include "engine/io/obj_loader.h"

#include <tiny_obj_loader.h>

#include <cstdint>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "engine/io/text_parsing.h"

namespace ptlab {
namespace {

struct ObjCounts {
  size_t positions = 0, normals = 0, uvs = 0, faces = 0;
};

// A face index checked only once the whole file is read (positive indices may refer forward).
struct PendingIndex {
  size_t line;
  int index;   // 1-based, positive
  int vertex;  // 1-based position within the face, for the message
  char kind;   // 'v', 't' or 'n'
};

// The separators tinyobjloader accepts ('\r' never reaches here: line ends are normalised).
bool IsBlank(char c) { return c == ' ' || c == '\t'; }

std::vector<std::string_view> SplitWords(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && IsBlank(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !IsBlank(line[i])) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

const char* KindName(char kind) {
  return kind == 'v' ? "position ('v')" : (kind == 't' ? "uv ('vt')" : "normal ('vn')");
}

class ObjValidator {
 public:
  explicit ObjValidator(const std::string& name) : name_(name) {}

  // Checks every line; fills counts_. Returns the first error.
  Status Run(std::string_view text) {
    size_t line_number = 0;
    size_t pos = 0;
    do {  // an empty file is one empty line; a final '\n' does not start a new line
      size_t end = text.find('\n', pos);
      if (end == std::string_view::npos) end = text.size();
      ++line_number;
      PTLAB_RETURN_IF_ERROR(CheckLine(text.substr(pos, end - pos), line_number));
      pos = end + 1;
    } while (pos < text.size());
    for (const PendingIndex& p : pending_) {
      const size_t count =
          p.kind == 'v' ? counts_.positions : (p.kind == 't' ? counts_.uvs : counts_.normals);
      if (size_t(p.index) > count)
        return Error(p.line, "face vertex " + std::to_string(p.vertex) + " refers to " +
                                 KindName(p.kind) + " " + std::to_string(p.index) +
                                 ", but the file defines only " + std::to_string(count) +
                                 "; expected an index in 1.." + std::to_string(count));
    }
    if (counts_.faces == 0)
      return Error(line_number,
                   "reached the end of the file without a face; expected at least one 'f' line");
    return Status::Ok();
  }

  const ObjCounts& counts() const { return counts_; }

 private:
  Status Error(size_t line, const std::string& message) const {
    return Status::Error(name_ + ":" + std::to_string(line) + ": " + message);
  }

  Status CheckNumbers(const std::vector<std::string_view>& words, size_t line, size_t min_count,
                      size_t max_count, const char* expected, float* values) {
    const size_t count = words.size() - 1;
    if (count < min_count || count > max_count)
      return Error(line, "expected " + std::string(expected) + ", found " + std::to_string(count) +
                             " number(s)");
    for (size_t i = 1; i < words.size(); ++i) {
      float v = 0;
      if (!ParseFloat(words[i], &v))
        return Error(line, "malformed number '" + std::string(words[i]) +
                               "'; expected a finite decimal number in '" + expected + "'");
      if (i <= 3) values[i - 1] = v;
    }
    return Status::Ok();
  }

  Status CheckLine(std::string_view line, size_t line_number) {
    const std::vector<std::string_view> words = SplitWords(line);
    if (words.empty() || words[0][0] == '#') return Status::Ok();
    const std::string_view key = words[0];
    float xyz[3] = {0, 0, 0};
    if (key == "v") {
      // 3 coordinates, optionally w, or 3 coordinates and an RGB colour.
      PTLAB_RETURN_IF_ERROR(CheckNumbers(words, line_number, 3, 6, "v x y z", xyz));
      if (words.size() - 1 == 5)
        return Error(line_number,
                     "expected 'v x y z', 'v x y z w' or 'v x y z r g b', found 5 "
                     "numbers");
      ++counts_.positions;
    } else if (key == "vn") {
      PTLAB_RETURN_IF_ERROR(CheckNumbers(words, line_number, 3, 3, "vn x y z", xyz));
      if (!(xyz[0] != 0 || xyz[1] != 0 || xyz[2] != 0))
        return Error(line_number, "expected a non-zero normal 'vn x y z', found 0 0 0");
      ++counts_.normals;
    } else if (key == "vt") {
      PTLAB_RETURN_IF_ERROR(CheckNumbers(words, line_number, 2, 3, "vt u v", xyz));
      ++counts_.uvs;
    } else if (key == "f") {
      PTLAB_RETURN_IF_ERROR(CheckFace(words, line_number));
      ++counts_.faces;
    } else if (key == "o" || key == "g" || key == "s" || key == "mtllib" || key == "usemtl" ||
               key == "l" || key == "p") {
      // Names, smoothing groups, materials, lines and points do not make triangles.
    } else {
      return Error(line_number, "unknown OBJ statement '" + std::string(key) +
                                    "'; expected v, vn, vt, f, o, g, s, mtllib, usemtl, l or p");
    }
    return Status::Ok();
  }

  Status CheckIndex(std::string_view text, char kind, int vertex, size_t line) {
    int index = 0;
    if (!ParseInt(text, &index) || index == 0)
      return Error(line, "malformed " + std::string(KindName(kind)) + " index '" +
                             std::string(text) + "' in face vertex " + std::to_string(vertex) +
                             "; expected a non-zero integer");
    if (index < 0) {
      const size_t defined =
          kind == 'v' ? counts_.positions : (kind == 't' ? counts_.uvs : counts_.normals);
      if (size_t(-int64_t(index)) > defined)
        return Error(line, "face vertex " + std::to_string(vertex) + " refers to " +
                               KindName(kind) + " " + std::to_string(index) + ", but only " +
                               std::to_string(defined) +
                               " are defined above; expected an "
                               "index in -" +
                               std::to_string(defined) + "..-1");
    } else {
      pending_.push_back({line, index, vertex, kind});
    }
    return Status::Ok();
  }

  Status CheckFace(const std::vector<std::string_view>& words, size_t line) {
    if (words.size() < 4)
      return Error(line, "expected a face with at least 3 vertices 'f a b c', found " +
                             std::to_string(words.size() - 1));
    for (size_t k = 1; k < words.size(); ++k) {
      const int vertex = int(k);
      const std::string_view w = words[k];
      const size_t slash1 = w.find('/');
      const size_t slash2 = slash1 == std::string_view::npos ? slash1 : w.find('/', slash1 + 1);
      if (slash2 != std::string_view::npos && w.find('/', slash2 + 1) != std::string_view::npos)
        return Error(
            line, "malformed face vertex '" + std::string(w) + "'; expected p, p/t, p//n or p/t/n");
      const std::string_view p = w.substr(0, slash1);
      std::string_view t, n;
      if (slash1 != std::string_view::npos) {
        t = slash2 == std::string_view::npos ? w.substr(slash1 + 1)
                                             : w.substr(slash1 + 1, slash2 - slash1 - 1);
        if (slash2 != std::string_view::npos) {
          n = w.substr(slash2 + 1);
          if (n.empty())
            return Error(line, "malformed face vertex '" + std::string(w) +
                                   "'; expected p, p/t, p//n or p/t/n");
        } else if (t.empty()) {
          return Error(line, "malformed face vertex '" + std::string(w) +
                                 "'; expected p, p/t, p//n or p/t/n");
        }
      }
      PTLAB_RETURN_IF_ERROR(CheckIndex(p, 'v', vertex, line));
      if (!t.empty()) PTLAB_RETURN_IF_ERROR(CheckIndex(t, 't', vertex, line));
      if (!n.empty()) PTLAB_RETURN_IF_ERROR(CheckIndex(n, 'n', vertex, line));
      // Nori needs every vertex of a mesh to have the same attributes; so do we.
      const int format = (t.empty() ? 0 : 1) | (n.empty() ? 0 : 2);
      if (format_line_ == 0) {
        format_ = format, format_line_ = line;
      } else if (format != format_) {
        static const char* const kFormats[4] = {"p", "p/t", "p//n", "p/t/n"};
        return Error(line, "face vertex '" + std::string(w) + "' is written " + kFormats[format] +
                               "; expected " + kFormats[format_] +
                               " like the first face vertex (line " + std::to_string(format_line_) +
                               ")");
      }
    }
    return Status::Ok();
  }

  const std::string& name_;
  ObjCounts counts_;
  std::vector<PendingIndex> pending_;
  int format_ = 0;
  size_t format_line_ = 0;
};

struct VertexKey {
  int p, t, n;
  bool operator==(const VertexKey&) const = default;
};
struct VertexKeyHash {
  size_t operator()(const VertexKey& k) const {
    uint64_t h = uint64_t(uint32_t(k.p)) * 0x9E3779B97F4A7C15ull;
    h ^= (uint64_t(uint32_t(k.t)) + 0x632BE59BD9B4E019ull + (h << 6) + (h >> 2));
    h ^= (uint64_t(uint32_t(k.n)) + 0x85EBCA77C2B2AE63ull + (h << 6) + (h >> 2));
    return size_t(h);
  }
};

}  // namespace

// One definition of a line for the validator and tinyobjloader: "\r\n" (DOS), a lone "\r"
// (classic Mac) and "\n" all end a line. tinyobjloader only knows the first and the last, so
// the text both readers see has "\n" alone.
std::string NormalizeLineEnds(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\r') {
      out.push_back(text[i]);
    } else if (i + 1 >= text.size() || text[i + 1] != '\n') {
      out.push_back('\n');
    }
  }
  return out;
}

StatusOr<MeshData> LoadObjFromString(const std::string& raw_text,
                                     const std::string& display_name) {
  const std::string text = NormalizeLineEnds(raw_text);
  ObjValidator validator(display_name);
  PTLAB_RETURN_IF_ERROR(validator.Run(text));
  const ObjCounts& counts = validator.counts();

  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // we fan-triangulate ourselves, in Nori's vertex order
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, "", config))
    return Status::Error(display_name + ": tinyobjloader failed: " + reader.Error());
  const tinyobj::attrib_t& attrib = reader.GetAttrib();

  size_t faces = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes())
    faces += shape.mesh.num_face_vertices.size();
  // The validation pass and tinyobjloader must agree on what the file holds.
  if (attrib.vertices.size() != 3 * counts.positions ||
      attrib.normals.size() != 3 * counts.normals || attrib.texcoords.size() != 2 * counts.uvs ||
      faces != counts.faces)
    return Status::Error(display_name + ": tinyobjloader read " +
                         std::to_string(attrib.vertices.size() / 3) + " positions and " +
                         std::to_string(faces) + " faces where " +
                         std::to_string(counts.positions) + " and " + std::to_string(counts.faces) +
                         " were expected");

  MeshData mesh;
  std::unordered_map<VertexKey, uint32_t, VertexKeyHash> vertex_of;
  std::vector<uint32_t> polygon;
  bool has_uvs = false, has_normals = false;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    size_t next = 0;
    for (const unsigned int face_size : shape.mesh.num_face_vertices) {
      polygon.clear();
      for (unsigned int k = 0; k < face_size; ++k) {
        const tinyobj::index_t& idx = shape.mesh.indices[next++];
        const VertexKey key{idx.vertex_index, idx.texcoord_index, idx.normal_index};
        auto [it, inserted] = vertex_of.try_emplace(key, uint32_t(mesh.positions.size()));
        if (inserted) {
          const size_t p = size_t(key.p);
          mesh.positions.push_back(
              {attrib.vertices[3 * p], attrib.vertices[3 * p + 1], attrib.vertices[3 * p + 2]});
          if (key.t >= 0) {
            has_uvs = true;
            const size_t t = size_t(key.t);
            mesh.uvs.push_back({attrib.texcoords[2 * t], attrib.texcoords[2 * t + 1]});
          }
          if (key.n >= 0) {
            has_normals = true;
            const size_t n = size_t(key.n);
            mesh.normals.push_back(
                {attrib.normals[3 * n], attrib.normals[3 * n + 1], attrib.normals[3 * n + 2]});
          }
        }
        polygon.push_back(it->second);
      }
      for (size_t k = 1; k + 1 < polygon.size(); ++k) {
        mesh.indices.push_back(polygon[0]);
        mesh.indices.push_back(polygon[k]);
        mesh.indices.push_back(polygon[k + 1]);
      }
    }
  }
  // The validator made the face vertex format uniform, so these are all-or-nothing.
  PTLAB_CHECK(!has_uvs || mesh.uvs.size() == mesh.positions.size());
  PTLAB_CHECK(!has_normals || mesh.normals.size() == mesh.positions.size());
  return mesh;
}

StatusOr<MeshData> LoadObj(const std::string& path) {
  std::string text;
  PTLAB_RETURN_IF_ERROR(ReadTextFile(path, "OBJ file", &text));
  return LoadObjFromString(text, path);
}

}  // namespace ptlab
