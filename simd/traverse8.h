// 8-wide packet and single-ray BVH8 traversal with the watertight triangle test (plain C++ API).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/bvh/bvh.h"
#include "engine/core/ray.h"
#include "simd/bvh8.h"
#include "simd/packet8.h"

namespace ptlab::simd {

// Every function here runs a Highway kernel (hn::CappedTag<float, 8>: one 8-lane vector on
// AVX2/AVX-512, two 4-lane halves on SSE4) chosen at run time among the compiled targets
// (simd/targets.h). Oracle: ptlab::Intersect1 / ptlab::Occluded1 (engine/bvh/intersect1.h) on
// the binary Bvh the Bvh8 was built from, spheres included (tested after the tree, packets
// with an 8-wide twin of IntersectSphere1, engine/bvh/sphere_intersect.h). Contract, per ray:
// the same hit or miss, the same primitive, and t, b1, b2 bit-identical (the kernel performs
// the oracle's float operations in the oracle's order, with FMA contraction disabled, and the
// same double-precision fallback on edges). The oracle's own packet kernels are
// OracleWavefrontKernels' (engine/wavefront/wavefront.h), which `--scalar` / PTLAB_FORCE_SCALAR=1
// render with.

/// Tuning of packet traversal (defaults are the measured best; see benchmarks/).
struct Traverse8Options {
  /// Hybrid traversal: when at most this many lanes of a packet still need a subtree, each of
  /// them traverses it alone (single-ray BVH8 traversal, all eight child boxes in one vector)
  /// instead of the packet testing every child box for 8 lanes. 0 = pure packet traversal.
  /// Measured (closest hit, same run, against 4): shadow rays veach +5 to +9 %, table -1 to
  /// -5 %, bounce rays table -1 to -2 %, the rest and the rendered scenes unchanged.
  uint32_t single_ray_lanes = 6;
  /// In a leaf with fewer triangles than active lanes, test one triangle against all lanes at
  /// a time (each lane's vertices permuted to its own watertight axes, blended per lane when
  /// the lanes' permutations differ); else each active lane tests the whole leaf in one vector.
  bool broadcast_leaves = true;
  /// A packet whose lanes point into different direction octants is incoherent: each lane
  /// traverses alone from the root (else the packet starts and the switch above applies).
  bool octant_fallback = true;
  /// single_ray_lanes for packets whose lanes share one origin (a pinhole camera's): their
  /// rays diverge only by direction, so they stay together deeper down the tree than rays
  /// from spread origins. -1: single_ray_lanes.
  int shared_origin_single_ray_lanes = 2;
  /// The octant fallback applies only to BVH8s over at least this many triangles. Lanes of
  /// an incoherent packet part ways after a few levels; in a small tree they still share most
  /// of their nodes and leaves, in a large one the packet's per-child tests are mostly wasted.
  /// Measured (same run, closest hit, against the fallback everywhere): bounce rays table
  /// (22.7 k triangles) +10 %, veach +34 %, terrain (1.05 M) -9 %; shadow rays +29 %, +5 %,
  /// +3 %. The threshold lies between those sizes and is not tuned further.
  uint32_t octant_fallback_min_triangles = 1u << 17;
  /// Any hit: packets from one origin test a node's leaf children at once, before its inner
  /// children, in BVH8s of fewer than this many triangles. Measured (Occluded8 camera rays,
  /// same run): table 0.73-0.78 -> 1.04-1.12 of Embree, veach 0.94-0.97 -> 1.22-1.25, but the
  /// 1 M-triangle terrain 0.88 -> 0.83-0.85, where a camera packet's leaf children are rarely
  /// all needed; the threshold is the octant fallback's, not tuned further.
  uint32_t leaves_first_max_triangles = 1u << 17;
};

/// Closest hits of the lanes in `active` (bit i = lane i) with t in (t_min, t_max). Returns
/// the lanes that hit; writes hits->{t, b1, b2, prim} of exactly those lanes and leaves every
/// other lane of *hits bit-identical (like the oracle, a miss does not write). Lanes outside
/// `active` are never read for decisions (they may hold NaN). Active lanes need finite o and
/// finite non-zero d; t_min >= t_max is an empty interval (no hit).
Mask8 Intersect8(const Bvh8& bvh, const RayPacket8& rays, Mask8 active, HitPacket8* hits,
                 const Traverse8Options& options = {});

/// Occluded8's tuning (measured, BM_Tune_Occluded8 in benchmarks/traverse_bench.cpp): any hit
/// gains from a packet's shared box tests near the root even when its lanes span several
/// octants, and lanes from spread origins (bounce and shadow rays) go single once six or fewer
/// need a subtree, camera packets (one origin) only at two. Against the closest-hit defaults of
/// 2026-11-26 (octant fallback everywhere, switch at two), same run: bounce rays table +34 %,
/// veach +68 %, terrain ±0; shadow rays +14 %, +11 %, +3 %; camera rays unchanged.
inline constexpr Traverse8Options kOccluded8Options{.single_ray_lanes = 6,
                                                    .broadcast_leaves = true,
                                                    .octant_fallback = false,
                                                    .shared_origin_single_ray_lanes = 2};

/// Lanes of `active` whose ray hits any triangle with t in (t_min, t_max); any-hit traversal
/// that stops a lane at its first hit and returns when every active lane is done. Same
/// per-lane answer as ptlab::Occluded1.
Mask8 Occluded8(const Bvh8& bvh, const RayPacket8& rays, Mask8 active,
                const Traverse8Options& options = kOccluded8Options);

/// Single-ray closest hit on the BVH8 (one ray, eight child boxes or up to eight leaf
/// triangles per vector). Same contract as ptlab::Intersect1, bit-identical.
bool Intersect1(const Bvh8& bvh, const Ray& ray, Hit* hit);

/// Single-ray any hit on the BVH8; same answer as ptlab::Occluded1.
bool Occluded1(const Bvh8& bvh, const Ray& ray);

/// Incoherent rays handled as a stream (Wald et al. 2014 style regrouping, measured in
/// benchmarks/traverse_bench.cpp): rays are sorted by direction octant and then by the Morton
/// code of their origin, cut into packets of eight, and traced with Intersect8. hit_mask[i]
/// is 1 for a hit (hits[i] written) and 0 for a miss (hits[i] untouched). Same per-ray
/// contract as Intersect1. `scratch` must hold n entries.
void IntersectStream(const Bvh8& bvh, const Ray* rays, size_t n, Hit* hits, uint8_t* hit_mask,
                     uint32_t* scratch, const Traverse8Options& options = {});

}  // namespace ptlab::simd
