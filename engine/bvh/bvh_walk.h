// The two depth-first walks of a binary BVH (an inner node's left child follows it, `offset`
// is its right child), nearer child first, with the robust slab test of box_intersect.h. The
// leaf work is the caller's: triangle rows in intersect1.cpp, instances in instance_level.cpp.
#pragma once

#include <cstdint>

#include "engine/bvh/box_intersect.h"
#include "engine/bvh/bvh.h"
#include "engine/core/check.h"

namespace ptlab {

/// Closest-hit walk. A child is entered when the ray enters its box in [t_min, *best_t]; the
/// farther of two children is deferred with its entry distance and popped only while that
/// entry is at or before *best_t · kRobustFarScale. leaf(node) runs at each leaf reached and
/// may lower *best_t (the closest hit so far), which prunes what follows.
template <class LeafFn>
void WalkBvhClosest(const BvhNode* nodes, const SlabRay& slab, float t_min, const float* best_t,
                    LeafFn&& leaf) {
  struct Deferred {
    uint32_t node;
    float t_entry;
  };
  Deferred stack[kBvhMaxDepth];
  int stack_size = 0;
  float t_entry;
  if (!IntersectBox(nodes[0], slab, t_min, *best_t, &t_entry)) return;
  uint32_t current = 0;
  for (;;) {
    const BvhNode& node = nodes[current];
    if (!node.IsLeaf()) {
      const uint32_t left = current + 1, right = node.offset;
      float t_left, t_right;
      const bool hit_left = IntersectBox(nodes[left], slab, t_min, *best_t, &t_left);
      const bool hit_right = IntersectBox(nodes[right], slab, t_min, *best_t, &t_right);
      if (hit_left && hit_right) {
        PTLAB_DCHECK(stack_size < kBvhMaxDepth);
        const bool right_first = t_right < t_left;
        stack[stack_size++] = right_first ? Deferred{left, t_left} : Deferred{right, t_right};
        current = right_first ? right : left;
        continue;
      }
      if (hit_left || hit_right) {
        current = hit_left ? left : right;
        continue;
      }
    } else {
      leaf(node);
    }
    // Pop the next subtree that may still hold a hit at or before the closest one.
    for (;;) {
      if (stack_size == 0) return;
      const Deferred& e = stack[--stack_size];
      if (e.t_entry <= *best_t * kRobustFarScale) {
        current = e.node;
        break;
      }
    }
  }
}

/// Any-hit walk over the boxes the ray enters in [t_min, t_max]: true as soon as leaf(node)
/// returns true, false when the tree is exhausted.
template <class LeafFn>
bool WalkBvhAny(const BvhNode* nodes, const SlabRay& slab, float t_min, float t_max,
                LeafFn&& leaf) {
  uint32_t stack[kBvhMaxDepth];
  int stack_size = 0;
  float t_entry;
  if (!IntersectBox(nodes[0], slab, t_min, t_max, &t_entry)) return false;
  uint32_t current = 0;
  for (;;) {
    const BvhNode& node = nodes[current];
    if (!node.IsLeaf()) {
      const uint32_t left = current + 1, right = node.offset;
      float t_left, t_right;
      const bool hit_left = IntersectBox(nodes[left], slab, t_min, t_max, &t_left);
      const bool hit_right = IntersectBox(nodes[right], slab, t_min, t_max, &t_right);
      if (hit_left && hit_right) {
        PTLAB_DCHECK(stack_size < kBvhMaxDepth);
        const bool right_first = t_right < t_left;
        stack[stack_size++] = right_first ? left : right;
        current = right_first ? right : left;
        continue;
      }
      if (hit_left || hit_right) {
        current = hit_left ? left : right;
        continue;
      }
    } else if (leaf(node)) {
      return true;
    }
    if (stack_size == 0) return false;
    current = stack[--stack_size];
  }
}

}  // namespace ptlab
