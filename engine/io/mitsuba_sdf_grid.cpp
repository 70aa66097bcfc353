// Mitsuba <shape type="sdfgrid">: a .vol file of signed distances over the object box [0, 1]^3.
#include <cmath>

#include "engine/bvh/sdf_grid_intersect.h"
#include "engine/io/mitsuba_scene_builder.h"
#include "engine/io/vol_grid.h"
#include "engine/scene/scene_limits.h"

namespace ptlab::internal {

Status MitsubaSceneBuilder::SdfGridShape(const MitsubaObject& obj, const Transform& to_world,
                                         MaterialRef material) {
  std::string normals = "smooth", filename;
  PTLAB_RETURN_IF_ERROR(obj.String("normals", &normals));
  if (normals != "smooth" && normals != "analytic")
    return obj.Error("normals", "sdfgrid normals \"" + normals +
                                    "\"; expected \"analytic\" or \"smooth\"");
  // Mitsuba's `grid` (a tensor) exists only from Python or C++, never in XML.
  PTLAB_RETURN_IF_ERROR(obj.Require("filename"));
  PTLAB_RETURN_IF_ERROR(obj.String("filename", &filename));
  if (material.tag() == MaterialTag::kDiffuse && scene_.materials.diffuse.textured()) {
    const uint32_t tex = scene_.materials.diffuse.albedo_texture[material.index()];
    if (tex != kNoTexture && (scene_.textures.Kind(tex) == TextureKind::kFaceAttribute ||
                              scene_.textures.Kind(tex) == TextureKind::kVertexAttribute))
      return Unsupported(obj.node(), "a mesh_attribute texture on an sdfgrid (it has none)");
  }
  StatusOr<std::string> path = Resolve(obj, "filename", filename);
  if (!path.ok()) return path.status();
  StatusOr<VolGrid> grid = LoadVolGrid(*path);
  if (!grid.ok())
    return obj.Error("filename", "cannot load the grid of " + DescribeMitsuba(obj.node()) + ": " +
                                     grid.status().message());
  if (grid->channels != 1)
    return obj.Error("filename", "the sdfgrid's volume file has " +
                                     std::to_string(grid->channels) + " channels; expected 1");
  if (grid->nx < 2 || grid->ny < 2 || grid->nz < 2)
    return obj.Error("filename", "the sdfgrid's volume file is " + std::to_string(grid->nx) +
                                     " x " + std::to_string(grid->ny) + " x " +
                                     std::to_string(grid->nz) + "; expected at least 2 points "
                                     "per axis");
  bool any_cell = false;  // Mitsuba refuses a grid without a cell the surface can cross
  for (size_t i = 0; i < grid->values.size() && !any_cell; ++i)
    any_cell = grid->values[i] <= 0.0f;
  bool any_pos = false;
  for (size_t i = 0; i < grid->values.size() && !any_pos; ++i) any_pos = grid->values[i] >= 0.0f;
  if (!any_cell || !any_pos)
    return obj.Error("filename", "the sdfgrid's values never change sign: no surface");
  for (int c = 0; c < 8; ++c) {
    const Vec3f w = to_world.ApplyPoint(
        {float(c & 1), float((c >> 1) & 1), float((c >> 2) & 1)});
    if (!(std::fabs(w.x) <= kMaxWorldCoordinate && std::fabs(w.y) <= kMaxWorldCoordinate &&
          std::fabs(w.z) <= kMaxWorldCoordinate))
      return obj.node().Error("the sdfgrid's box reaches beyond the world's coordinate limit");
  }
  if (scene_.sdf_grids.size() + 1 >= kMaxSdfGrids) return obj.node().Error("too many sdfgrids");
  scene_.input_files.push_back(*path);
  scene_.sdf_grids.Append(grid->nx, grid->ny, grid->nz, grid->values, to_world, material,
                          normals == "smooth" ? SdfNormals::kSmooth : SdfNormals::kAnalytic);
  return Status::Ok();
}

}  // namespace ptlab::internal
