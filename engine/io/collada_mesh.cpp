// COLLADA mesh reading: sources through accessors, <vertices>, and the primitive index lists.
#include "engine/io/collada_mesh.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string_view>
#include <unordered_map>

#include "engine/io/text_parsing.h"

namespace ptlab::collada {
namespace {

bool ParseIntToken(std::string_view text, int* v) { return ParseInt(text, v); }

// A source's values through its accessor: element i is values[i * width .. + width).
struct SourceData {
  std::vector<float> values;
  size_t count = 0;
  int width = 0;
};

// Reads <source> through <technique_common><accessor>, keeping the first `width` params.
Status ReadSource(const Document& doc, const pugi::xml_node& source, int width,
                  SourceData* out) {
  PTLAB_RETURN_IF_ERROR(doc.CheckChildren(source, {"float_array", "technique_common", "asset"},
                                          /*extras=*/true));
  const pugi::xml_node accessor = source.child("technique_common").child("accessor");
  if (!accessor)
    return doc.Error(source, "<source> has no <technique_common><accessor>; expected one");
  PTLAB_RETURN_IF_ERROR(doc.CheckChildren(source.child("technique_common"), {"accessor"}));
  PTLAB_RETURN_IF_ERROR(doc.CheckChildren(accessor, {"param"}));
  pugi::xml_node array;
  PTLAB_RETURN_IF_ERROR(doc.Resolve(accessor, "source", "float_array", &array));
  std::vector<float> values;
  PTLAB_RETURN_IF_ERROR(doc.Floats(array, &values));
  if (const pugi::xml_attribute count = array.attribute("count");
      count && count.as_ullong() != values.size())
    return doc.Error(array, std::string("<float_array> count=\"") + std::string(count.value()) + "\" but it holds " +
                                std::to_string(values.size()) + " numbers");
  const auto attr = [&](const char* name, long long fallback, long long* v) -> Status {
    const pugi::xml_attribute a = accessor.attribute(name);
    if (!a) {
      if (fallback < 0)
        return doc.Error(accessor, std::string("<accessor> has no '") + name + "' attribute");
      *v = fallback;
      return Status::Ok();
    }
    int parsed = 0;
    if (!ParseIntToken(a.value(), &parsed) || parsed < 0)
      return doc.Error(accessor, std::string("<accessor> ") + name + "=\"" + a.value() +
                                     "\" is not an integer >= 0");
    *v = parsed;
    return Status::Ok();
  };
  long long count = 0, stride = 0, offset = 0;
  PTLAB_RETURN_IF_ERROR(attr("count", -1, &count));
  PTLAB_RETURN_IF_ERROR(attr("stride", 1, &stride));
  PTLAB_RETURN_IF_ERROR(attr("offset", 0, &offset));
  long long params = 0;
  for (const pugi::xml_node p : accessor.children("param")) (void)p, ++params;
  if (params < width)
    return doc.Error(accessor, "<accessor> has " + std::to_string(params) +
                                   " <param>s; expected at least " + std::to_string(width));
  if (stride < params)
    return doc.Error(accessor, "<accessor> stride=\"" + std::to_string(stride) +
                                   "\" is smaller than its " + std::to_string(params) +
                                   " params; expected stride >= the number of params");
  if (count > 0 && offset + (count - 1) * stride + params > (long long)values.size())
    return doc.Error(accessor, "<accessor> count=\"" + std::to_string(count) + "\" stride=\"" +
                                   std::to_string(stride) + "\" offset=\"" +
                                   std::to_string(offset) + "\" reaches past the " +
                                   std::to_string(values.size()) + " numbers of <float_array> at " +
                                   doc.at.At(array));
  out->count = size_t(count);
  out->width = width;
  out->values.resize(size_t(count) * size_t(width));
  for (long long i = 0; i < count; ++i)
    for (int k = 0; k < width; ++k)
      out->values[size_t(i) * width + k] = values[size_t(offset + i * stride + k)];
  return Status::Ok();
}

// One input of a primitive: which source, and where its index sits in a vertex tuple.
struct Input {
  const SourceData* source = nullptr;
  uint32_t offset = 0;
  pugi::xml_node node;
};

struct PrimitiveInputs {
  Input position, normal, texcoord;
  uint32_t tuple_size = 0;
};

class MeshReader {
 public:
  MeshReader(const Document& doc, const pugi::xml_node& mesh) : doc_(doc), mesh_(mesh) {}

  Status Read(std::vector<MeshPart>* parts) {
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(
        mesh_, {"source", "vertices", "polylist", "triangles", "polygons"}, /*extras=*/false));
    for (const pugi::xml_node child : mesh_.children()) {
      const std::string_view name = child.name();
      if (name == "polylist" || name == "triangles" || name == "polygons") {
        MeshPart part;
        part.node = child;
        part.material_symbol = child.attribute("material").value();
        PTLAB_RETURN_IF_ERROR(ReadPrimitive(child, &part.mesh));
        parts->push_back(std::move(part));
      }
    }
    if (parts->empty())
      return doc_.Error(mesh_, "<mesh> has no polylist, triangles or polygons; expected one");
    return Status::Ok();
  }

 private:
  // The source named by an <input source="#id">, read once.
  Status SourceOf(const pugi::xml_node& input, int width, const SourceData** out) {
    pugi::xml_node source;
    PTLAB_RETURN_IF_ERROR(doc_.Resolve(input, "source", "source", &source));
    if (source.parent() != mesh_)
      return doc_.Error(input, std::string("source=\"") + std::string(input.attribute("source").value()) +
                                   "\" names a <source> of another <mesh>");
    auto it = sources_.find(source.offset_debug());
    if (it == sources_.end()) {
      SourceData data;
      PTLAB_RETURN_IF_ERROR(ReadSource(doc_, source, width, &data));
      it = sources_.emplace(source.offset_debug(), std::move(data)).first;
    } else if (it->second.width != width) {
      return doc_.Error(input, "the <source> is used as both a " + std::to_string(width) +
                                   "- and a " + std::to_string(it->second.width) +
                                   "-component input");
    }
    *out = &it->second;
    return Status::Ok();
  }

  // Assigns a POSITION / NORMAL / TEXCOORD input (from <vertices> or the primitive).
  Status TakeInput(const pugi::xml_node& input, uint32_t offset, PrimitiveInputs* in) {
    const std::string_view semantic = input.attribute("semantic").value();
    Input* slot = nullptr;
    int width = 3;
    if (semantic == "POSITION") slot = &in->position;
    else if (semantic == "NORMAL") slot = &in->normal;
    else if (semantic == "TEXCOORD") slot = &in->texcoord, width = 2;
    else return doc_.NotSupported(input, std::string("input semantic \"") + std::string(semantic) + "\"");
    if (slot->source) {
      // Several texture coordinate sets: the first is used (CS184 reads set 0 only).
      if (semantic == "TEXCOORD") return Status::Ok();
      return doc_.Error(input, std::string("a second ") + std::string(semantic) + " input; expected one");
    }
    PTLAB_RETURN_IF_ERROR(SourceOf(input, width, &slot->source));
    slot->offset = offset;
    slot->node = input;
    return Status::Ok();
  }

  Status ReadInputs(const pugi::xml_node& prim, PrimitiveInputs* in) {
    uint32_t max_offset = 0;
    for (const pugi::xml_node input : prim.children("input")) {
      int offset = 0;
      if (!ParseIntToken(input.attribute("offset").value(), &offset) || offset < 0)
        return doc_.Error(input, "<input> offset=\"" +
                                     std::string(input.attribute("offset").value()) +
                                     "\" is not an integer >= 0");
      max_offset = std::max(max_offset, uint32_t(offset));
      if (std::string_view(input.attribute("semantic").value()) == "VERTEX") {
        pugi::xml_node vertices;
        PTLAB_RETURN_IF_ERROR(doc_.Resolve(input, "source", "vertices", &vertices));
        PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(vertices, {"input"}, /*extras=*/true));
        for (const pugi::xml_node v : vertices.children("input"))
          PTLAB_RETURN_IF_ERROR(TakeInput(v, uint32_t(offset), in));
      } else {
        PTLAB_RETURN_IF_ERROR(TakeInput(input, uint32_t(offset), in));
      }
    }
    if (!in->position.source)
      return doc_.Error(prim, std::string("<") + std::string(prim.name()) +
                                  "> has no VERTEX input with a POSITION; expected one");
    in->tuple_size = max_offset + 1;
    return Status::Ok();
  }

  Status ReadPrimitive(const pugi::xml_node& prim, MeshData* mesh) {
    const std::string_view kind = prim.name();
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(
        prim, kind == "polylist" ? std::initializer_list<std::string_view>{"input", "vcount", "p"}
                                 : std::initializer_list<std::string_view>{"input", "p"},
        /*extras=*/true));
    PrimitiveInputs in;
    PTLAB_RETURN_IF_ERROR(ReadInputs(prim, &in));
    int count = 0;
    if (!ParseIntToken(prim.attribute("count").value(), &count) || count < 0)
      return doc_.Error(prim, std::string("<") + std::string(kind) + "> count=\"" +
                                  std::string(prim.attribute("count").value()) +
                                  "\" is not an integer >= 0");
    // Polygon sizes and the index list, whatever the primitive kind.
    std::vector<uint32_t> sizes, indices;
    const auto index_mismatch = [&](uint64_t corners) {
      return doc_.Error(
          prim, std::string("<") + std::string(kind) + "> has " + std::to_string(indices.size()) +
                    " indices; its " + std::to_string(count) + " polygons of " +
                    std::to_string(corners) + " corners with " + std::to_string(in.tuple_size) +
                    " inputs need " + std::to_string(corners * in.tuple_size));
    };
    if (kind == "polygons") {
      for (const pugi::xml_node p : prim.children("p")) {
        std::vector<uint32_t> one;
        PTLAB_RETURN_IF_ERROR(doc_.Indices(p, &one));
        if (one.size() % in.tuple_size != 0)
          return doc_.Error(p, "<p> holds " + std::to_string(one.size()) +
                                   " indices; expected a multiple of " +
                                   std::to_string(in.tuple_size) + " (one per input offset)");
        sizes.push_back(uint32_t(one.size() / in.tuple_size));
        indices.insert(indices.end(), one.begin(), one.end());
      }
    } else {
      const pugi::xml_node p = prim.child("p");
      if (!p && count > 0) return doc_.Error(prim, std::string("<") + std::string(kind) + "> has no <p>");
      if (p) PTLAB_RETURN_IF_ERROR(doc_.Indices(p, &indices));
      if (kind == "triangles") {
        // The count is the file's: checked against the index list before it sizes anything (a
        // count of 10^9 with a short <p> asked for 4 GiB of polygon sizes; found by fuzzing).
        if (3 * uint64_t(count) * in.tuple_size != indices.size())
          return index_mismatch(3 * uint64_t(count));
        sizes.assign(size_t(count), 3);
      } else {
        const pugi::xml_node vcount = prim.child("vcount");
        if (!vcount && count > 0) return doc_.Error(prim, "<polylist> has no <vcount>");
        if (vcount) PTLAB_RETURN_IF_ERROR(doc_.Indices(vcount, &sizes));
      }
    }
    if (sizes.size() != size_t(count))
      return doc_.Error(prim, std::string("<") + std::string(kind) + "> count=\"" + std::to_string(count) +
                                  "\" but it lists " + std::to_string(sizes.size()) +
                                  " polygons");
    uint64_t corners = 0;
    for (uint32_t s : sizes) corners += s;
    if (corners * in.tuple_size != indices.size()) return index_mismatch(corners);
    return Triangulate(prim, in, sizes, indices, mesh);
  }

  // An index of input `input` at corner `c`, checked against its source.
  Status IndexOf(const pugi::xml_node& prim, const Input& input, const std::vector<uint32_t>& idx,
                 size_t c, uint32_t tuple, uint32_t* out) {
    const uint32_t i = idx[c * tuple + input.offset];
    if (i >= input.source->count)
      return doc_.Error(prim, "index " + std::to_string(i) + " of corner " + std::to_string(c) +
                                  std::string(" (") + std::string(input.node.attribute("semantic").value()) +
                                  " input at " + doc_.at.At(input.node) +
                                  ") is out of range; its source has " +
                                  std::to_string(input.source->count) + " elements");
    *out = i;
    return Status::Ok();
  }

  Status Triangulate(const pugi::xml_node& prim, const PrimitiveInputs& in,
                     const std::vector<uint32_t>& sizes, const std::vector<uint32_t>& idx,
                     MeshData* mesh) {
    std::map<std::array<uint32_t, 3>, uint32_t> vertex_of;
    std::vector<uint32_t> corner_vertex(idx.size() / in.tuple_size);
    for (size_t c = 0; c < corner_vertex.size(); ++c) {
      std::array<uint32_t, 3> key = {0, 0, 0};
      PTLAB_RETURN_IF_ERROR(IndexOf(prim, in.position, idx, c, in.tuple_size, &key[0]));
      if (in.normal.source)
        PTLAB_RETURN_IF_ERROR(IndexOf(prim, in.normal, idx, c, in.tuple_size, &key[1]));
      if (in.texcoord.source)
        PTLAB_RETURN_IF_ERROR(IndexOf(prim, in.texcoord, idx, c, in.tuple_size, &key[2]));
      const auto [it, added] = vertex_of.emplace(key, uint32_t(mesh->positions.size()));
      if (added) {
        const float* p = &in.position.source->values[size_t(key[0]) * 3];
        mesh->positions.push_back({p[0], p[1], p[2]});
        if (in.normal.source) {
          const float* n = &in.normal.source->values[size_t(key[1]) * 3];
          const Vec3f normal{n[0], n[1], n[2]};
          const float len = Length(normal);
          if (!(len > 1e-12f) || !std::isfinite(len))
            return doc_.Error(in.normal.node, "normal " + std::to_string(key[1]) +
                                                  " is zero or not finite; expected non-zero "
                                                  "normals");
          mesh->normals.push_back(normal / len);
        }
        if (in.texcoord.source) {
          const float* t = &in.texcoord.source->values[size_t(key[2]) * 2];
          mesh->uvs.push_back({t[0], t[1]});
        }
      }
      corner_vertex[c] = it->second;
    }
    size_t first = 0;
    for (size_t k = 0; k < sizes.size(); ++k) {
      if (sizes[k] < 3)
        return doc_.Error(prim, "polygon " + std::to_string(k) + " has " +
                                    std::to_string(sizes[k]) + " vertices; expected at least 3");
      for (uint32_t j = 1; j + 1 < sizes[k]; ++j)
        mesh->indices.insert(mesh->indices.end(),
                             {corner_vertex[first], corner_vertex[first + j],
                              corner_vertex[first + j + 1]});
      first += sizes[k];
    }
    return Status::Ok();
  }

  const Document& doc_;
  pugi::xml_node mesh_;
  std::map<ptrdiff_t, SourceData> sources_;
};

}  // namespace

StatusOr<Geometry> ReadGeometry(const Document& doc, const pugi::xml_node& geometry) {
  PTLAB_RETURN_IF_ERROR(doc.CheckChildren(geometry, {"mesh", "asset"}, /*extras=*/true));
  Geometry g;
  if (const pugi::xml_node mesh = geometry.child("mesh")) {
    MeshReader reader(doc, mesh);
    PTLAB_RETURN_IF_ERROR(reader.Read(&g.parts));
    return g;
  }
  const pugi::xml_node cgl = doc.CglTechnique(geometry);
  if (!cgl)
    return doc.NotSupported(geometry, "a geometry without <mesh> or a CGL <sphere>");
  PTLAB_RETURN_IF_ERROR(doc.CheckChildren(cgl, {"sphere"}));
  const pugi::xml_node sphere = cgl.child("sphere");
  if (!sphere) return doc.NotSupported(geometry, "a CGL technique without <sphere>");
  PTLAB_RETURN_IF_ERROR(doc.CheckChildren(sphere, {"radius"}));
  if (!sphere.child("radius")) return doc.Error(sphere, "<sphere> has no <radius>");
  PTLAB_RETURN_IF_ERROR(doc.FixedFloats(sphere.child("radius"), 1, &g.sphere_radius));
  if (!(g.sphere_radius > 0))
    return doc.Error(sphere.child("radius"), "the sphere radius must be > 0");
  g.is_sphere = true;
  return g;
}

}  // namespace ptlab::collada
