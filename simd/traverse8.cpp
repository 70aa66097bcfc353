// Highway dynamic dispatch of simd/traverse8 (foreach_target over traverse8-inl.h) and the
// plain C++ entry points.

// Bit-identity with the oracle needs every a * b + c evaluated as two rounded operations: GCC
// contracts vector (and scalar) multiply-add into FMA on the AVX2/AVX-512 targets otherwise.
#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

// clang-format off
#include "simd/targets.h"  // first: the target policy
// clang-format on

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/traverse8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/traverse8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

Mask8 Intersect8Impl(const Bvh8& bvh, const RayPacket8& rays, Mask8 active, HitPacket8* hits,
                     const Traverse8Options& options, const float* t_bound) {
  return Intersect8Kernel(bvh, rays, active, hits, options, t_bound);
}

Mask8 Occluded8Impl(const Bvh8& bvh, const RayPacket8& rays, Mask8 active,
                    const Traverse8Options& options) {
  return Occluded8Kernel(bvh, rays, active, options);
}

bool Intersect1Impl(const Bvh8& bvh, const Ray& ray, Hit* hit, float t_bound) {
  return Intersect1Kernel(bvh, ray, hit, t_bound);
}

bool Occluded1Impl(const Bvh8& bvh, const Ray& ray) { return Occluded1Kernel(bvh, ray); }

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <bit>

#include "engine/bvh/box_intersect.h"
#include "engine/bvh/bvh_walk.h"
#include "engine/bvh/instance_level.h"
#include "engine/core/check.h"

namespace ptlab::simd {

HWY_EXPORT(Intersect8Impl);
HWY_EXPORT(Occluded8Impl);
HWY_EXPORT(Intersect1Impl);
HWY_EXPORT(Occluded1Impl);

namespace {

// Interleaves the low 10 bits of x, y, z (Morton order).
uint32_t Morton3(uint32_t x, uint32_t y, uint32_t z) {
  auto spread = [](uint32_t v) {
    v &= 0x3ffu;
    v = (v | (v << 16)) & 0x030000ffu;
    v = (v | (v << 8)) & 0x0300f00fu;
    v = (v | (v << 4)) & 0x030c30c3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
  };
  return spread(x) | (spread(y) << 1) | (spread(z) << 2);
}

// Instancing: the instance level's any-hit walk (engine/bvh/instance_level.h, the oracle's own
// code) with the groups' BVH8s as the group queries, lane by lane after the top level's packet.

bool OccludedGroup8(const void* groups, uint32_t g, const Ray& ray) {
  return Occluded1(static_cast<const Bvh8*>(groups)[g], ray);
}

// The pruning bound of a group query (Intersect8Kernel's t_bound) for a lane whose best hit so
// far is at best_t (`found`) or none (best_t = the ray's t_max). With a hit, the next float
// above it: a group hit at exactly best_t must still come back, to break the tie on the id
// here (the packet leaf test, like the oracle's, keeps a hit at t = its start distance only
// below it), and anything the group returns beyond best_t loses the comparison that follows.
// Safe for the same reason the oracle's own walk may prune boxes with its closest hit: the
// robust slab test never rejects a box holding a triangle hit at or before the bound.
float GroupBound(bool found, float best_t) {
  return found ? std::nextafter(best_t, INFINITY) : best_t;
}

// A group may hold spheres or sdfgrids (not today: a group's spheres become world spheres);
// their tests take the closest distance as t_max, so such a group is queried unbounded.
bool Boundable(const Bvh8& group) {
  return group.spheres.size() == 0 && group.sdf_grids.size() == 0;
}

// The instances' closest hit for one ray: the oracle's IntersectInstances walk (same boxes,
// same order, the same (t, id) rule) whose group queries start at the best hit so far
// (GroupBound) instead of the ray's t_max, so a group behind the best hit is left after its
// first boxes. The hits a query returns at or before the best hit are the unbounded query's.
bool IntersectInstances8(const Bvh8& bvh, const Ray& ray, bool found, Hit* best) {
  const InstanceLevel& level = bvh.instances;
  if (level.empty() || !(ray.t_min < ray.t_max)) return found;
  float best_t = found ? best->t : ray.t_max;
  WalkBvhClosest(level.nodes.data(), MakeSlabRay(ray), ray.t_min, &best_t,
                 [&](const BvhNode& node) {
                   const uint32_t i = level.order[node.offset];
                   const Bvh8& group = bvh.groups[level.group[i]];
                   const float bound = Boundable(group) ? GroupBound(found, best_t) : ray.t_max;
                   Hit h;
                   if (!HWY_DYNAMIC_DISPATCH(Intersect1Impl)(group, RayToInstance(level, i, ray),
                                                             &h, bound))
                     return;
                   const uint32_t prim = level.first_prim[i] + h.prim;
                   if (!found || h.t < best->t || (h.t == best->t && prim < best->prim)) {
                     *best = {h.t, h.b1, h.b2, prim};
                     best_t = h.t;
                     found = true;
                   }
                 });
  return found;
}

// The instance tree's box test for the eight lanes of a packet at once: IntersectBox's
// operations (the same slab distances, the same NaN-tolerant max/min order, the same robust far
// scale) over lane arrays, which the compiler vectorizes; the scalar test per lane cost 14 % of
// the instanced terrain's camera and shadow packets (perf, 2026-12-07). Conservative like the
// oracle's: a lane skips only instances it cannot hit at or before its far end.
struct InstanceLanes {
  alignas(32) float o[3][8], inv[3][8];
  alignas(32) float t_min[8];
  alignas(32) float neg[3][8];  // 1 where the lane's inv_d component is negative (signbit)
};

// Lanes of `rays` in `live` (others get benign values that enter nothing).
InstanceLanes MakeInstanceLanes(const RayPacket8& rays, Mask8 live) {
  InstanceLanes l;
  const float* org[3] = {rays.org_x, rays.org_y, rays.org_z};
  const float* dir[3] = {rays.dir_x, rays.dir_y, rays.dir_z};
  for (int j = 0; j < 8; ++j) {
    const bool on = LaneActive(live, j);
    for (int a = 0; a < 3; ++a) {
      l.o[a][j] = on ? org[a][j] : 0.0f;
      l.inv[a][j] = on ? 1.0f / dir[a][j] : 1.0f;
      l.neg[a][j] = std::signbit(l.inv[a][j]) ? 1.0f : 0.0f;
    }
    l.t_min[j] = on ? rays.t_min[j] : 1.0f;
  }
  return l;
}

// Lanes of `lanes` whose ray enters the node's box in [t_min, t_far[j]]; *first_entry: the
// least entry distance among them (INFINITY if none). Lanes outside `lanes` need benign
// t_far (finite or not, never NaN-producing beyond what the test tolerates).
Mask8 LanesInBox(const BvhNode& n, const InstanceLanes& l, const float* t_far, Mask8 lanes,
                 float* first_entry) {
  const float lo[3] = {n.bounds_min.x, n.bounds_min.y, n.bounds_min.z};
  const float hi[3] = {n.bounds_max.x, n.bounds_max.y, n.bounds_max.z};
  alignas(32) float t0[8], t1[8];
  for (int j = 0; j < 8; ++j) t0[j] = l.t_min[j], t1[j] = t_far[j];
  for (int a = 0; a < 3; ++a) {
    for (int j = 0; j < 8; ++j) {
      const bool neg = l.neg[a][j] != 0.0f;
      const float near = ((neg ? hi[a] : lo[a]) - l.o[a][j]) * l.inv[a][j];
      const float far = ((neg ? lo[a] : hi[a]) - l.o[a][j]) * l.inv[a][j];
      t0[j] = near > t0[j] ? near : t0[j];
      t1[j] = far < t1[j] ? far : t1[j];
    }
  }
  Mask8 in = 0;
  float first = INFINITY;
  for (int j = 0; j < 8; ++j) {
    const bool enters = t0[j] <= t1[j] * kRobustFarScale;
    in |= Mask8(enters) << j;
  }
  in &= lanes;
  for (Mask8 todo = in; todo != 0; todo &= todo - 1) {
    const int j = std::countr_zero(todo);
    first = std::min(first, t0[j]);
  }
  *first_entry = first;
  return in;
}

// RayToInstance for the lanes of `lanes` (the same operations in the same order, so the same
// bits), into `local`: every lane, branch-free (a lane outside the caller's mask may compute
// with NaN, harmlessly; it is never traced).
void PacketToInstance(const InstanceLevel& level, uint32_t i, const RayPacket8& rays,
                      RayPacket8* local) {
  const float* m = level.world_to_group.data() + size_t(i) * 12;
  for (int j = 0; j < 8; ++j) {
    const float ox = rays.org_x[j], oy = rays.org_y[j], oz = rays.org_z[j];
    const float dx = rays.dir_x[j], dy = rays.dir_y[j], dz = rays.dir_z[j];
    local->org_x[j] = m[0] * ox + m[1] * oy + m[2] * oz + m[3];
    local->org_y[j] = m[4] * ox + m[5] * oy + m[6] * oz + m[7];
    local->org_z[j] = m[8] * ox + m[9] * oy + m[10] * oz + m[11];
    local->dir_x[j] = m[0] * dx + m[1] * dy + m[2] * dz;
    local->dir_y[j] = m[4] * dx + m[5] * dy + m[6] * dz;
    local->dir_z[j] = m[8] * dx + m[9] * dy + m[10] * dz;
    local->t_min[j] = rays.t_min[j];
    local->t_max[j] = rays.t_max[j];
  }
}

}  // namespace

// The instance level for a packet: the instance tree walked once for all lanes (a node is
// entered when any lane's ray enters its box before that lane's best hit, the oracle's
// conservative slab test lane by lane), and at each instance the lanes that enter its box moved
// into the group (RayToInstance, the oracle's function) and traced as one packet through the
// group's BVH8. Each lane keeps the least (t, id), which does not depend on the visiting order,
// so every lane's hit is the oracle's (IntersectInstances) bit for bit. `hit`: the lanes that
// hold a hit in *hits already; returns the lanes that hold one now.
Mask8 IntersectInstancesPacket(const Bvh8& bvh, const RayPacket8& rays, Mask8 active, Mask8 hit,
                               HitPacket8* hits, const Traverse8Options& options) {
  const InstanceLevel& level = bvh.instances;
  for (Mask8 todo = active; todo != 0; todo &= todo - 1) {
    const int j = std::countr_zero(todo);
    if (!(rays.t_min[j] < rays.t_max[j])) active &= ~LaneBit(j);
  }
  const InstanceLanes lanes8 = MakeInstanceLanes(rays, active);
  alignas(32) float best_t[8];
  for (int j = 0; j < 8; ++j)
    best_t[j] = !LaneActive(active, j) ? 0.0f : LaneActive(hit, j) ? hits->t[j] : rays.t_max[j];
  uint32_t stack[kBvhMaxDepth];
  int stack_size = 0;
  float entry;
  if (LanesInBox(level.nodes[0], lanes8, best_t, active, &entry) == 0) return hit;
  uint32_t current = 0;
  for (;;) {
    const BvhNode& node = level.nodes[current];
    if (!node.IsLeaf()) {
      const uint32_t left = current + 1, right = node.offset;
      float e_left, e_right;
      const bool l = LanesInBox(level.nodes[left], lanes8, best_t, active, &e_left) != 0;
      const bool r = LanesInBox(level.nodes[right], lanes8, best_t, active, &e_right) != 0;
      if (l && r) {
        stack[stack_size++] = e_right < e_left ? left : right;
        current = e_right < e_left ? right : left;
        continue;
      }
      if (l || r) {
        current = l ? left : right;
        continue;
      }
    } else {
      const uint32_t i = level.order[node.offset];
      const Mask8 lanes = LanesInBox(node, lanes8, best_t, active, &entry);
      if (lanes != 0) {
        RayPacket8 local;
        PacketToInstance(level, i, rays, &local);
        const Bvh8& group = bvh.groups[level.group[i]];
        alignas(32) float bound[8] = {};
        for (Mask8 todo = lanes; todo != 0; todo &= todo - 1) {
          const int j = std::countr_zero(todo);
          bound[j] = GroupBound(LaneActive(hit, j), best_t[j]);
        }
        HitPacket8 h;
        const Mask8 got = HWY_DYNAMIC_DISPATCH(Intersect8Impl)(
            group, local, lanes, &h, options, Boundable(group) ? bound : nullptr);
        for (Mask8 todo = got; todo != 0; todo &= todo - 1) {
          const int j = std::countr_zero(todo);
          const uint32_t prim = level.first_prim[i] + h.prim[j];
          if (!LaneActive(hit, j) || h.t[j] < hits->t[j] ||
              (h.t[j] == hits->t[j] && prim < hits->prim[j])) {
            SetLaneHit(hits, j, h.t[j], h.b1[j], h.b2[j], prim);
            best_t[j] = h.t[j];
            hit |= LaneBit(j);
          }
        }
      }
    }
    if (stack_size == 0) return hit;
    current = stack[--stack_size];
  }
}

// Whether the active lanes' directions all point into one octant (sign bits of d equal).
bool OneOctant(const RayPacket8& rays, Mask8 active) {
  int octant = -1;
  for (Mask8 todo = active; todo != 0; todo &= todo - 1) {
    const int j = std::countr_zero(todo);
    const int o = int(std::signbit(rays.dir_x[j])) | int(std::signbit(rays.dir_y[j])) << 1 |
                  int(std::signbit(rays.dir_z[j])) << 2;
    if (octant >= 0 && o != octant) return false;
    octant = o;
  }
  return true;
}

// The instances: packets whose lanes share a direction octant as a packet
// (IntersectInstancesPacket), others lane by lane (the oracle's walk with the groups' BVH8s).
// Measured on terrain16 (paired with Embree, 2026-12-06): the packet walk took camera rays'
// Intersect8 from 0.84 to 0.91 of Embree but bounce rays' from 0.76 to 0.62; shadow rays 0.75 /
// 0.74. Both give the oracle's hits bit for bit.
Mask8 Intersect8(const Bvh8& bvh, const RayPacket8& rays, Mask8 active, HitPacket8* hits,
                 const Traverse8Options& options) {
  Mask8 hit = HWY_DYNAMIC_DISPATCH(Intersect8Impl)(bvh, rays, active, hits, options, nullptr);
  if (bvh.instances.empty()) return hit;
  active &= kAllLanes;
  if (OneOctant(rays, active))
    return IntersectInstancesPacket(bvh, rays, active, hit, hits, options);
  for (Mask8 todo = active; todo != 0; todo &= todo - 1) {
    const int j = std::countr_zero(todo);
    Hit h{hits->t[j], hits->b1[j], hits->b2[j], hits->prim[j]};
    if (IntersectInstances8(bvh, GetLaneRay(rays, j), LaneActive(hit, j), &h)) {
      SetLaneHit(hits, j, h.t, h.b1, h.b2, h.prim);
      hit |= LaneBit(j);
    }
  }
  return hit;
}

// Any hit on the instances for a packet: the instance tree walked once for the open lanes, each
// instance's entering lanes moved into the group and traced with Occluded8; a lane closes at its
// first hit. Returns the lanes of `open` that are occluded.
Mask8 OccludedInstancesPacket(const Bvh8& bvh, const RayPacket8& rays, Mask8 open,
                              const Traverse8Options& options) {
  const InstanceLevel& level = bvh.instances;
  for (Mask8 todo = open; todo != 0; todo &= todo - 1) {
    const int j = std::countr_zero(todo);
    if (!(rays.t_min[j] < rays.t_max[j])) open &= ~LaneBit(j);
  }
  const InstanceLanes lanes8 = MakeInstanceLanes(rays, open);
  alignas(32) float t_max[8];
  for (int j = 0; j < 8; ++j) t_max[j] = LaneActive(open, j) ? rays.t_max[j] : 0.0f;
  Mask8 done = 0;
  float entry;
  uint32_t stack[kBvhMaxDepth];
  int stack_size = 0;
  if (open == 0 || LanesInBox(level.nodes[0], lanes8, t_max, open, &entry) == 0) return 0;
  uint32_t current = 0;
  for (;;) {
    const BvhNode& node = level.nodes[current];
    if (!node.IsLeaf()) {
      const uint32_t left = current + 1, right = node.offset;
      const bool l = LanesInBox(level.nodes[left], lanes8, t_max, open & ~done, &entry) != 0;
      const bool r = LanesInBox(level.nodes[right], lanes8, t_max, open & ~done, &entry) != 0;
      if (l && r) stack[stack_size++] = right;
      if (l || r) {
        current = l ? left : right;
        continue;
      }
    } else {
      const uint32_t i = level.order[node.offset];
      const Mask8 lanes = LanesInBox(node, lanes8, t_max, open & ~done, &entry);
      if (lanes != 0) {
        RayPacket8 local;
        PacketToInstance(level, i, rays, &local);
        done |= HWY_DYNAMIC_DISPATCH(Occluded8Impl)(bvh.groups[level.group[i]], local, lanes,
                                                    options);
        if (done == open) return done;
      }
    }
    if (stack_size == 0) return done;
    current = stack[--stack_size];
  }
}

Mask8 Occluded8(const Bvh8& bvh, const RayPacket8& rays, Mask8 active,
                const Traverse8Options& options) {
  Mask8 hit = HWY_DYNAMIC_DISPATCH(Occluded8Impl)(bvh, rays, active, options);
  if (bvh.instances.empty()) return hit;
  if (OneOctant(rays, active & kAllLanes & ~hit))
    return hit | OccludedInstancesPacket(bvh, rays, active & kAllLanes & ~hit, options);
  for (Mask8 todo = active & kAllLanes & ~hit; todo != 0; todo &= todo - 1) {
    const int j = std::countr_zero(todo);
    if (OccludedInstances(bvh.instances, GetLaneRay(rays, j), OccludedGroup8, bvh.groups.data()))
      hit |= LaneBit(j);
  }
  return hit;
}

bool Intersect1(const Bvh8& bvh, const Ray& ray, Hit* hit) {
  const bool found = HWY_DYNAMIC_DISPATCH(Intersect1Impl)(bvh, ray, hit, ray.t_max);
  if (bvh.instances.empty()) return found;
  return IntersectInstances8(bvh, ray, found, hit);
}

bool Occluded1(const Bvh8& bvh, const Ray& ray) {
  if (HWY_DYNAMIC_DISPATCH(Occluded1Impl)(bvh, ray)) return true;
  return !bvh.instances.empty() &&
         OccludedInstances(bvh.instances, ray, OccludedGroup8, bvh.groups.data());
}

void IntersectStream(const Bvh8& bvh, const Ray* rays, size_t n, Hit* hits, uint8_t* hit_mask,
                     uint32_t* scratch, const Traverse8Options& options) {
  std::fill(hit_mask, hit_mask + n, uint8_t{0});
  if (bvh.empty() || n == 0) return;
  // Scene box = union of the root's child boxes.
  const Bvh8Node& root = bvh.Node(0);
  Vec3f lo = {root.lo_x[0], root.lo_y[0], root.lo_z[0]};
  Vec3f hi = {root.hi_x[0], root.hi_y[0], root.hi_z[0]};
  for (uint32_t c = 1; c < root.num_children; ++c) {
    lo = Min(lo, Vec3f{root.lo_x[c], root.lo_y[c], root.lo_z[c]});
    hi = Max(hi, Vec3f{root.hi_x[c], root.hi_y[c], root.hi_z[c]});
  }
  const Vec3f extent = hi - lo;
  auto quantize = [](float v, float l, float e) {
    const float q = e > 0.0f ? (v - l) / e * 1023.0f : 0.0f;
    return static_cast<uint32_t>(std::clamp(q, 0.0f, 1023.0f));
  };
  // Key: direction octant (3 bits) above the Morton code of the origin (30 bits), above the
  // ray index (the low 29 bits; streams are limited to 2^29 rays).
  PTLAB_CHECK(n < (size_t{1} << 29));
  std::vector<uint64_t> keys(n);
  for (size_t i = 0; i < n; ++i) {
    const Ray& r = rays[i];
    const uint32_t octant = (r.d.x < 0 ? 1u : 0u) | (r.d.y < 0 ? 2u : 0u) | (r.d.z < 0 ? 4u : 0u);
    const uint32_t morton =
        Morton3(quantize(r.o.x, lo.x, extent.x), quantize(r.o.y, lo.y, extent.y),
                quantize(r.o.z, lo.z, extent.z));
    keys[i] = (uint64_t{octant} << 59) | (uint64_t{morton} << 29) | i;
  }
  std::sort(keys.begin(), keys.end());
  for (size_t i = 0; i < n; ++i) scratch[i] = static_cast<uint32_t>(keys[i] & ((1u << 29) - 1));
  for (size_t base = 0; base < n; base += 8) {
    RayPacket8 p;
    const int count = static_cast<int>(std::min<size_t>(8, n - base));
    for (int j = 0; j < count; ++j) SetLaneRay(&p, j, rays[scratch[base + j]]);
    HitPacket8 h;
    const Mask8 got = Intersect8(bvh, p, (1u << count) - 1, &h, options);
    for (int j = 0; j < count; ++j) {
      if (!LaneActive(got, j)) continue;
      const uint32_t i = scratch[base + j];
      hits[i] = {h.t[j], h.b1[j], h.b2[j], h.prim[j]};
      hit_mask[i] = 1;
    }
  }
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
