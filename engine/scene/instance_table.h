// Instancing (Mitsuba `shapegroup` + `instance`): shape groups whose triangles are stored once,
// in group (object) space, and instances that place a group in the world by an affine transform.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/core/transform.h"

namespace ptlab {

/// Groups: each is the scene triangle rows [first_row, first_row + row_count) (TriangleTable,
/// TriangleShadingTable), in the group's own space; those rows are not part of the world on
/// their own, only through instances. Instances: a group and its to_world transform.
///
/// Hit ids: a hit on triangle `local` (0-based within its group) of instance i has
/// Hit::prim = T + first_prim[i] + local, where T is the scene's triangle count and
/// first_prim[i] the sum of the row counts of the groups of instances 0..i-1 (InstanceHitId).
/// So every (instance, triangle) pair has its own id above the scene's triangle rows and below
/// kSphereHitBit, and closest-hit ties break on it as on any other id. An empty table costs
/// nothing: traversal checks it once per ray or packet.
struct InstanceTable {
  std::vector<uint32_t> group_first_row, group_row_count;  // per group
  std::vector<uint32_t> group;                             // per instance: its group
  std::vector<Transform> to_world;                         // per instance
  std::vector<uint32_t> first_prim;                        // per instance (see above)

  size_t groups() const { return group_first_row.size(); }
  size_t size() const { return group.size(); }
  bool empty() const { return group.empty(); }
  /// Instanced ids in use: first_prim of the next instance.
  uint64_t instanced_prims() const {
    return group.empty() ? 0 : uint64_t{first_prim.back()} + group_row_count[group.back()];
  }

  uint32_t AddGroup(uint32_t first_row, uint32_t row_count) {
    group_first_row.push_back(first_row);
    group_row_count.push_back(row_count);
    return uint32_t(group_first_row.size() - 1);
  }
  void AddInstance(uint32_t g, const Transform& t) {
    first_prim.push_back(uint32_t(instanced_prims()));
    group.push_back(g);
    to_world.push_back(t);
  }
};

/// Where an instanced hit id points: the instance and the scene triangle row (in group space).
struct InstancedRow {
  uint32_t instance;
  uint32_t row;
};

/// Whether `prim` (a triangle hit id, not a sphere's) is an instanced id of a scene with
/// `triangle_rows` triangle rows.
inline bool IsInstancedHit(uint32_t prim, size_t triangle_rows) { return prim >= triangle_rows; }

/// The instance and group row of instanced hit id `prim` (IsInstancedHit): a binary search
/// over the instances' first ids.
inline InstancedRow FindInstancedRow(const InstanceTable& t, size_t triangle_rows, uint32_t prim) {
  const uint32_t x = prim - uint32_t(triangle_rows);
  const auto it = std::upper_bound(t.first_prim.begin(), t.first_prim.end(), x);
  const uint32_t i = uint32_t(it - t.first_prim.begin()) - 1;
  return {i, t.group_first_row[t.group[i]] + (x - t.first_prim[i])};
}

}  // namespace ptlab
