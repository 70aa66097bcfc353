// COLLADA scene assembly: the visual scene's node tree instancing geometry, lights and a camera.
#include "engine/io/collada_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <pugixml.hpp>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/core/memory_budget.h"
#include "engine/core/similarity.h"
#include "engine/core/parse_number.h"
#include "engine/io/collada_document.h"
#include "engine/io/collada_effect.h"
#include "engine/io/collada_instance_count.h"
#include "engine/io/collada_library.h"
#include "engine/io/collada_mesh.h"
#include "engine/io/collada_transform.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/light/distant_disk.h"
#include "engine/io/mesh_builder.h"
#include "engine/scene/scene_limits.h"
#include "engine/io/shapes.h"
#include "engine/io/text_parsing.h"
#include "engine/io/xml_locator.h"

namespace ptlab {
namespace {

using namespace collada;  // Document, LightDesc, ReadLight, ReadCamera, ApplyPoint, ...

constexpr float kCs184FocalDistance = 4.7f;  // CS184 pathtracer's -d default
constexpr float kHuge = 3.0e38f;

class ColladaReader {
 public:
  // `input_bytes`: the file's size, which bounds what its instances may expand into by default.
  ColladaReader(const Document& doc, uint64_t input_bytes)
      : doc_(doc), input_bytes_(input_bytes) {}

  Status Read(const pugi::xml_node& root) {
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(
        root,
        {"asset", "library_cameras", "library_lights", "library_images", "library_effects",
         "library_materials", "library_geometries", "library_controllers", "library_nodes",
         "library_visual_scenes", "scene"},
        /*extras=*/true));
    const std::string_view version = root.attribute("version").value();
    if (version != "1.4.1" && version != "1.4.0")
      return doc_.NotSupported(root, std::string("COLLADA version \"") + std::string(version) +
                                         "\"; expected 1.4.1");
    PTLAB_RETURN_IF_ERROR(ReadAssetFrame(doc_, root.child("asset"), &global_));
    for (const char* empty : {"library_images", "library_controllers"})
      for (const pugi::xml_node lib : root.children(empty))
        PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(lib, {}, /*extras=*/true));
    PTLAB_RETURN_IF_ERROR(ReadLibraries(root));

    const pugi::xml_node scene = root.child("scene");
    if (!scene) return doc_.Error(root, "no <scene>; expected <scene><instance_visual_scene>");
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(scene, {"instance_visual_scene"}, true));
    const pugi::xml_node instance = scene.child("instance_visual_scene");
    if (!instance) return doc_.Error(scene, "<scene> has no <instance_visual_scene>");
    pugi::xml_node visual;
    PTLAB_RETURN_IF_ERROR(doc_.Resolve(instance, "url", "visual_scene", &visual));
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(visual, {"node", "asset"}, true));
    // Count what the node tree instances before expanding any of it: a few kilobytes of
    // <instance_node>s can multiply into billions of triangles.
    InstanceCounter counter(doc_, geometries_);
    uint64_t primitives = 0;
    for (const pugi::xml_node node : visual.children("node")) {
      uint64_t n = 0;
      PTLAB_RETURN_IF_ERROR(counter.Count(node, 0, &n));
      primitives = SaturatingAdd(primitives, n);
    }
    const std::string over = OverExpansionBudget(
        double(primitives) * double(kSceneBytesPerTriangle), input_bytes_,
        "the visual scene instances " + std::to_string(primitives) +
            (primitives == kCountSaturated ? "+" : "") +
            " triangles and spheres (through its <instance_node>s), which");
    if (!over.empty()) return doc_.Error(visual, over);
    std::vector<pugi::xml_node> path;
    for (const pugi::xml_node node : visual.children("node"))
      PTLAB_RETURN_IF_ERROR(ReadNode(node, global_, &path));
    if (!camera_)
      return doc_.Error(visual, "the visual scene instances no camera; expected one "
                                "<instance_camera>");
    PTLAB_RETURN_IF_ERROR(PlaceCamera(visual));
    FinalizeAreaLights(&scene_);
    return Status::Ok();
  }

  Scene TakeScene() { return std::move(scene_); }

 private:
  // CS184 keeps only the direction of the file's camera: its Application::load aims it at the
  // centre of the bounding box of the scene's objects (lights excluded) from 1.5 times the
  // box's diagonal, with world +y up (the view direction's tilt is kept; the up vector of the
  // file is used only when the view is vertical).
  Status PlaceCamera(const pugi::xml_node& visual) {
    if (!(bounds_max_.x >= bounds_min_.x))
      return doc_.Error(visual, "the visual scene has no geometry to aim the camera at");
    const Vec3f target = (bounds_min_ + bounds_max_) * 0.5f;
    const float distance = 1.5f * Length(bounds_max_ - bounds_min_);
    const Vec3f f = view_dir_;
    Vec3f left = Cross(Vec3f{0, 1, 0}, f);
    if (!(Length(left) > 1e-6f)) left = Cross(view_up_, f);
    if (!(Length(left) > 1e-6f))
      return doc_.Error(camera_, "the camera looks straight up or down and its node gives no "
                                 "up direction");
    left = Normalize(left);
    const Vec3f origin = target - f * distance;
    const Matrix4 m = Columns(left, Cross(f, left), f, origin);
    Matrix4 inv;
    if (!Inverse(m, &inv)) return doc_.Error(camera_, "the camera frame is singular");
    scene_.camera.camera_to_world = Transform(m, inv);
    scene_.camera.focus_distance = kCs184FocalDistance;
    return Status::Ok();
  }

  void ExpandBounds(uint32_t first_triangle) {
    const TriangleTable& tri = scene_.triangles;
    for (uint32_t t = first_triangle; t < tri.size(); ++t)
      for (const Vec3f& v : {tri.V0(t), tri.V1(t), tri.V2(t)}) ExpandBoundsTo(v);
  }
  void ExpandBoundsTo(const Vec3f& v) {
    bounds_min_ = {std::min(bounds_min_.x, v.x), std::min(bounds_min_.y, v.y),
                   std::min(bounds_min_.z, v.z)};
    bounds_max_ = {std::max(bounds_max_.x, v.x), std::max(bounds_max_.y, v.y),
                   std::max(bounds_max_.z, v.z)};
  }

  // Every effect, material, geometry, light and camera is read (and checked) up front, used
  // or not, so that nothing in a file is silently skipped.
  Status ReadLibraries(const pugi::xml_node& root) {
    for (const pugi::xml_node lib : root.children("library_effects")) {
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(lib, {"effect", "asset"}, true));
      for (const pugi::xml_node effect : lib.children("effect")) {
        StatusOr<collada::Effect> e = collada::ReadEffect(doc_, effect);
        if (!e.ok()) return e.status();
        effects_.emplace(effect.offset_debug(), std::move(*e));
      }
    }
    for (const pugi::xml_node lib : root.children("library_materials")) {
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(lib, {"material", "asset"}, true));
      for (const pugi::xml_node material : lib.children("material")) {
        PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(material, {"instance_effect", "asset"}, true));
        const pugi::xml_node instance = material.child("instance_effect");
        if (!instance) return doc_.Error(material, "<material> has no <instance_effect>");
        PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(instance, {}, true));
        pugi::xml_node effect;
        PTLAB_RETURN_IF_ERROR(doc_.Resolve(instance, "url", "effect", &effect));
        effect_of_material_[material.offset_debug()] = effect.offset_debug();
      }
    }
    for (const pugi::xml_node lib : root.children("library_geometries")) {
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(lib, {"geometry", "asset"}, true));
      for (const pugi::xml_node geometry : lib.children("geometry")) {
        StatusOr<collada::Geometry> g = collada::ReadGeometry(doc_, geometry);
        if (!g.ok()) return g.status();
        geometries_.emplace(geometry.offset_debug(), std::move(*g));
      }
    }
    for (const pugi::xml_node lib : root.children("library_lights")) {
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(lib, {"light", "asset"}, true));
      for (const pugi::xml_node light : lib.children("light")) {
        LightDesc desc;
        PTLAB_RETURN_IF_ERROR(ReadLight(doc_, light, &desc));
        lights_.emplace(light.offset_debug(), desc);
      }
    }
    for (const pugi::xml_node lib : root.children("library_cameras")) {
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(lib, {"camera", "asset"}, true));
      for (const pugi::xml_node camera : lib.children("camera")) {
        CameraDesc desc;
        PTLAB_RETURN_IF_ERROR(ReadCamera(doc_, camera, &desc));
        cameras_.emplace(camera.offset_debug(), desc);
      }
    }
    for (const pugi::xml_node lib : root.children("library_nodes"))
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(lib, {"node", "asset"}, true));
    return Status::Ok();
  }

  Status TooDeep(const pugi::xml_node& node) const { return NodesTooDeep(doc_, node); }

  // `path` holds the nodes being read (for cycles through instance_node).
  Status ReadNode(const pugi::xml_node& node, const Matrix4& parent,
                  std::vector<pugi::xml_node>* path) {
    if (path->size() >= kMaxNodeDepth) return TooDeep(node);
    for (const pugi::xml_node& open : *path)
      if (open == node)
        return doc_.Error(node, "node '" + NodeName(node) + "' instances itself (a cycle of "
                                "<instance_node>s); expected a tree");
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(
        node,
        {"matrix", "translate", "rotate", "scale", "node", "instance_geometry", "instance_light",
         "instance_camera", "instance_node", "asset"},
        /*extras=*/true));
    Matrix4 local;
    PTLAB_RETURN_IF_ERROR(ReadNodeTransform(doc_, node, &scene_.load_warnings, &local));
    const Matrix4 world = parent * local;
    path->push_back(node);
    for (const pugi::xml_node child : node.children()) {
      const std::string_view name = child.name();
      if (name == "node") {
        PTLAB_RETURN_IF_ERROR(ReadNode(child, world, path));
      } else if (name == "instance_node") {
        pugi::xml_node target;
        PTLAB_RETURN_IF_ERROR(doc_.Resolve(child, "url", "node", &target));
        PTLAB_RETURN_IF_ERROR(ReadNode(target, world, path));
      } else if (name == "instance_geometry") {
        PTLAB_RETURN_IF_ERROR(InstanceGeometry(child, world));
      } else if (name == "instance_light") {
        PTLAB_RETURN_IF_ERROR(InstanceLight(child, world));
      } else if (name == "instance_camera") {
        PTLAB_RETURN_IF_ERROR(InstanceCamera(child, world));
      }
    }
    path->pop_back();
    return Status::Ok();
  }

  Status InstanceCamera(const pugi::xml_node& instance, const Matrix4& world) {
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(instance, {}, true));
    if (camera_)
      return doc_.Error(instance, "a second <instance_camera> (first at " + doc_.at.At(camera_) +
                                      "); expected one camera");
    pugi::xml_node camera;
    PTLAB_RETURN_IF_ERROR(doc_.Resolve(instance, "url", "camera", &camera));
    camera_ = instance;
    CameraDesc desc = cameras_.at(camera.offset_debug());
    // COLLADA cameras look down their local -z with +y up; ptlab's camera space looks along +z
    // with +x to the image's left. Scale is dropped: the frame is made orthonormal.
    const Vec3f forward = ApplyVector(world, {0, 0, -1}), up = ApplyVector(world, {0, 1, 0});
    if (!(Length(forward) > 0) || !std::isfinite(Length(forward)) ||
        !std::isfinite(Length(up)))
      return doc_.Error(instance, "the camera's node transform has no view direction");
    view_dir_ = Normalize(forward);
    view_up_ = Length(up) > 0 ? Normalize(up) : Vec3f{0, 0, 0};
    scene_.camera = desc;
    return Status::Ok();
  }

  Status InstanceLight(const pugi::xml_node& instance, const Matrix4& world) {
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(instance, {}, true));
    pugi::xml_node light;
    PTLAB_RETURN_IF_ERROR(doc_.Resolve(instance, "url", "light", &light));
    const LightDesc& desc = lights_.at(light.offset_debug());
    if (desc.kind != LightDesc::Kind::kArea)
      return PlaceLight(doc_, instance, light, desc, world, &scene_);
    // CS184's area light: the unit square [-1/2, 1/2]² of the light's local xy plane,
    // emitting towards local -z (both triangles and normals face -z).
    MeshData quad;
    quad.positions = {{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {-0.5f, 0.5f, 0}};
    quad.normals.assign(4, Vec3f{0, 0, -1});
    quad.indices = {0, 2, 1, 0, 3, 2};
    const MaterialRef black = scene_.materials.AddDiffuse({0, 0, 0});
    uint32_t row = 0;
    PTLAB_RETURN_IF_ERROR(AddWorldMesh(instance, quad, world, black, "area light " +
                                       NodeName(light), &row));
    AddAreaEmitter(row, desc.color);
    return Status::Ok();
  }

  void AddAreaEmitter(uint32_t mesh_row, const Color3f& radiance) {
    AttachAreaLight(&scene_, mesh_row, radiance);
  }

  // A CGL sphere of world centre c and radius r as a SphereTable row.
  Status AddAnalyticSphere(const pugi::xml_node& instance, const Vec3f& c, float r,
                           MaterialRef material) {
    if (!(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && r > 0 &&
          std::isfinite(r)))
      return doc_.Error(instance,
                        "the sphere's node transform gives no finite centre and radius > 0");
    // The sphere itself must lie within the scene's coordinates (a radius of 1e20 was only
    // noticed later, as a camera the scene's bounds could not place).
    const float reach = std::max({std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)}) + r;
    if (!(reach <= kMaxWorldCoordinate))
      return doc_.Error(instance, "the sphere (world radius " + FormatLimit(r) + ", centre " +
                                      FormatLimit(c.x) + ", " + FormatLimit(c.y) + ", " +
                                      FormatLimit(c.z) + ") reaches beyond the scene's "
                                      "coordinates [-1e12, 1e12]; expected a smaller radius");
    if (scene_.spheres.size() + 1 >= kMaxSpheres)
      return doc_.Error(instance, "too many spheres; at most " + std::to_string(kMaxSpheres - 1));
    scene_.spheres.Append(c, r, material);
    ExpandBoundsTo(c - Vec3f{r, r, r});
    ExpandBoundsTo(c + Vec3f{r, r, r});
    return Status::Ok();
  }

  // Appends `mesh` through `world` (which must be invertible) and checks its coordinates.
  Status AddWorldMesh(const pugi::xml_node& instance, const MeshData& mesh, const Matrix4& world,
                      MaterialRef material, const std::string& name, uint32_t* row) {
    Matrix4 inv;
    if (!Inverse(world, &inv))
      return doc_.Error(instance, "the node transform of '" + name + "' is singular");
    const uint32_t first = uint32_t(scene_.triangles.size());
    *row = AddMesh(&scene_, mesh, Transform(world, inv), material, name);
    const TriangleTable& tri = scene_.triangles;
    for (uint32_t t = first; t < tri.size(); ++t)
      for (const Vec3f& v : {tri.V0(t), tri.V1(t), tri.V2(t)})
        if (!(std::abs(v.x) <= kMaxWorldCoordinate && std::abs(v.y) <= kMaxWorldCoordinate &&
              std::abs(v.z) <= kMaxWorldCoordinate))
          return doc_.Error(instance, "a world-space vertex of '" + name +
                                          "' lies beyond +-1e12; expected coordinates and "
                                          "transforms that keep it finite and within range");
    return Status::Ok();
  }

  // The ptlab row of a <material> (one per material element) and its emitted radiance.
  Status MaterialOf(const pugi::xml_node& material, MaterialRef* ref, Color3f* radiance) {
    const ptrdiff_t key = material.offset_debug();
    auto it = material_rows_.find(key);
    if (it == material_rows_.end()) {
      const collada::Effect& effect = effects_.at(effect_of_material_.at(key));
      StatusOr<MaterialRef> row = collada::AddEffectMaterial(doc_, effect, &scene_.materials);
      if (!row.ok()) return row.status();
      const Color3f emitted =
          effect.model == collada::Effect::Model::kEmission ? effect.radiance : Color3f{};
      it = material_rows_.emplace(key, std::make_pair(*row, emitted)).first;
    }
    *ref = it->second.first;
    *radiance = it->second.second;
    return Status::Ok();
  }

  Status InstanceGeometry(const pugi::xml_node& instance, const Matrix4& world) {
    PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(instance, {"bind_material"}, true));
    pugi::xml_node geometry;
    PTLAB_RETURN_IF_ERROR(doc_.Resolve(instance, "url", "geometry", &geometry));
    // bind_material: symbol -> <material>, in order.
    std::vector<std::pair<std::string, pugi::xml_node>> bound;
    const pugi::xml_node bind = instance.child("bind_material");
    if (bind) {
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(bind, {"technique_common"}, true));
      const pugi::xml_node common = bind.child("technique_common");
      PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(common, {"instance_material"}));
      for (const pugi::xml_node im : common.children("instance_material")) {
        PTLAB_RETURN_IF_ERROR(doc_.CheckChildren(im, {}, true));
        pugi::xml_node material;
        PTLAB_RETURN_IF_ERROR(doc_.Resolve(im, "target", "material", &material));
        bound.emplace_back(im.attribute("symbol").value(), material);
      }
    }
    const collada::Geometry& g = geometries_.at(geometry.offset_debug());
    const std::string name = NodeName(geometry);
    // CS184 gives a sphere the first bound material; a mesh part the one bound to its symbol.
    const auto material_for = [&](const std::string& symbol, const pugi::xml_node& user,
                                  MaterialRef* ref, Color3f* radiance) -> Status {
      *radiance = {};
      pugi::xml_node material;
      if (g.is_sphere) {
        if (!bound.empty()) material = bound.front().second;
      } else {
        for (const auto& [s, m] : bound)
          if (s == symbol) material = m;
        if (!material && !symbol.empty() && bind)
          return doc_.Error(user, "material symbol '" + symbol + "' is not bound by the "
                                  "<instance_geometry> at " + doc_.at.At(instance));
      }
      if (!material) {
        *ref = scene_.materials.AddDiffuse({0.5f, 0.5f, 0.5f});
        return Status::Ok();
      }
      return MaterialOf(material, ref, radiance);
    };
    const auto add_mesh = [&](const MeshData& mesh, MaterialRef ref,
                              const Color3f& radiance) -> Status {
      uint32_t row = 0;
      const uint32_t first = uint32_t(scene_.triangles.size());
      PTLAB_RETURN_IF_ERROR(AddWorldMesh(instance, mesh, world, ref, name, &row));
      ExpandBounds(first);
      if (!IsBlack(radiance)) AddAreaEmitter(row, radiance);
      return Status::Ok();
    };
    const auto add = [&](const MeshData& mesh, const std::string& symbol,
                         const pugi::xml_node& user) -> Status {
      if (mesh.indices.empty()) return Status::Ok();
      MaterialRef ref;
      Color3f radiance;
      PTLAB_RETURN_IF_ERROR(material_for(symbol, user, &ref, &radiance));
      return add_mesh(mesh, ref, radiance);
    };
    if (g.is_sphere) {
      MaterialRef ref;
      Color3f radiance;
      PTLAB_RETURN_IF_ERROR(material_for("", geometry, &ref, &radiance));
      // An analytic sphere where it stays one: not emissive (area lights sample triangles) and
      // under a similarity transform (a non-uniform scale makes an ellipsoid).
      float scale = 0;
      if (IsBlack(radiance) && IsSimilarity(world, &scale))
        return AddAnalyticSphere(instance, ApplyPoint(world, {0, 0, 0}), g.sphere_radius * scale,
                                 ref);
      return add_mesh(MakeSphere({0, 0, 0}, g.sphere_radius), ref, radiance);
    }
    for (const collada::MeshPart& part : g.parts)
      PTLAB_RETURN_IF_ERROR(add(part.mesh, part.material_symbol, part.node));
    return Status::Ok();
  }

  const Document& doc_;
  Scene scene_;
  Matrix4 global_;
  pugi::xml_node camera_;  // the <instance_camera> read
  Vec3f view_dir_, view_up_;  // its world view direction and up vector (unit)
  Vec3f bounds_min_{kHuge, kHuge, kHuge}, bounds_max_{-kHuge, -kHuge, -kHuge};
  std::map<ptrdiff_t, collada::Effect> effects_;
  std::map<ptrdiff_t, ptrdiff_t> effect_of_material_;
  std::map<ptrdiff_t, collada::Geometry> geometries_;
  uint64_t input_bytes_ = 0;
  std::map<ptrdiff_t, LightDesc> lights_;
  std::map<ptrdiff_t, CameraDesc> cameras_;
  std::map<ptrdiff_t, std::pair<MaterialRef, Color3f>> material_rows_;
};

}  // namespace

StatusOr<Scene> LoadColladaSceneFromString(const std::string& text,
                                           const std::string& display_name) {
  const internal::XmlLocator at(text, display_name);
  pugi::xml_document xml;
  const pugi::xml_parse_result result =
      xml.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
  if (result.status == pugi::status_no_document_element)
    return Status::Error(at.AtOffset(0) + ": no root element; expected a <COLLADA> element");
  if (!result)
    return Status::Error(at.AtOffset(result.offset) + ": XML syntax error: " +
                         result.description());
  pugi::xml_node root;
  PTLAB_RETURN_IF_ERROR(at.FindSingleRoot(xml, "COLLADA", &root));
  if (std::string_view(root.name()) != "COLLADA")
    return at.Error(root, std::string("root element <") + std::string(root.name()) +
                              ">; expected <COLLADA>");
  Document doc(at);
  PTLAB_RETURN_IF_ERROR(doc.IndexIds(root));
  ColladaReader reader(doc, text.size());
  PTLAB_RETURN_IF_ERROR(reader.Read(root));
  Scene scene = reader.TakeScene();
  scene.source_path = display_name;
  // CS184's defaults (its AppConfig: 1 sample per pixel, max ray depth 1, 1 sample per area
  // light); its pixel samples are uniform over the pixel square: a box filter.
  scene.sampler.sample_count = 1;
  scene.integrator.type = IntegratorDesc::Type::kPathEms;
  scene.integrator.max_depth = 1;
  scene.integrator.light_samples = 1;
  scene.filter.type = FilterDesc::Type::kBox;
  scene.filter.radius = 0.5f;
  return scene;
}

StatusOr<Scene> LoadColladaScene(const std::string& path) {
  std::string text;
  PTLAB_RETURN_IF_ERROR(ReadTextFile(path, "scene file", &text));
  StatusOr<Scene> scene = LoadColladaSceneFromString(text, path);
  if (scene.ok()) scene->input_files.insert(scene->input_files.begin(), path);
  return scene;
}

}  // namespace ptlab
