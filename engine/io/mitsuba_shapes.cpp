// Mitsuba <shape>s: obj (ply and serialized once their readers are wired in), rectangle, cube,
// disk, cylinder, sphere; with their BSDF and area emitter.
#include <cmath>
#include <numbers>

#include "engine/bvh/sphere_intersect.h"
#include "engine/core/similarity.h"
#include "engine/core/frame.h"
#include "engine/io/mitsuba_meshes.h"
#include "engine/io/mitsuba_scene_builder.h"
#include "engine/io/obj_loader.h"
#include "engine/io/ply_loader.h"
#include "engine/io/serialized_loader.h"
#include "engine/io/shapes.h"
#include "engine/io/xml_properties.h"
#include "engine/scene/scene_limits.h"

namespace ptlab::internal {
namespace {

// Rim vertices of a Mitsuba disk and cylinder: the edge is then within 5e-6 (relative) of the
// circle.
constexpr int kMitsubaDiskSegments = 1024;

// Mitsuba's vertex normals for a mesh without them: at each vertex, the sum of its triangles'
// face normals weighted by the triangle's interior angle there (Thürmer & Wüthrich 1998).
void ComputeAngleWeightedNormals(MeshData* mesh) {
  std::vector<Vec3f> sum(mesh->positions.size(), Vec3f{0, 0, 0});
  for (size_t t = 0; t + 2 < mesh->indices.size(); t += 3) {
    const uint32_t idx[3] = {mesh->indices[t], mesh->indices[t + 1], mesh->indices[t + 2]};
    const Vec3f p[3] = {mesh->positions[idx[0]], mesh->positions[idx[1]], mesh->positions[idx[2]]};
    const Vec3f n = Cross(p[1] - p[0], p[2] - p[0]);
    if (!(Length(n) > 0)) continue;
    const Vec3f face = Normalize(n);
    for (int k = 0; k < 3; ++k) {
      const Vec3f a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
      if (!(Length(a) > 0 && Length(b) > 0)) continue;
      const float c = std::clamp(Dot(Normalize(a), Normalize(b)), -1.0f, 1.0f);
      sum[idx[k]] = sum[idx[k]] + std::acos(c) * face;
    }
  }
  mesh->normals.resize(sum.size());
  for (size_t i = 0; i < sum.size(); ++i)
    mesh->normals[i] = Length(sum[i]) > 0 ? Normalize(sum[i]) : Vec3f{0, 0, 1};
}

}  // namespace

Status MitsubaSceneBuilder::MeshFile(const MitsubaObject& obj, MeshData* mesh, std::string* name) {
  const std::string& type = obj.type();
  std::string filename;
  PTLAB_RETURN_IF_ERROR(obj.Require("filename"));
  PTLAB_RETURN_IF_ERROR(obj.String("filename", &filename));
  // The mesh file readers: OBJ, PLY and Mitsuba's serialized format (shape `shape_index`).
  int shape_index = 0;
  if (type == "serialized") {
    PTLAB_RETURN_IF_ERROR(obj.Integer("shape_index", &shape_index));
    if (shape_index < 0) return obj.Error("shape_index", "shape_index must be >= 0");
  }
  StatusOr<std::string> path = Resolve(obj, "filename", filename);
  if (!path.ok()) return path.status();
  const std::string key = *path + (type == "serialized" ? "#" + std::to_string(shape_index) : "");
  auto it = meshes_.find(key);
  if (it == meshes_.end()) {
    StatusOr<MeshData> loaded = type == "ply"          ? LoadPly(*path)
                                : type == "serialized" ? LoadSerialized(*path, uint32_t(shape_index))
                                                       : LoadObj(*path);
    if (!loaded.ok())
      return obj.Error("filename", "cannot load the mesh of " + DescribeMitsuba(obj.node()) + ": " +
                                       loaded.status().message());
    it = meshes_.emplace(key, std::move(*loaded)).first;
    scene_.input_files.push_back(*path);
  }
  *mesh = it->second;
  *name = filename;
  return Status::Ok();
}

Status MitsubaSceneBuilder::Shape(const MitsubaNode& node) {
  StatusOr<MitsubaObject> read = Read(node);
  if (!read.ok()) return read.status();
  const MitsubaObject& obj = *read;
  const std::string& type = obj.type();
  const bool mesh_file = type == "obj" || type == "ply" || type == "serialized";
  if (mesh_file) {
    std::vector<const char*> names = {"filename", "to_world", "face_normals", "flip_normals"};
    names.push_back(type == "serialized" ? "shape_index" : "flip_tex_coords");
    PTLAB_RETURN_IF_ERROR(obj.Expect(names));
  } else if (type == "rectangle" || type == "cube" || type == "disk") {
    PTLAB_RETURN_IF_ERROR(obj.Expect({"to_world", "flip_normals"}));
  } else if (type == "sphere") {
    PTLAB_RETURN_IF_ERROR(obj.Expect({"center", "radius", "to_world", "flip_normals"}));
  } else if (type == "cylinder") {
    PTLAB_RETURN_IF_ERROR(obj.Expect({"radius", "p0", "p1", "to_world", "flip_normals"}));
  } else if (type == "sdfgrid") {
    PTLAB_RETURN_IF_ERROR(obj.Expect({"filename", "normals", "to_world"}));
  } else if (type == "shapegroup" || type == "instance" ||
             type == "ellipsoids" || type == "ellipsoidsmesh" || type == "bsplinecurve" ||
             type == "linearcurve" || type == "merge") {
    return Unsupported(node);
  } else {
    return node.Error("unknown shape type '" + type +
                      "'; expected obj, ply, serialized, rectangle, cube, disk, cylinder, "
                      "sphere or sdfgrid");
  }
  // Mitsuba flips v of OBJ files by default and of PLY files only when asked; a serialized file
  // stores v flipped already, which LoadSerialized undoes (it returns the OBJ convention), so
  // its v is always flipped here and the format takes no flip_tex_coords.
  bool flip_normals = false, face_normals = false, flip_tex_coords = type != "ply";
  PTLAB_RETURN_IF_ERROR(obj.Boolean("flip_normals", &flip_normals));
  if (mesh_file) {
    PTLAB_RETURN_IF_ERROR(obj.Boolean("face_normals", &face_normals));
    if (type != "serialized")
      PTLAB_RETURN_IF_ERROR(obj.Boolean("flip_tex_coords", &flip_tex_coords));
  }
  Transform to_world;
  PTLAB_RETURN_IF_ERROR(obj.TransformProperty("to_world", &to_world));

  const MitsubaNode *bsdf = nullptr, *emitter = nullptr;
  for (const MitsubaNode* child : obj.children()) {
    const MitsubaNode** slot = child->tag == "bsdf"      ? &bsdf
                               : child->tag == "emitter" ? &emitter
                                                         : nullptr;
    if (!slot) {
      if (child->tag == "medium" || child->tag == "texture") return Unsupported(*child);
      return child->Error("<" + child->tag + "> is not allowed inside " + DescribeMitsuba(node) +
                          "; expected bsdf or emitter");
    }
    if (*slot) return child->Error("a second <" + child->tag + "> in " + DescribeMitsuba(node));
    *slot = child;
  }
  MaterialRef material;
  if (bsdf) {
    StatusOr<MaterialRef> m = Bsdf(*bsdf);
    if (!m.ok()) return m.status();
    material = *m;
  }
  Color3f radiance;
  uint32_t emitter_texture = kNoTexture;
  if (emitter) PTLAB_RETURN_IF_ERROR(AreaEmitter(*emitter, &radiance, &emitter_texture));
  if (!bsdf) material = scene_.materials.AddDiffuse({0.5f, 0.5f, 0.5f});  // Mitsuba's default

  if (type == "sdfgrid") {
    if (emitter) return Unsupported(node, "an emitting sdfgrid (Mitsuba's cannot emit either)");
    return SdfGridShape(obj, to_world, material);
  }
  MeshData mesh;
  std::string name = type;
  if (type == "sphere") {
    Vec3f center{0, 0, 0};
    float radius = 1;
    PTLAB_RETURN_IF_ERROR(obj.Point("center", &center));
    PTLAB_RETURN_IF_ERROR(obj.Float("radius", &radius));
    if (!(radius > 0)) return obj.Error("radius", "sphere radius must be > 0");
    float scale = 0;
    if (!IsSimilarity(to_world.matrix(), &scale))
      return Unsupported(node, "a sphere under a non-uniform scale or shear");
    if (emitter) return Unsupported(node, "an emitting sphere");
    if (flip_normals) return Unsupported(node, "flip_normals on a sphere");
    if (material.tag() == MaterialTag::kDiffuse && scene_.materials.diffuse.textured()) {
      const uint32_t tex = scene_.materials.diffuse.albedo_texture[material.index()];
      if (tex != kNoTexture && (scene_.textures.Kind(tex) == TextureKind::kFaceAttribute ||
                                scene_.textures.Kind(tex) == TextureKind::kVertexAttribute))
        return Unsupported(node, "a mesh_attribute texture on a sphere (it has no attributes)");
    }
    const Vec3f c = to_world.ApplyPoint(center);
    const float r = radius * scale;
    if (!(std::fabs(c.x) + r <= kMaxWorldCoordinate && std::fabs(c.y) + r <= kMaxWorldCoordinate &&
          std::fabs(c.z) + r <= kMaxWorldCoordinate))
      return node.Error("the sphere reaches beyond the world's coordinate limit");
    if (scene_.spheres.size() + 1 >= kMaxSpheres) return node.Error("too many spheres");
    // The uv frame: to_world's inverse linear part times its scale (a rotation, maybe a mirror).
    const Matrix4& inv = to_world.inverse_matrix();
    SphereUvFrame frame;
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 3; ++col) frame[3 * row + col] = inv.m[row][col] * scale;
    scene_.spheres.Append(c, r, material, frame);
    return Status::Ok();
  }
  if (mesh_file) {
    PTLAB_RETURN_IF_ERROR(MeshFile(obj, &mesh, &name));
    if (face_normals)
      mesh.normals.clear();
    else if (mesh.normals.empty())
      ComputeAngleWeightedNormals(&mesh);
    if (flip_tex_coords)
      for (Vec2f& uv : mesh.uvs) uv.y = 1.0f - uv.y;
  } else if (type == "cylinder") {
    // Mitsuba's cylinder: the unit one (radius 1, z from 0 to 1) scaled to (radius, radius,
    // |p1 - p0|), turned so that +z runs along p1 - p0 (the frame of that axis, Duff et al.'s
    // basis as Mitsuba's coordinate_system), moved to p0, then to_world.
    float radius = 1;
    Vec3f p0{0, 0, 0}, p1{0, 0, 1};
    PTLAB_RETURN_IF_ERROR(obj.Float("radius", &radius));
    PTLAB_RETURN_IF_ERROR(obj.Point("p0", &p0));
    PTLAB_RETURN_IF_ERROR(obj.Point("p1", &p1));
    if (!(radius > 0 && radius <= kMaxWorldCoordinate))
      return obj.Error("radius", "cylinder radius must be in (0, " +
                                     FormatNumber(kMaxWorldCoordinate) + "]");
    const float length = Length(p1 - p0);
    if (!(length > 0 && length <= kMaxWorldCoordinate))
      return obj.Error(obj.Has("p1") ? "p1" : "p0",
                       "the cylinder's axis p1 - p0 must have a length in (0, " +
                           FormatNumber(kMaxWorldCoordinate) + "]");
    const Frame axis(Normalize(p1 - p0));
    Matrix4 frame;
    for (int r = 0; r < 3; ++r) {
      frame.m[r][0] = axis.s[r], frame.m[r][1] = axis.t[r], frame.m[r][2] = axis.n[r];
    }
    to_world = to_world * Transform::Translate(p0) * Transform(frame, Transpose(frame)) *
               Transform::Scale({radius, radius, length});
    mesh = MakeMitsubaCylinder(kMitsubaDiskSegments);
  } else {
    mesh = type == "rectangle" ? MakeRectangle()
           : type == "cube"    ? MakeMitsubaCube()
                               : MakeMitsubaDisk(kMitsubaDiskSegments);
  }
  if (flip_normals) {
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
      std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
    for (Vec3f& n : mesh.normals) n = -n;
  }
  const uint32_t first = uint32_t(scene_.triangles.size());
  const uint32_t row = AddMesh(&scene_, mesh, to_world, material, name);
  PTLAB_RETURN_IF_ERROR(BindMeshAttribute(node, material, mesh, first));
  const TriangleTable& tri = scene_.triangles;
  for (uint32_t t = first; t < tri.size(); ++t)
    for (const Vec3f& v : {tri.V0(t), tri.V1(t), tri.V2(t)})
      if (!(std::abs(v.x) <= kMaxWorldCoordinate && std::abs(v.y) <= kMaxWorldCoordinate &&
            std::abs(v.z) <= kMaxWorldCoordinate))
        return node.Error("a world-space vertex of " + DescribeMitsuba(node) +
                          " is not finite or beyond the coordinate limit");
  if (emitter) {
    AttachAreaLight(&scene_, row, radiance);
    // The texture column exists once an area light has a texture (AreaLightTable).
    AreaLightTable& lights = scene_.area_lights;
    if (emitter_texture != kNoTexture || !lights.texture.empty()) {
      lights.texture.resize(lights.size(), kNoTexture);
      lights.texture.back() = emitter_texture;
    }
  }
  return Status::Ok();
}

}  // namespace ptlab::internal
