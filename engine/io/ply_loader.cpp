// Stanford PLY loading: the body's rows into MeshData and Mitsuba's attribute grouping (the
// header is read by ply_header, the values by ply_readers).
#include "engine/io/ply_loader.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/core/input_file.h"
#include "engine/image/srgb.h"
#include "engine/io/ply_header.h"
#include "engine/io/ply_readers.h"

namespace ptlab {
namespace {

using namespace ply;  // PlyType, Element, Header, ParseHeader, AsciiReader, BinaryReader

// What a vertex or face property is used for.
enum class Role { kX, kY, kZ, kNx, kNy, kNz, kU, kV, kIndices, kAttribute, kSkip };

struct Column {
  Role role = Role::kSkip;
  int attribute = -1, channel = 0;
};

// Groups the attribute properties of `e` (those whose column role is kAttribute) into
// MeshAttributes as Mitsuba does (see ply_loader.h), appended to `attributes`; fills
// columns[i].attribute (counted from the first attribute appended here) and channel.
void GroupAttributes(const Element& e, const std::string& domain, std::vector<Column>* columns,
                     std::vector<MeshAttribute>* attributes, std::vector<bool>* integer_attr) {
  static constexpr std::string_view kSchemes[4][4] = {
      {"x", "y", "z", "w"}, {"r", "g", "b", "a"}, {"0", "1", "2", "3"}, {"1", "2", "3", "4"}};
  static constexpr std::string_view kColorSchemes[2][4] = {{"r", "g", "b", "a"},
                                                           {"red", "green", "blue", "alpha"}};
  const size_t n = e.props.size(), base = attributes->size();
  size_t i = 0;
  while (i < n) {
    if ((*columns)[i].role != Role::kAttribute) {
      ++i;
      continue;
    }
    const std::string& name = e.props[i].name;
    std::string group_name = domain + "_" + name;
    size_t length = 1;
    // A prefix-less colour: r g b [a] or red green blue [alpha].
    for (const auto& scheme : kColorSchemes) {
      if (name != scheme[0]) continue;
      size_t k = 1;
      while (k < 4 && i + k < n && (*columns)[i + k].role == Role::kAttribute &&
             e.props[i + k].name == scheme[k])
        ++k;
      group_name = domain + "_color";
      length = k;
    }
    const size_t underscore = name.rfind('_');
    if (length == 1 && underscore != std::string::npos && underscore > 0) {
      const std::string prefix = name.substr(0, underscore);
      const std::string_view suffix = std::string_view(name).substr(underscore + 1);
      for (const auto& scheme : kSchemes) {
        if (suffix != scheme[0]) continue;
        size_t k = 1;
        while (k < 4 && i + k < n && (*columns)[i + k].role == Role::kAttribute &&
               e.props[i + k].name == prefix + "_" + std::string(scheme[k]))
          ++k;
        group_name = domain + "_" + prefix;
        length = k;
        break;
      }
    }
    MeshAttribute a;
    a.name = group_name;
    a.dim = uint32_t(length);
    const int index = int(attributes->size() - base);
    for (size_t k = 0; k < length; ++k) {
      (*columns)[i + k].attribute = index;
      (*columns)[i + k].channel = int(k);
    }
    integer_attr->push_back(IsInteger(e.props[i].type));
    attributes->push_back(std::move(a));
    i += length;
  }
}

// An attribute value as Mitsuba stores it: integers normalised and decoded from sRGB.
float AttributeValue(double v, PlyType t) {
  if (!IsInteger(t)) return float(v);
  const double x = v / TypeMax(t);
  return x < 0 ? -SrgbToLinear(float(-x)) : SrgbToLinear(float(x));
}

template <class Reader>
class BodyParser {
 public:
  BodyParser(Reader* reader, const std::string& name) : r_(*reader), name_(name) {}

  Status Parse(const Header& h, MeshData* mesh) {
    const Element* vertex = nullptr;
    for (const Element& e : h.elements)
      if (e.name == "vertex") vertex = &e;
    if (vertex == nullptr) return Status::Error(name_ + ": the header has no element 'vertex'");
    if (vertex->count > uint64_t(UINT32_MAX))
      return Status::Error(name_ + ":" + std::to_string(vertex->line) + ": " +
                           std::to_string(vertex->count) +
                           " vertices; expected at most 4294967295");
    vertex_count_ = vertex->count;
    bool have_faces = false;
    for (const Element& e : h.elements) {
      if (e.count > 0 && e.props.empty())
        return Status::Error(name_ + ":" + std::to_string(e.line) + ": element '" + e.name +
                             "' has rows but no properties");
      // Every row takes at least MinRowBytes: a count that the bytes left cannot hold is an
      // error before anything is allocated for it.
      const uint64_t min_row = r_.MinRowBytes(e);
      if (min_row > 0 && e.count > r_.Remaining() / min_row)
        return Status::Error(r_.Where() + ": element '" + e.name + "' declares " +
                             std::to_string(e.count) + " rows (header line " +
                             std::to_string(e.line) + "), but only " +
                             std::to_string(r_.Remaining()) + " bytes are left");
      Status s;
      if (e.name == "vertex") {
        s = ReadVertices(e, mesh);
      } else if (e.name == "face") {
        have_faces = true;
        s = ReadFaces(e, mesh);
      } else {
        s = SkipRows(e);
      }
      if (!s.ok()) return s;
    }
    if (!have_faces) return Status::Error(name_ + ": the header has no element 'face'");
    if (!r_.AtEnd())
      return Status::Error(r_.Where() + ": expected the end of the file after the last element");
    if (mesh->indices.empty()) return Status::Error(name_ + ": the mesh has no faces");
    return Status::Ok();
  }

 private:
  Status ValueError(const Element& e, uint64_t row, const Property& p, PlyType t,
                    const char* what) {
    return Status::Error(r_.Where() + ": expected " + what + " (" + TypeName(t) +
                         ") for property '" + p.name + "' of " + e.name + " " +
                         std::to_string(row) + ", " + r_.Found());
  }

  Status SkipList(const Element& e, uint64_t row, const Property& p) {
    double count = 0;
    if (!r_.Read(p.count_type, &count)) return ValueError(e, row, p, p.count_type, "a list count");
    if (count < 0)
      return Status::Error(r_.Where() + ": negative list count for property '" + p.name + "'");
    double v = 0;
    for (uint64_t k = 0; k < uint64_t(count); ++k)
      if (!r_.Read(p.type, &v)) return ValueError(e, row, p, p.type, "a list item");
    return Status::Ok();
  }

  Status SkipRows(const Element& e) {
    double v = 0;
    for (uint64_t row = 0; row < e.count; ++row) {
      for (const Property& p : e.props) {
        if (p.list) {
          const Status s = SkipList(e, row, p);
          if (!s.ok()) return s;
        } else if (!r_.Read(p.type, &v)) {
          return ValueError(e, row, p, p.type, "a number");
        }
      }
    }
    return Status::Ok();
  }

  Status ReadVertices(const Element& e, MeshData* mesh) {
    std::vector<Column> columns(e.props.size());
    const auto find = [&](std::string_view n) -> int {
      for (size_t i = 0; i < e.props.size(); ++i)
        if (e.props[i].name == n && !e.props[i].list) return int(i);
      return -1;
    };
    const int x = find("x"), y = find("y"), z = find("z");
    if (x < 0 || y < 0 || z < 0)
      return Status::Error(name_ + ":" + std::to_string(e.line) +
                           ": element 'vertex' needs scalar properties x, y and z");
    columns[size_t(x)].role = Role::kX;
    columns[size_t(y)].role = Role::kY;
    columns[size_t(z)].role = Role::kZ;
    const int nx = find("nx"), ny = find("ny"), nz = find("nz");
    const bool has_normals = nx >= 0 && ny >= 0 && nz >= 0;
    if (!has_normals && (nx >= 0 || ny >= 0 || nz >= 0))
      return Status::Error(name_ + ":" + std::to_string(e.line) +
                           ": element 'vertex' has some of nx, ny, nz; expected all three or "
                           "none");
    if (has_normals) {
      columns[size_t(nx)].role = Role::kNx;
      columns[size_t(ny)].role = Role::kNy;
      columns[size_t(nz)].role = Role::kNz;
    }
    bool has_uvs = false;
    for (const auto& [un, vn] :
         {std::pair{"u", "v"}, std::pair{"s", "t"}, std::pair{"texture_u", "texture_v"},
          std::pair{"texture_s", "texture_t"}}) {
      const int u = find(un), v = find(vn);
      if (u < 0 || v < 0 || has_uvs) continue;
      columns[size_t(u)].role = Role::kU;
      columns[size_t(v)].role = Role::kV;
      has_uvs = true;
    }
    for (size_t i = 0; i < e.props.size(); ++i)
      if (columns[i].role == Role::kSkip && !e.props[i].list) columns[i].role = Role::kAttribute;
    const size_t first_attribute = mesh->attributes.size();
    std::vector<bool> integer_attr;
    GroupAttributes(e, "vertex", &columns, &mesh->attributes, &integer_attr);
    for (size_t a = first_attribute; a < mesh->attributes.size(); ++a)
      mesh->attributes[a].values.resize(size_t(e.count) * mesh->attributes[a].dim);

    mesh->positions.resize(size_t(e.count));
    if (has_normals) mesh->normals.resize(size_t(e.count));
    if (has_uvs) mesh->uvs.resize(size_t(e.count));
    for (uint64_t row = 0; row < e.count; ++row) {
      Vec3f& pos = mesh->positions[row];
      for (size_t i = 0; i < e.props.size(); ++i) {
        const Property& p = e.props[i];
        if (p.list) {
          const Status s = SkipList(e, row, p);
          if (!s.ok()) return s;
          continue;
        }
        double v = 0;
        if (!r_.Read(p.type, &v)) return ValueError(e, row, p, p.type, "a number");
        const float f = float(v);
        switch (columns[i].role) {
          case Role::kX:
            pos.x = f;
            break;
          case Role::kY:
            pos.y = f;
            break;
          case Role::kZ:
            pos.z = f;
            break;
          case Role::kNx:
            mesh->normals[row].x = f;
            break;
          case Role::kNy:
            mesh->normals[row].y = f;
            break;
          case Role::kNz:
            mesh->normals[row].z = f;
            break;
          case Role::kU:
            mesh->uvs[row].x = f;
            break;
          case Role::kV:
            mesh->uvs[row].y = f;
            break;
          case Role::kAttribute: {
            MeshAttribute& a = mesh->attributes[first_attribute + size_t(columns[i].attribute)];
            a.values[size_t(row) * a.dim + size_t(columns[i].channel)] = AttributeValue(v, p.type);
            break;
          }
          case Role::kIndices:
          case Role::kSkip:
            break;
        }
      }
      if (!(std::isfinite(pos.x) && std::isfinite(pos.y) && std::isfinite(pos.z)))
        return Status::Error(r_.Where() + ": vertex " + std::to_string(row) +
                             ": position is not finite");
      if (has_normals) {
        const Vec3f& n = mesh->normals[row];
        if (!(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z)) ||
            (n.x == 0 && n.y == 0 && n.z == 0))
          return Status::Error(r_.Where() + ": vertex " + std::to_string(row) +
                               ": normal is zero or not finite; expected a non-zero finite "
                               "vector");
      }
      if (has_uvs && !(std::isfinite(mesh->uvs[row].x) && std::isfinite(mesh->uvs[row].y)))
        return Status::Error(r_.Where() + ": vertex " + std::to_string(row) + ": uv is not finite");
    }
    return Status::Ok();
  }

  Status ReadFaces(const Element& e, MeshData* mesh) {
    std::vector<Column> columns(e.props.size());
    int index_prop = -1;
    for (size_t i = 0; i < e.props.size(); ++i) {
      const Property& p = e.props[i];
      if (p.list && (p.name == "vertex_indices" || p.name == "vertex_index") && index_prop < 0) {
        if (!IsInteger(p.type))
          return Status::Error(name_ + ":" + std::to_string(e.line) + ": list '" + p.name +
                               "' has items of type " + TypeName(p.type) +
                               "; expected an integer type");
        columns[i].role = Role::kIndices;
        index_prop = int(i);
      } else if (!p.list) {
        columns[i].role = Role::kAttribute;
      }
    }
    if (index_prop < 0)
      return Status::Error(name_ + ":" + std::to_string(e.line) +
                           ": element 'face' has no list property vertex_indices or "
                           "vertex_index");
    const size_t first_attribute = mesh->attributes.size();
    std::vector<bool> integer_attr;
    GroupAttributes(e, "face", &columns, &mesh->attributes, &integer_attr);
    std::vector<float> row_values;  // this face's attribute values, attribute by attribute
    std::vector<size_t> offsets;
    size_t total_dim = 0;
    for (size_t a = first_attribute; a < mesh->attributes.size(); ++a) {
      offsets.push_back(total_dim);
      total_dim += mesh->attributes[a].dim;
    }
    row_values.resize(total_dim);
    mesh->indices.reserve(size_t(e.count) * 3);
    std::vector<uint32_t> polygon;
    for (uint64_t row = 0; row < e.count; ++row) {
      for (size_t i = 0; i < e.props.size(); ++i) {
        const Property& p = e.props[i];
        if (columns[i].role == Role::kIndices) {
          double count = 0;
          if (!r_.Read(p.count_type, &count))
            return ValueError(e, row, p, p.count_type, "a vertex count");
          if (count < 3)
            return Status::Error(r_.Where() + ": face " + std::to_string(row) + " has " +
                                 std::to_string(int64_t(count)) + " vertices; expected 3 or more");
          // Checked before the polygon's storage grows: each index takes a byte at least.
          if (uint64_t(count) > r_.Remaining())
            return Status::Error(r_.Where() + ": face " + std::to_string(row) + " declares " +
                                 std::to_string(uint64_t(count)) +
                                 " vertices, more than the bytes left");
          polygon.resize(size_t(count));
          for (size_t k = 0; k < polygon.size(); ++k) {
            double v = 0;
            if (!r_.Read(p.type, &v)) return ValueError(e, row, p, p.type, "a vertex index");
            if (v < 0 || v >= double(vertex_count_))
              return Status::Error(r_.Where() + ": face " + std::to_string(row) +
                                   ": vertex index " + std::to_string(int64_t(v)) +
                                   " out of range; expected 0 to " +
                                   std::to_string(int64_t(vertex_count_) - 1));
            polygon[k] = uint32_t(v);
          }
        } else if (p.list) {
          const Status s = SkipList(e, row, p);
          if (!s.ok()) return s;
        } else {
          double v = 0;
          if (!r_.Read(p.type, &v)) return ValueError(e, row, p, p.type, "a number");
          if (columns[i].attribute >= 0)
            row_values[offsets[size_t(columns[i].attribute)] + size_t(columns[i].channel)] =
                AttributeValue(v, p.type);
        }
      }
      for (size_t k = 1; k + 1 < polygon.size(); ++k) {
        mesh->indices.insert(mesh->indices.end(), {polygon[0], polygon[k], polygon[k + 1]});
        for (size_t a = 0; a < offsets.size(); ++a) {
          MeshAttribute& attr = mesh->attributes[first_attribute + a];
          attr.values.insert(attr.values.end(), row_values.begin() + long(offsets[a]),
                             row_values.begin() + long(offsets[a] + attr.dim));
        }
      }
    }
    return Status::Ok();
  }

  Reader& r_;
  const std::string& name_;
  uint64_t vertex_count_ = 0;
};

}  // namespace

StatusOr<MeshData> LoadPlyFromBytes(const std::string& bytes, const std::string& display_name) {
  StatusOr<Header> header = ParseHeader(bytes, display_name);
  if (!header.ok()) return header.status();
  MeshData mesh;
  Status s;
  if (header->format == Header::Format::kAscii) {
    AsciiReader reader(bytes, header->body_offset, header->body_line, display_name);
    s = BodyParser<AsciiReader>(&reader, display_name).Parse(*header, &mesh);
  } else {
    BinaryReader reader(bytes, header->body_offset, header->format == Header::Format::kBinaryBig,
                        display_name);
    s = BodyParser<BinaryReader>(&reader, display_name).Parse(*header, &mesh);
  }
  if (!s.ok()) return s;
  return mesh;
}

StatusOr<MeshData> LoadPly(const std::string& path) {
  std::string bytes;
  const Status read = ReadInputFile(path, "PLY mesh", &bytes);
  if (!read.ok()) return read;
  return LoadPlyFromBytes(bytes, path);
}

}  // namespace ptlab
