// Nori XML <mesh>/<shape>: OBJ files and the Mitsuba-style procedural shapes, with their BSDF and area emitter.

#include "engine/bsdf/conductor_presets.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <map>
#include <pugixml.hpp>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/core/memory_budget.h"
#include "engine/image/image_io.h"
#include "engine/light/distant_disk.h"
#include "engine/light/environment_map.h"
#include "engine/io/mesh_builder.h"
#include "engine/io/obj_loader.h"
#include "engine/scene/scene_limits.h"
#include "engine/io/shapes.h"
#include "engine/io/text_parsing.h"
#include "engine/io/xml_loader_internal.h"
#include "engine/io/xml_scene_parser.h"

namespace ptlab::internal {

Status SceneParser::ParseShape(const pugi::xml_node& node) {
  PTLAB_RETURN_IF_ERROR(CheckAttributes(at_, node, {"type"}));
  const std::string type = node.attribute("type").value();
  PropertyList props(&at_, node);
  std::vector<pugi::xml_node> children;
  PTLAB_RETURN_IF_ERROR(Collect(node, {"bsdf", "emitter"}, &props, &children));

  MeshData generated;
  const MeshData* mesh = &generated;
  std::string name = type;
  if (type == "obj") {
    PTLAB_RETURN_IF_ERROR(props.Expect({"filename", "toWorld"}));
    PTLAB_RETURN_IF_ERROR(props.Require("filename", "string"));
  } else if (type == "sphere") {
    PTLAB_RETURN_IF_ERROR(props.Expect({"center", "radius", "toWorld"}));
    Vec3f center;
    float radius = 1.0f;
    PTLAB_RETURN_IF_ERROR(props.Point("center", &center));
    PTLAB_RETURN_IF_ERROR(props.Float("radius", &radius));
    if (!(radius > 0)) return props.Error("radius", "sphere radius must be > 0");
    generated = MakeSphere(center, radius);
  } else if (type == "rectangle" || type == "cube" || type == "disk") {
    PTLAB_RETURN_IF_ERROR(props.Expect({"toWorld"}));
    generated =
        type == "rectangle" ? MakeRectangle() : (type == "cube" ? MakeCube() : MakeDisk());
  } else {
    return at_.Error(node, "unknown " + std::string(node.name()) + " type '" + type +
                               "'; expected obj, sphere, rectangle, cube or disk");
  }
  Transform to_world;
  PTLAB_RETURN_IF_ERROR(props.TransformProperty("toWorld", &to_world));

  pugi::xml_node bsdf_node, emitter_node;
  for (const pugi::xml_node child : children)
    PTLAB_RETURN_IF_ERROR(TakeSingleton(
        child, std::string_view(child.name()) == "bsdf" ? &bsdf_node : &emitter_node));
  // Nori's default material for a mesh without a BSDF.
  MaterialRef material;
  if (bsdf_node) {
    StatusOr<MaterialRef> parsed = ParseBsdf(bsdf_node);
    if (!parsed.ok()) return parsed.status();
    material = *parsed;
  }
  Color3f radiance;
  if (emitter_node) PTLAB_RETURN_IF_ERROR(ParseAreaEmitter(emitter_node, &radiance));

  if (type == "obj") {
    std::string filename;
    PTLAB_RETURN_IF_ERROR(props.String("filename", &filename));
    const std::string path = Resolve(filename);
    auto it = obj_cache_.find(path);
    if (it == obj_cache_.end()) {
      StatusOr<MeshData> loaded = LoadObj(path);
      if (!loaded.ok())
        return at_.Error(node, "cannot load the OBJ file of " + Describe(node) + ": " +
                                   loaded.status().message());
      it = obj_cache_.emplace(path, std::move(*loaded)).first;
      scene_.input_files.push_back(path);
      std::error_code ec;
      const uintmax_t bytes = std::filesystem::file_size(path, ec);
      if (!ec) input_bytes_ += uint64_t(bytes);
    }
    mesh = &it->second;
    name = filename;
  }
  if (!bsdf_node) material = scene_.materials.AddDiffuse({0.5f, 0.5f, 0.5f});
  // Every shape appends its triangles (an OBJ used again is appended again): a short file of
  // many shapes may not grow past its expansion budget.
  const uint64_t triangles = uint64_t(scene_.triangles.size()) + mesh->triangle_count();
  const std::string over = OverExpansionBudget(
      double(triangles) * double(kSceneBytesPerTriangle), input_bytes_,
      "with " + Describe(node) + " the scene's " + std::to_string(triangles) + " triangles");
  if (!over.empty()) return at_.Error(node, over);
  const uint32_t first = uint32_t(scene_.triangles.size());
  const uint32_t row = AddMesh(&scene_, *mesh, to_world, material, name);
  const TriangleTable& tri = scene_.triangles;
  for (uint32_t t = first; t < tri.size(); ++t)
    for (const Vec3f& v : {tri.V0(t), tri.V1(t), tri.V2(t)})
      if (!(std::abs(v.x) <= kMaxWorldCoordinate && std::abs(v.y) <= kMaxWorldCoordinate &&
            std::abs(v.z) <= kMaxWorldCoordinate))
        return at_.Error(node, "triangle " + std::to_string(t - first) + " of " + Describe(node) +
                                   " has the world-space vertex (" + FormatNumber(v.x) + ", " +
                                   FormatNumber(v.y) + ", " + FormatNumber(v.z) +
                                   "); expected coordinates and toWorld that keep every "
                                   "coordinate finite and within +-" +
                                   FormatNumber(kMaxWorldCoordinate));
  if (emitter_node) AttachAreaLight(&scene_, row, radiance);
  return Status::Ok();
}

}  // namespace ptlab::internal
