// Instancing's top level: a median-split tree over instance boxes and its two walks.
#include "engine/bvh/instance_level.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "engine/bvh/bvh_walk.h"

namespace ptlab {
namespace {

struct InstanceBox {
  Vec3f lo, hi;
  uint32_t instance;
};

// Depth-first median split on the longest axis of the centroids' box; one instance per leaf.
// Depth is below log2(n) + 1, far below kBvhMaxDepth.
uint32_t BuildNode(std::vector<InstanceBox>& boxes, size_t begin, size_t end, InstanceLevel* l) {
  const uint32_t index = uint32_t(l->nodes.size());
  l->nodes.emplace_back();
  Vec3f lo = boxes[begin].lo, hi = boxes[begin].hi;
  Vec3f clo = (boxes[begin].lo + boxes[begin].hi) * 0.5f, chi = clo;
  for (size_t i = begin; i < end; ++i) {
    lo = Min(lo, boxes[i].lo), hi = Max(hi, boxes[i].hi);
    const Vec3f c = (boxes[i].lo + boxes[i].hi) * 0.5f;
    clo = Min(clo, c), chi = Max(chi, c);
  }
  l->nodes[index].bounds_min = lo;
  l->nodes[index].bounds_max = hi;
  if (end - begin == 1) {
    l->nodes[index].offset = uint32_t(l->order.size());
    l->nodes[index].count = 1;
    l->order.push_back(boxes[begin].instance);
    return index;
  }
  const Vec3f side = chi - clo;
  const int axis = side.x >= side.y && side.x >= side.z ? 0 : side.y >= side.z ? 1 : 2;
  const size_t mid = begin + (end - begin) / 2;
  const auto key = [axis](const InstanceBox& b) {
    const float c[3] = {b.lo.x + b.hi.x, b.lo.y + b.hi.y, b.lo.z + b.hi.z};
    return c[axis];
  };
  std::nth_element(boxes.begin() + long(begin), boxes.begin() + long(mid), boxes.begin() + long(end),
                   [&](const InstanceBox& a, const InstanceBox& b) {
                     return key(a) < key(b) || (key(a) == key(b) && a.instance < b.instance);
                   });
  BuildNode(boxes, begin, mid, l);
  const uint32_t right = BuildNode(boxes, mid, end, l);
  l->nodes[index].offset = right;
  l->nodes[index].axis = uint16_t(axis);
  return index;
}

}  // namespace

InstanceLevel BuildInstanceLevel(const InstanceTable& instances, uint32_t triangle_rows,
                                 const std::vector<GroupBounds>& group_bounds) {
  InstanceLevel l;
  const size_t n = instances.size();
  if (n == 0) return l;
  std::vector<InstanceBox> boxes;
  for (uint32_t i = 0; i < n; ++i) {
    const GroupBounds& g = group_bounds[instances.group[i]];
    const Matrix4& inv = instances.to_world[i].inverse_matrix();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) l.world_to_group.push_back(inv.m[r][c]);
    l.group.push_back(instances.group[i]);
    l.first_prim.push_back(triangle_rows + instances.first_prim[i]);
    if (!(g.lo.x <= g.hi.x && g.lo.y <= g.hi.y && g.lo.z <= g.hi.z)) continue;
    Vec3f lo{INFINITY, INFINITY, INFINITY}, hi = -lo;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3f p{corner & 1 ? g.hi.x : g.lo.x, corner & 2 ? g.hi.y : g.lo.y,
                    corner & 4 ? g.hi.z : g.lo.z};
      const Vec3f w = instances.to_world[i].ApplyPoint(p);
      lo = Min(lo, w), hi = Max(hi, w);
    }
    const float mag = std::max({std::fabs(lo.x), std::fabs(lo.y), std::fabs(lo.z),
                                std::fabs(hi.x), std::fabs(hi.y), std::fabs(hi.z)});
    const Vec3f pad{1e-5f * mag, 1e-5f * mag, 1e-5f * mag};
    boxes.push_back({lo - pad, hi + pad, i});
  }
  if (!boxes.empty()) BuildNode(boxes, 0, boxes.size(), &l);
  return l;
}

Ray RayToInstance(const InstanceLevel& level, uint32_t i, const Ray& ray) {
  const float* m = level.world_to_group.data() + size_t(i) * 12;
  const Vec3f o = ray.o, d = ray.d;
  Ray r;
  r.o = {m[0] * o.x + m[1] * o.y + m[2] * o.z + m[3], m[4] * o.x + m[5] * o.y + m[6] * o.z + m[7],
         m[8] * o.x + m[9] * o.y + m[10] * o.z + m[11]};
  r.d = {m[0] * d.x + m[1] * d.y + m[2] * d.z, m[4] * d.x + m[5] * d.y + m[6] * d.z,
         m[8] * d.x + m[9] * d.y + m[10] * d.z};
  r.t_min = ray.t_min;
  r.t_max = ray.t_max;
  return r;
}

bool IntersectInstances(const InstanceLevel& level, const Ray& ray, bool found, Hit* best,
                        GroupIntersectFn intersect, const void* groups) {
  if (level.empty() || !(ray.t_min < ray.t_max)) return found;
  float best_t = found ? best->t : ray.t_max;
  WalkBvhClosest(level.nodes.data(), MakeSlabRay(ray), ray.t_min, &best_t,
                 [&](const BvhNode& node) {
                   const uint32_t i = level.order[node.offset];
                   Hit h;
                   if (!intersect(groups, level.group[i], RayToInstance(level, i, ray), &h)) return;
                   const uint32_t prim = level.first_prim[i] + h.prim;
                   if (!found || h.t < best->t || (h.t == best->t && prim < best->prim)) {
                     *best = {h.t, h.b1, h.b2, prim};
                     best_t = h.t;
                     found = true;
                   }
                 });
  return found;
}

bool OccludedInstances(const InstanceLevel& level, const Ray& ray, GroupOccludedFn occluded,
                       const void* groups) {
  if (level.empty() || !(ray.t_min < ray.t_max)) return false;
  return WalkBvhAny(level.nodes.data(), MakeSlabRay(ray), ray.t_min, ray.t_max,
                    [&](const BvhNode& node) {
                      const uint32_t i = level.order[node.offset];
                      return occluded(groups, level.group[i], RayToInstance(level, i, ray));
                    });
}

}  // namespace ptlab
