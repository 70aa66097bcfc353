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
                     const Traverse8Options& options) {
  return Intersect8Kernel(bvh, rays, active, hits, options);
}

Mask8 Occluded8Impl(const Bvh8& bvh, const RayPacket8& rays, Mask8 active,
                    const Traverse8Options& options) {
  return Occluded8Kernel(bvh, rays, active, options);
}

bool Intersect1Impl(const Bvh8& bvh, const Ray& ray, Hit* hit) {
  return Intersect1Kernel(bvh, ray, hit);
}

bool Occluded1Impl(const Bvh8& bvh, const Ray& ray) { return Occluded1Kernel(bvh, ray); }

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <bit>

#include "engine/bvh/instance_level.h"
#include "engine/core/check.h"
#include "simd/instance_box8.h"

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

// Instancing for single rays: the instance level's walks (engine/bvh/instance_level.h, the
// oracle's own code) with the groups' BVH8s as the group queries.
bool IntersectGroup8(const void* groups, uint32_t g, const Ray& ray, Hit* hit) {
  return Intersect1(static_cast<const Bvh8*>(groups)[g], ray, hit);
}

bool OccludedGroup8(const void* groups, uint32_t g, const Ray& ray) {
  return Occluded1(static_cast<const Bvh8*>(groups)[g], ray);
}

// The lanes of `lanes` whose ray enters the node's box in [t_min, t_far[j]] (InstanceBoxLanes:
// the oracle's IntersectBox in vectors; tested lane by lane with scalar code, the box tests
// cost 14 % of the instanced terrain's camera and shadow packets, perf 2026-12-07);
// *first_entry: the least entry distance among them (INFINITY if none).
Mask8 LanesInBox(const BvhNode& n, const InstanceLanes& l, const float* t_far, Mask8 lanes,
                 float* first_entry) {
  alignas(32) float t_entry[8];
  const Mask8 in = InstanceBoxLanes(n, l, t_far, t_entry) & lanes;
  float first = INFINITY;
  for (Mask8 todo = in; todo != 0; todo &= todo - 1)
    first = std::min(first, t_entry[std::countr_zero(todo)]);
  *first_entry = first;
  return in;
}

// RayToInstance for every lane of `rays` into `local` (the same operations in the same order,
// so the same bits), branch-free: a lane outside the caller's mask may compute with NaN,
// harmlessly; it is never traced.
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
        HitPacket8 h;
        const Mask8 got = HWY_DYNAMIC_DISPATCH(Intersect8Impl)(bvh.groups[level.group[i]], local,
                                                               lanes, &h, options);
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

// The instances of every packet go through the packet walk, whatever its lanes' octants.
// Measured on terrain16 (paired with Embree, 2026-12-07, one run each way, load 8): with the
// vectorized box test, against the lane-by-lane walk for packets of mixed octants: bounce rays
// Intersect8 0.73 -> 0.78, Occluded8 0.75 -> 0.83; shadow rays 0.76 -> 0.79, 0.83 -> 0.86 (the
// lane-by-lane walk had won with the scalar box test: 0.76 against 0.62, 2026-12-06). Every lane
// gets the oracle's hit bit for bit either way.
Mask8 Intersect8(const Bvh8& bvh, const RayPacket8& rays, Mask8 active, HitPacket8* hits,
                 const Traverse8Options& options) {
  const Mask8 hit = HWY_DYNAMIC_DISPATCH(Intersect8Impl)(bvh, rays, active, hits, options);
  if (bvh.instances.empty()) return hit;
  return IntersectInstancesPacket(bvh, rays, active & kAllLanes, hit, hits, options);
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
        done |=
            HWY_DYNAMIC_DISPATCH(Occluded8Impl)(bvh.groups[level.group[i]], local, lanes, options);
        if (done == open) return done;
      }
    }
    if (stack_size == 0) return done;
    current = stack[--stack_size];
  }
}

Mask8 Occluded8(const Bvh8& bvh, const RayPacket8& rays, Mask8 active,
                const Traverse8Options& options) {
  const Mask8 hit = HWY_DYNAMIC_DISPATCH(Occluded8Impl)(bvh, rays, active, options);
  if (bvh.instances.empty()) return hit;
  return hit | OccludedInstancesPacket(bvh, rays, active & kAllLanes & ~hit, options);
}

bool Intersect1(const Bvh8& bvh, const Ray& ray, Hit* hit) {
  const bool found = HWY_DYNAMIC_DISPATCH(Intersect1Impl)(bvh, ray, hit);
  if (bvh.instances.empty()) return found;
  return IntersectInstances(bvh.instances, ray, found, hit, IntersectGroup8, bvh.groups.data());
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
