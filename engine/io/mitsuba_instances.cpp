// Mitsuba instancing: <shape type="shapegroup" id=...> holding shapes, and
// <shape type="instance"> with a <ref id> to a group and a to_world transform. A group's
// triangles are added once, in group space (InstanceTable); its analytic spheres become one
// world sphere per instance (four floats each; a sphere needs a similarity to stay one).
#include <cmath>
#include <string>

#include "engine/bvh/sdf_grid_intersect.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/core/memory_budget.h"
#include "engine/core/similarity.h"
#include "engine/io/mitsuba_scene_builder.h"
#include "engine/scene/scene_limits.h"

namespace ptlab::internal {
namespace {

// Instanced hit ids stay below 2^30 (InstanceTable), so with the scene's triangle rows (fewer
// than 2^28) they never reach a sphere's id bit.
constexpr uint64_t kMaxInstancedTriangles = uint64_t{1} << 30;
// What an instanced sphere costs: its row in the sphere table and its share of the BVHs
// (20 M spheres from a 48 KB file peaked at 3.3 GB RSS, 167 bytes each).
constexpr double kSceneBytesPerSphere = 168;
// An instanced sdfgrid copies its placement (a transform, its inverse and bounds).
constexpr double kSceneBytesPerSdfGrid = 512;

const std::string& TypeOf(const MitsubaNode& node) {
  static const std::string kNone;
  const std::string* type = node.Attribute("type");
  return type ? *type : kNone;
}

}  // namespace

Status MitsubaSceneBuilder::SceneShape(const MitsubaNode& node) {
  const std::string& type = TypeOf(node);
  if (type == "shapegroup") {
    StatusOr<uint32_t> group = ShapeGroup(node);
    return group.ok() ? Status::Ok() : group.status();
  }
  if (type == "instance") return Instance(node);
  return Shape(node);
}

StatusOr<uint32_t> MitsubaSceneBuilder::ShapeGroup(const MitsubaNode& node) {
  if (const auto it = shape_groups_.find(&node); it != shape_groups_.end()) return it->second.group;
  StatusOr<MitsubaObject> read = Read(node);
  if (!read.ok()) return read.status();
  PTLAB_RETURN_IF_ERROR(read->Expect({}));
  const uint32_t first_row = uint32_t(scene_.triangles.size());
  const size_t first_sphere = scene_.spheres.size();
  const size_t first_grid = scene_.sdf_grids.size();
  for (const MitsubaNode* child : read->children()) {
    if (child->tag != "shape")
      return child->Error("<" + child->tag + "> is not allowed inside " + DescribeMitsuba(node) +
                          "; expected shape");
    const std::string& type = TypeOf(*child);
    if (type == "shapegroup" || type == "instance")
      return child->Error("nested instancing: " + DescribeMitsuba(*child) + " inside " +
                          DescribeMitsuba(node) +
                          "; a shapegroup holds plain shapes only (Mitsuba forbids nesting)");
    for (const MitsubaNode& grandchild : child->children)
      if (grandchild.tag == "emitter")
        return grandchild.Error("an emitter in a shape of " + DescribeMitsuba(node) +
                                "; shape groups hold no emitters (as in Mitsuba)");
    PTLAB_RETURN_IF_ERROR(Shape(*child));
  }
  GroupShapes shapes;
  const uint32_t rows = uint32_t(scene_.triangles.size()) - first_row;
  shapes.group = scene_.instances.AddGroup(first_row, rows);
  // The group's spheres leave the world's table: each instance adds its own.
  SphereTable& world = scene_.spheres;
  for (size_t i = first_sphere; i < world.size(); ++i)
    shapes.spheres.Append(world.Center(i), world.radius[i], world.material[i], world.uv_frame[i]);
  for (auto* column : {&world.center_x, &world.center_y, &world.center_z, &world.radius})
    column->resize(first_sphere);
  world.material.resize(first_sphere);
  world.uv_frame.resize(first_sphere);
  // Likewise its sdfgrids (in group space until an instance places them).
  for (size_t i = first_grid; i < scene_.sdf_grids.size(); ++i)
    shapes.sdf_grids.AppendPlaced(scene_.sdf_grids, i, scene_.sdf_grids.to_world[i],
                                  scene_.sdf_grids.material[i]);
  scene_.sdf_grids.Truncate(first_grid);
  shapes.lo = {INFINITY, INFINITY, INFINITY};
  shapes.hi = -shapes.lo;
  const TriangleTable& tri = scene_.triangles;
  for (uint32_t t = first_row; t < tri.size(); ++t)
    for (const Vec3f& v : {tri.V0(t), tri.V1(t), tri.V2(t)})
      shapes.lo = Min(shapes.lo, v), shapes.hi = Max(shapes.hi, v);
  for (size_t i = 0; i < shapes.sdf_grids.size(); ++i)
    for (int c = 0; c < 8; ++c) {
      const Vec3f v = shapes.sdf_grids.to_world[i].ApplyPoint(
          {float(c & 1), float((c >> 1) & 1), float((c >> 2) & 1)});
      shapes.lo = Min(shapes.lo, v), shapes.hi = Max(shapes.hi, v);
    }
  const uint32_t group = shapes.group;
  shape_groups_.emplace(&node, std::move(shapes));
  return group;
}

Status MitsubaSceneBuilder::Instance(const MitsubaNode& node) {
  StatusOr<MitsubaObject> read = Read(node);
  if (!read.ok()) return read.status();
  const MitsubaObject& obj = *read;
  PTLAB_RETURN_IF_ERROR(obj.Expect({"to_world"}));
  Transform to_world;
  PTLAB_RETURN_IF_ERROR(obj.TransformProperty("to_world", &to_world));
  // The <ref> (or nested object) element, for messages.
  const MitsubaNode* where = &node;
  for (const MitsubaNode& child : node.children)
    if (child.tag == "ref" || child.tag == "shape") where = &child;
  if (obj.children().size() != 1)
    return where->Error(DescribeMitsuba(node) + " needs exactly one <ref id=...> to a shapegroup");
  const MitsubaNode& target = *obj.children()[0];
  if (target.tag != "shape" || TypeOf(target) != "shapegroup")
    return where->Error(DescribeMitsuba(node) + " refers to " + DescribeMitsuba(target) + " (at " +
                        target.where + "); expected a <shape type=\"shapegroup\">");
  StatusOr<uint32_t> group = ShapeGroup(target);
  if (!group.ok()) return group.status();
  const GroupShapes& shapes = shape_groups_.at(&target);
  // The group's box in the world, inside the coordinate limit.
  if (shapes.lo.x <= shapes.hi.x) {
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3f p{corner & 1 ? shapes.hi.x : shapes.lo.x, corner & 2 ? shapes.hi.y : shapes.lo.y,
                    corner & 4 ? shapes.hi.z : shapes.lo.z};
      const Vec3f w = to_world.ApplyPoint(p);
      if (!(std::fabs(w.x) <= kMaxWorldCoordinate && std::fabs(w.y) <= kMaxWorldCoordinate &&
            std::fabs(w.z) <= kMaxWorldCoordinate))
        return node.Error(DescribeMitsuba(node) +
                          " places its group beyond the world's coordinate limit (|x| <= 1e12)");
    }
  }
  // A group's spheres and sdfgrids are copied per instance: the copies are counted before they
  // are made, against what the scene's files may expand into (--max-memory).
  if (shapes.spheres.size() > 0 || shapes.sdf_grids.size() > 0) {
    const double copies =
        double(scene_.spheres.size() + shapes.spheres.size()) * kSceneBytesPerSphere +
        double(scene_.sdf_grids.size() + shapes.sdf_grids.size()) * kSceneBytesPerSdfGrid;
    if (const std::string over = OverExpansionBudget(
            copies, doc_.input_bytes,
            "the instanced spheres and sdfgrids (" +
                std::to_string(scene_.spheres.size() + shapes.spheres.size()) + " spheres)");
        !over.empty())
      return node.Error(DescribeMitsuba(node) + ": " + over);
  }
  if (shapes.spheres.size() > 0) {
    float scale = 0;
    if (!IsSimilarity(to_world.matrix(), &scale))
      return Unsupported(node, "an instance of a group with a sphere under a non-uniform scale "
                               "or shear");
    // The uv frame: the group sphere's after the instance's (its inverse linear part · scale).
    const Matrix4& inv = to_world.inverse_matrix();
    SphereUvFrame placed;
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 3; ++col) placed[3 * row + col] = inv.m[row][col] * scale;
    for (size_t i = 0; i < shapes.spheres.size(); ++i) {
      if (scene_.spheres.size() + 1 >= kMaxSpheres) return node.Error("too many spheres");
      scene_.spheres.Append(to_world.ApplyPoint(shapes.spheres.Center(i)),
                            shapes.spheres.radius[i] * scale, shapes.spheres.material[i],
                            ComposeSphereUvFrames(shapes.spheres.uv_frame[i], placed));
    }
  }
  for (size_t i = 0; i < shapes.sdf_grids.size(); ++i) {
    if (scene_.sdf_grids.size() + 1 >= kMaxSdfGrids) return node.Error("too many sdfgrids");
    scene_.sdf_grids.AppendPlaced(shapes.sdf_grids, i, to_world * shapes.sdf_grids.to_world[i],
                                  shapes.sdf_grids.material[i]);
  }
  scene_.instances.AddInstance(*group, to_world);
  if (scene_.instances.instanced_prims() >= kMaxInstancedTriangles)
    return node.Error("too many instanced triangles (2^30 or more over all instances)");
  return Status::Ok();
}

}  // namespace ptlab::internal
