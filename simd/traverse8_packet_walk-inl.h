// simd/traverse8's packet walk (closest hit and any hit), with the hybrid switch to single rays.
// Part of simd/traverse8-inl.h: re-included once per target with it (hwy/foreach_target.h).

#if defined(PTLAB_SIMD_TRAVERSE8_PACKET_WALK_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TRAVERSE8_PACKET_WALK_INL_H_
#undef PTLAB_SIMD_TRAVERSE8_PACKET_WALK_INL_H_
#else
#define PTLAB_SIMD_TRAVERSE8_PACKET_WALK_INL_H_
#endif

#include "hwy/highway.h"
#include "simd/traverse8_packet_nodes-inl.h"
#include "simd/traverse8_packet_leaves-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Out of line, so that the single-ray loop is compiled as tightly as simd::Intersect1 and not
// inside the much larger packet function (measured: ~15% faster on incoherent packets). The
// loop over the lanes is inside: one call and one stack frame for the lanes of a subtree.
template <bool kAnyHit>
HWY_NOINLINE uint32_t TraverseLanesAlone(const Bvh8& bvh, Bvh8Ref ref, PacketState* s, uint32_t m) {
  uint32_t hit_lanes = 0;
  for (; m != 0; m &= m - 1) {
    const int j = std::countr_zero(m);
    LaneBest best{s->best_t[j], static_cast<uint32_t>(s->best_prim[j]), s->best_b1[j],
                  s->best_b2[j]};
    if (TraverseSingle<kAnyHit>(bvh, ref, LaneSingleRay(*s, j), s->wt, static_cast<size_t>(j),
                                &best)) {
      hit_lanes |= LaneBit(j);
    }
    if constexpr (!kAnyHit) {
      s->best_t[j] = best.t, s->best_prim[j] = static_cast<int32_t>(best.prim);
      s->best_b1[j] = best.b1, s->best_b2[j] = best.b2;
    }
  }
  return hit_lanes;
}

// Each lane of m traverses the subtree `ref` alone. Returns the lanes that hit (any hit).
template <bool kAnyHit>
HWY_INLINE uint32_t SingleRayLanes(const Bvh8& bvh, Bvh8Ref ref, PacketState* s, uint32_t m) {
  // Any hit: a leaf needs none of the traversal's setup, each lane tests it from its lane of
  // the packet. Measured (Occluded8, same run): shadow rays table +7 %, terrain +3 %,
  // bounce rays terrain +7 %. Closest hit lost 3 % on camera rays that way (table, terrain),
  // so it keeps the traversal. In the renders, of the lanes that go single, those at a leaf
  // are any hit: table 32 %, veach 6 %; closest hit: table 44 %, veach 66 %.
  if (kAnyHit && IsLeaf(ref)) return LeafLanes<kAnyHit>(DF(), bvh, ref, s, m);
  return TraverseLanesAlone<kAnyHit>(bvh, ref, s, m);
}

// Largest closest-hit distance among the lanes of m (the frustum's far end).
HWY_INLINE float MaxBestT(DF d, const PacketState& s, uint32_t m) {
  const size_t lanes = hn::Lanes(d);
  const uint32_t half_mask = (1u << lanes) - 1;
  float t = -kInf;
  for (size_t i = 0; i < 8; i += lanes) {
    const uint32_t half = (m >> i) & half_mask;
    if (half == 0) continue;
    const float b = ReduceLive<true>(d, hn::Load(d, s.best_t + i), MaskFromBits(d, half));
    t = b > t ? b : t;
  }
  return t;
}

// Any hit: the lanes of each leaf child of `node` in `candidates` (cbits[c]) that are not
// `done` yet test it now; the leaf children's cbits are cleared, and the lanes that hit are
// cleared from the inner children's. Returns the lanes that hit.
HWY_INLINE uint32_t PacketLeafChildren(DF d, const Bvh8& bvh, const Bvh8Node& node, PacketState* s,
                                       uint32_t candidates, uint32_t done,
                                       uint32_t single_ray_lanes, const Traverse8Options& options,
                                       uint32_t* cbits) {
  uint32_t hit_lanes = 0;
  for (uint32_t todo = candidates & node.leaf_children; todo != 0; todo &= todo - 1) {
    const int c = std::countr_zero(todo);
    const uint32_t m = cbits[c] & ~(done | hit_lanes);
    cbits[c] = 0;
    if (m == 0) continue;
    hit_lanes |= static_cast<uint32_t>(std::popcount(m)) <= single_ray_lanes
                     ? SingleRayLanes<true>(bvh, node.child[c], s, m)
                     : LeafPacket<true>(d, bvh, node.child[c], s, m, options);
  }
  if (hit_lanes != 0) {
    for (uint32_t todo = candidates; todo != 0; todo &= todo - 1) {
      cbits[std::countr_zero(todo)] &= ~hit_lanes;
    }
  }
  return hit_lanes;
}

// Packet traversal with the hybrid switch to single rays. Closest hit: fills s->best_*;
// any hit: returns the lanes that hit.
// Out of line: its 33 KB stack frame is only set up for packets that traverse as packets.
template <bool kAnyHit>
HWY_NOINLINE uint32_t TraversePacket(const Bvh8& bvh, PacketState* s, uint32_t live,
                                     const Traverse8Options& options) {
  const DF d;
  struct alignas(32) Entry {
    float t_entry[8];
    Bvh8Ref ref;
    uint32_t mask;
  };
  Entry stack[kStackSize];
  int sp = 0;
  uint32_t done = 0;  // any hit: lanes already occluded
  const uint32_t single_ray_lanes =
      s->shared_origin && options.shared_origin_single_ray_lanes >= 0
          ? static_cast<uint32_t>(options.shared_origin_single_ray_lanes)
          : options.single_ray_lanes;
  // The subtree being visited and its lanes. The nearest child hit is visited next without a
  // round trip through the stack: its lanes were just tested against their closest hits.
  Bvh8Ref ref = 0;
  uint32_t m = live;
  for (;;) {
    bool descend = false;
    if (static_cast<uint32_t>(std::popcount(m)) <= single_ray_lanes) {
      // Too few rays left to fill a vector: each finishes this subtree alone.
      done |= SingleRayLanes<kAnyHit>(bvh, ref, s, m);
      if (kAnyHit && done == live) return done;
    } else if (IsLeaf(ref)) {
      done |= LeafPacket<kAnyHit>(d, bvh, ref, s, m, options);
      if (kAnyHit && done == live) return done;
    } else {
      const Bvh8Node& node = bvh.Node(ref);
      uint32_t candidates = (1u << node.num_children) - 1;
      if (s->frustum) {
        candidates = FrustumChildren(d, *s, node, MaxBestT(d, *s, m));
      }
      if (candidates != 0) {
        uint32_t cbits[8];
        alignas(32) float t_near[8][8];
        float key[8];
        PacketChildren<kAnyHit>(d, *s, node, m, candidates, cbits, t_near, key);
        // Packets from one origin (camera rays) test their leaf children at once under any
        // hit, as TraverseSingle does, in trees below options.leaves_first_max_triangles.
        // Other packets were slower that way (veach bounce rays 42 -> 30 M rays/s, table
        // shadow rays -6 %).
        if (kAnyHit && s->shared_origin &&
            bvh.num_triangles < options.leaves_first_max_triangles) {
          done |= PacketLeafChildren(d, bvh, node, s, candidates, done, single_ray_lanes, options,
                                     cbits);
          if (done == live) return done;
        }
        // The children hit by any lane, farthest (by the key) first; any hit keeps the
        // children's order.
        int order[8], n = 0;
        for (uint32_t todo = candidates; todo != 0; todo &= todo - 1) {
          const int c = std::countr_zero(todo);
          if (cbits[c] == 0) continue;
          int k = n++;
          if constexpr (!kAnyHit)
            for (; k > 0 && key[order[k - 1]] < key[c]; --k) order[k] = order[k - 1];
          order[k] = c;
        }
        if (n > 0) {
          PTLAB_DCHECK(sp + n - 1 <= kStackSize);
          for (int k = 0; k < n - 1; ++k) {
            const int c = order[k];
            Entry& out = stack[sp++];
            out.ref = node.child[c];
            out.mask = cbits[c];
            // Large scenes wait on memory: start loading the subtrees visited later.
            PrefetchChild(bvh, out.ref);
            if constexpr (!kAnyHit)
              for (int j = 0; j < 8; ++j) out.t_entry[j] = t_near[c][j];
          }
          ref = node.child[order[n - 1]];
          m = cbits[order[n - 1]];
          descend = true;
        }
      }
    }
    if (descend) continue;
    // Pop the next subtree that still has lanes whose closest hit may lie inside it.
    for (;;) {
      if (sp == 0) return done;
      const Entry& e = stack[--sp];
      m = kAnyHit ? (e.mask & ~done) : LanesBeforeClosest(d, *s, e.t_entry, e.mask);
      if (m != 0) {
        ref = e.ref;
        break;
      }
    }
  }
  return done;
}

// An incoherent packet (lanes in several direction octants) in a large BVH would test every
// child box for lanes that mostly miss it, so each lane traverses alone from the root; a
// coherent one, or any in a small BVH, traverses as a packet (with the hybrid switch below
// single_ray_lanes).
template <bool kAnyHit>
HWY_INLINE uint32_t TraverseLanes(const Bvh8& bvh, PacketState* s, uint32_t live,
                                  const Traverse8Options& options) {
  if (options.octant_fallback && !s->coherent &&
      bvh.num_triangles >= options.octant_fallback_min_triangles) {
    return SingleRayLanes<kAnyHit>(bvh, 0, s, live);
  }
  return TraversePacket<kAnyHit>(bvh, s, live, options);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TRAVERSE8_PACKET_WALK_INL_H_ toggle
