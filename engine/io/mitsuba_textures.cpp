// Mitsuba <texture>s: bitmap, checkerboard and mesh_attribute, as rows of the scene's
// TextureTable (engine/scene/texture_tables.h), and their binding to a mesh's attributes.
#include <array>
#include <cmath>

#include "engine/image/texture_image.h"
#include "engine/io/mitsuba_scene_builder.h"
#include "engine/scene/material_textures.h"  // mask

namespace ptlab::internal {
namespace {

// Mitsuba's to_uv: the 4x4 transform's rows and columns 0, 1 and 3 (an affine map of the plane).
void SetToUv(TextureTable* t, uint32_t id, const Transform& to_uv) {
  const Matrix4& m = to_uv.matrix();
  t->m00[id] = m.m[0][0], t->m01[id] = m.m[0][1], t->m02[id] = m.m[0][3];
  t->m10[id] = m.m[1][0], t->m11[id] = m.m[1][1], t->m12[id] = m.m[1][3];
}

}  // namespace

namespace {

// Mitsuba's checkerboard gives a scalar parameter (Texture::eval_1) color0 where the two
// half-period tests differ, i.e. on the squares where its colour evaluation (eval) gives color1.
// A scalar parameter therefore reads a copy of the row with the two colours swapped, so that
// TexturedFloat (the luminance of EvalTexture) is Mitsuba's eval_1. Other kinds: the row itself.
uint32_t ScalarTextureRow(TextureTable* t, uint32_t id) {
  if (t->Kind(id) != TextureKind::kCheckerboard) return id;
  const uint32_t row = t->AddRow(TextureKind::kCheckerboard, 1, 1, 6);
  t->filter[row] = t->filter[id], t->wrap[row] = t->wrap[id];
  t->m00[row] = t->m00[id], t->m01[row] = t->m01[id], t->m02[row] = t->m02[id];
  t->m10[row] = t->m10[id], t->m11[row] = t->m11[id], t->m12[row] = t->m12[id];
  const size_t from = t->offset[id], to = t->offset[row];
  for (int k = 0; k < 3; ++k) {
    t->data[to + k] = t->data[from + 3 + k];
    t->data[to + 3 + k] = t->data[from + k];
  }
  return row;
}

}  // namespace

StatusOr<uint32_t> MitsubaSceneBuilder::ScalarTexture(const MitsubaNode& node) {
  if (const auto it = scalar_textures_.find(&node); it != scalar_textures_.end()) return it->second;
  StatusOr<uint32_t> texture = Texture(node);
  if (!texture.ok()) return texture.status();
  const uint32_t row = ScalarTextureRow(&scene_.textures, *texture);
  scalar_textures_[&node] = row;
  return row;
}

StatusOr<uint32_t> MitsubaSceneBuilder::Texture(const MitsubaNode& node) {
  if (const auto it = textures_.find(&node); it != textures_.end()) return it->second;
  StatusOr<MitsubaObject> read = Read(node);
  if (!read.ok()) return read.status();
  const MitsubaObject& obj = *read;
  const std::string& type = obj.type();
  TextureTable& t = scene_.textures;
  uint32_t id = kNoTexture;
  if (type == "bitmap") {
    PTLAB_RETURN_IF_ERROR(
        obj.Expect({"filename", "filter_type", "wrap_mode", "raw", "to_uv", "format", "accel"}));
    PTLAB_RETURN_IF_ERROR(obj.Require("filename"));
    std::string filename, filter = "bilinear", wrap = "repeat";
    bool raw = false;
    PTLAB_RETURN_IF_ERROR(obj.String("filename", &filename));
    PTLAB_RETURN_IF_ERROR(obj.String("filter_type", &filter));
    PTLAB_RETURN_IF_ERROR(obj.String("wrap_mode", &wrap));
    PTLAB_RETURN_IF_ERROR(obj.Boolean("raw", &raw));
    if (filter != "bilinear" && filter != "nearest")
      return obj.Error("filter_type", "unknown filter_type '" + filter +
                                          "'; expected bilinear or nearest");
    if (wrap != "repeat" && wrap != "mirror" && wrap != "clamp")
      return obj.Error("wrap_mode",
                       "unknown wrap_mode '" + wrap + "'; expected repeat, mirror or clamp");
    if (const MitsubaProperty* f = obj.Get("format"); f && f->text != "variant")
      return Unsupported(node, "format = " + f->text);
    Transform to_uv;
    PTLAB_RETURN_IF_ERROR(obj.TransformProperty("to_uv", &to_uv));
    StatusOr<std::string> path = Resolve(obj, "filename", filename);
    if (!path.ok()) return path.status();
    StatusOr<Image> image = ReadTextureImage(*path, raw);
    if (!image.ok()) return obj.Error("filename", image.status().message());
    scene_.input_files.push_back(*path);
    const size_t texels = size_t(image->width) * size_t(image->height);
    if (t.data.size() + 3 * texels >= (size_t(1) << 31))
      return obj.Error("filename", "the scene's textures exceed 2^31 floats");
    id = t.AddRow(TextureKind::kBitmap, uint32_t(image->width), uint32_t(image->height),
                  3 * texels);
    std::copy(image->rgb.begin(), image->rgb.end(), t.data.begin() + t.offset[id]);
    t.filter[id] = uint8_t(filter == "nearest" ? TextureFilter::kNearest : TextureFilter::kBilinear);
    t.wrap[id] = uint8_t(wrap == "mirror"  ? TextureWrap::kMirror
                         : wrap == "clamp" ? TextureWrap::kClamp
                                           : TextureWrap::kRepeat);
    SetToUv(&t, id, to_uv);
  } else if (type == "checkerboard") {
    PTLAB_RETURN_IF_ERROR(obj.Expect({"color0", "color1", "to_uv"}));
    Color3f c0{0.4f, 0.4f, 0.4f}, c1{0.2f, 0.2f, 0.2f};  // Mitsuba's defaults
    PTLAB_RETURN_IF_ERROR(obj.Color("color0", SpectrumUse::kReflectance, &c0));
    PTLAB_RETURN_IF_ERROR(obj.Color("color1", SpectrumUse::kReflectance, &c1));
    Transform to_uv;
    PTLAB_RETURN_IF_ERROR(obj.TransformProperty("to_uv", &to_uv));
    id = t.AddRow(TextureKind::kCheckerboard, 1, 1, 6);
    float* d = &t.data[t.offset[id]];
    d[0] = c0.r, d[1] = c0.g, d[2] = c0.b, d[3] = c1.r, d[4] = c1.g, d[5] = c1.b;
    SetToUv(&t, id, to_uv);
  } else if (type == "rawconstant") {  // normal: a constant value, used as is (raw)
    PTLAB_RETURN_IF_ERROR(obj.Expect({"value"}));
    PTLAB_RETURN_IF_ERROR(obj.Require("value"));
    const MitsubaProperty* p = obj.Get("value");
    Color3f c;
    if (p->type == MitsubaProperty::Type::kVector || p->type == MitsubaProperty::Type::kPoint) {
      Vec3f v;
      PTLAB_RETURN_IF_ERROR(obj.Vector("value", &v));
      c = {v.x, v.y, v.z};
    } else if (p->type == MitsubaProperty::Type::kRgb) {
      c = p->rgb;
    } else {
      float v = 0;
      PTLAB_RETURN_IF_ERROR(obj.Float("value", &v));
      c = {v, v, v};
    }
    if (!(std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b)))
      return obj.Error("value", "value must be finite");
    // A checkerboard of two equal colours: the same value at every uv (gradient 0).
    id = t.AddRow(TextureKind::kCheckerboard, 1, 1, 6);
    float* d = &t.data[t.offset[id]];
    d[0] = d[3] = c.r, d[1] = d[4] = c.g, d[2] = d[5] = c.b;
  } else if (type == "mesh_attribute") {
    PTLAB_RETURN_IF_ERROR(obj.Expect({"name", "scale"}));
    PTLAB_RETURN_IF_ERROR(obj.Require("name"));
    std::string name;
    PTLAB_RETURN_IF_ERROR(obj.String("name", &name));
    float scale = 1;
    PTLAB_RETURN_IF_ERROR(obj.Float("scale", &scale));
    if (scale != 1) return Unsupported(node, "scale != 1");
    const bool face = name.starts_with("face_");
    if (!face && !name.starts_with("vertex_"))
      return obj.Error("name", "mesh attribute name '" + name +
                                   "' must start with 'vertex_' or 'face_'");
    // No triangles yet: the shape that uses it binds its attribute (BindMeshAttribute).
    id = t.AddRow(face ? TextureKind::kFaceAttribute : TextureKind::kVertexAttribute, 0, 0, 0);
    attribute_names_[id] = {name, &node};
  } else {
    return Unsupported(node);
  }
  if (!obj.children().empty())
    return obj.children()[0]->Error("<" + obj.children()[0]->tag + "> is not allowed inside " +
                                    DescribeMitsuba(node));
  textures_[&node] = id;
  return id;
}

Status MitsubaSceneBuilder::BindMeshAttribute(const MitsubaNode& shape, MaterialRef material,
                                              const MeshData& mesh, uint32_t first_triangle) {
  // mask: every texture the material reads (a blend's weight, a mask's opacity, nested
  // materials' textures), not only a diffuse albedo.
  std::vector<uint32_t> ids;
  MaterialTextures(scene_.materials, material, &ids);
  for (const uint32_t id : ids)
    PTLAB_RETURN_IF_ERROR(BindMeshAttributeTexture(shape, id, mesh, first_triangle));
  return Status::Ok();
}

Status MitsubaSceneBuilder::BindMeshAttributeTexture(const MitsubaNode& shape, uint32_t id,
                                                     const MeshData& mesh,
                                                     uint32_t first_triangle) {
  TextureTable& t = scene_.textures;
  const TextureKind kind = t.Kind(id);
  if (kind != TextureKind::kFaceAttribute && kind != TextureKind::kVertexAttribute)
    return Status::Ok();
  const auto& [name, node] = attribute_names_.at(id);
  if (t.height[id] != 0)
    return Unsupported(*node, "a mesh_attribute texture used by more than one shape");
  const MeshAttribute* attribute = nullptr;
  for (const MeshAttribute& a : mesh.attributes)
    if (a.name == name) attribute = &a;
  if (attribute == nullptr)
    return shape.Error(DescribeMitsuba(shape) + " has no attribute '" + name +
                       "' for its mesh_attribute texture");
  const size_t triangles = mesh.triangle_count();
  const uint32_t dim = attribute->dim;
  // The attribute's value of a row as RGB: one channel replicated, else the first three.
  const auto rgb = [&](size_t row) {
    const float* v = &attribute->values[row * dim];
    double c[3];
    for (int k = 0; k < 3; ++k) c[k] = dim >= 3 ? v[k] : v[0];
    for (double& x : c)
      if (!std::isfinite(x)) x = 0;
    return std::array<double, 3>{c[0], c[1], c[2]};
  };
  const bool face = kind == TextureKind::kFaceAttribute;
  const size_t per = face ? 3 : kVertexAttributeFloats;
  if (t.data.size() + per * triangles >= (size_t(1) << 31))
    return shape.Error("the scene's textures exceed 2^31 floats");
  t.offset[id] = uint32_t(t.data.size());
  t.width[id] = first_triangle, t.height[id] = uint32_t(triangles);
  t.data.resize(t.data.size() + per * triangles, 0.0f);
  float* out = &t.data[t.offset[id]];
  for (size_t tri = 0; tri < triangles; ++tri, out += per) {
    if (face) {
      const auto c = rgb(tri);
      for (int k = 0; k < 3; ++k) out[k] = float(c[k]);
      continue;
    }
    // The plane through the corners' values: g · e1 = a1 − a0, g · e2 = a2 − a0 with g in the
    // triangle's plane (g = α e1 + β e2), in double; a degenerate triangle gets g = 0.
    const uint32_t row = first_triangle + uint32_t(tri);
    const Vec3f v0 = scene_.triangles.V0(row), v1 = scene_.triangles.V1(row),
                v2 = scene_.triangles.V2(row);
    const double e1[3] = {double(v1.x) - v0.x, double(v1.y) - v0.y, double(v1.z) - v0.z};
    const double e2[3] = {double(v2.x) - v0.x, double(v2.y) - v0.y, double(v2.z) - v0.z};
    const double a = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
    const double b = e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2];
    const double c = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
    const double det = a * c - b * b;
    const bool ok = det > 1e-12 * a * c;
    const auto c0 = rgb(mesh.indices[3 * tri]), c1 = rgb(mesh.indices[3 * tri + 1]),
               c2 = rgb(mesh.indices[3 * tri + 2]);
    out[0] = v0.x, out[1] = v0.y, out[2] = v0.z;
    for (int k = 0; k < 3; ++k) {
      float* o = out + 3 + 4 * k;
      const double d1 = c1[k] - c0[k], d2 = c2[k] - c0[k];
      if (!ok) {
        o[0] = float((c0[k] + c1[k] + c2[k]) / 3), o[1] = o[2] = o[3] = 0;
        continue;
      }
      const double alpha = (c * d1 - b * d2) / det, beta = (a * d2 - b * d1) / det;
      o[0] = float(c0[k]);
      for (int j = 0; j < 3; ++j) o[1 + j] = float(alpha * e1[j] + beta * e2[j]);
    }
  }
  return Status::Ok();
}

}  // namespace ptlab::internal
