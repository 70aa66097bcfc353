// BuildSceneBvh: one tree, or the top tree, the group trees and the instance level.
#include "engine/bvh/scene_bvh.h"

#include <cmath>
#include <vector>

#include "engine/bvh/bvh_build.h"
#include "engine/bvh/instance_level.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/core/check.h"

namespace ptlab {
namespace {

void AppendRow(const TriangleTable& from, uint32_t row, TriangleTable* to) {
  to->Append(from.V0(row), from.V1(row), from.V2(row));
}

}  // namespace

Bvh BuildSceneBvh(const Scene& scene, int threads) {
  const InstanceTable& in = scene.instances;
  if (in.groups() == 0) {
    Bvh bvh = BuildBvh(scene.triangles, scene.spheres, threads);
    bvh.sdf_grids = scene.sdf_grids;
    return bvh;
  }
  const TriangleTable& all = scene.triangles;
  const uint32_t rows = uint32_t(all.size());
  PTLAB_CHECK(uint64_t{rows} + in.instanced_prims() < uint64_t{kSphereHitBit});
  std::vector<uint8_t> grouped(rows, 0);
  for (size_t g = 0; g < in.groups(); ++g)
    for (uint32_t r = in.group_first_row[g]; r < in.group_first_row[g] + in.group_row_count[g]; ++r)
      grouped[r] = 1;
  TriangleTable top;
  std::vector<uint32_t> top_rows;
  for (uint32_t r = 0; r < rows; ++r)
    if (!grouped[r]) AppendRow(all, r, &top), top_rows.push_back(r);
  Bvh bvh = BuildBvh(top, scene.spheres, threads);
  bvh.sdf_grids = scene.sdf_grids;
  for (uint32_t& p : bvh.prim_id) p = top_rows[p];
  std::vector<GroupBounds> bounds;
  for (size_t g = 0; g < in.groups(); ++g) {
    TriangleTable t;
    for (uint32_t r = in.group_first_row[g]; r < in.group_first_row[g] + in.group_row_count[g]; ++r)
      AppendRow(all, r, &t);
    bvh.groups.push_back(BuildBvh(t));
    const Bvh& gb = bvh.groups.back();
    if (gb.empty())
      bounds.push_back({{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}});
    else
      bounds.push_back({gb.nodes[0].bounds_min, gb.nodes[0].bounds_max});
  }
  bvh.instances = BuildInstanceLevel(in, rows, bounds);
  return bvh;
}

}  // namespace ptlab
