// Highway kernels of simd/traverse8: the entry points; their parts are the traverse8_*-inl.h.
// Re-included once per target by simd/traverse8.cpp (hwy/foreach_target.h); no dispatch here.

#if defined(PTLAB_SIMD_TRAVERSE8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TRAVERSE8_INL_H_
#undef PTLAB_SIMD_TRAVERSE8_INL_H_
#else
#define PTLAB_SIMD_TRAVERSE8_INL_H_
#endif

#include "hwy/highway.h"
#include "simd/packet8.h"
#include "simd/traverse8.h"
#include "simd/traverse8_beside_bvh-inl.h"
#include "simd/traverse8_packet_walk-inl.h"
#include "simd/traverse8_single-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// ---------------------------------------------------------------------------------------------
// Entry points (dispatched from simd/traverse8.cpp).

HWY_INLINE Mask8 Intersect8Kernel(const Bvh8& bvh, const RayPacket8& rays, Mask8 active,
                                  HitPacket8* hits, const Traverse8Options& options) {
  const bool spheres = bvh.spheres.size() != 0;
  const bool grids = bvh.sdf_grids.size() != 0;
  if (bvh.empty() && !spheres && !grids) return 0;
  PacketState s;
  const Mask8 live = SetupPacket(rays, active & kAllLanes, &s);
  if (live == 0) return 0;
  if (!bvh.empty()) TraverseLanes<false>(bvh, &s, live, options);
  if (spheres) SphereLanes<false>(bvh, rays, &s, live);
  if (grids) SdfGridLanes<false>(bvh, rays, &s, live);
  // The live lanes that hit, copied out with masked stores (lanes that miss keep what *hits
  // held): the lane-by-lane copy this replaces cost table's packet render 2 % (1.72 -> 1.68 s).
  const DF d;
  const DI di;
  const size_t lanes = hn::Lanes(d);
  const uint32_t half_mask = (1u << lanes) - 1;
  Mask8 result = 0;
  for (size_t i = 0; i < 8; i += lanes) {
    const VI prim = hn::Load(di, s.best_prim + i);
    const MF hit =
        hn::AndNot(hn::RebindMask(d, hn::Eq(prim, hn::Set(di, static_cast<int32_t>(kNoHit)))),
                   MaskFromBits(d, (live >> i) & half_mask));
    hn::BlendedStore(hn::Load(d, s.best_t + i), hit, d, hits->t + i);
    hn::BlendedStore(hn::Load(d, s.best_b1 + i), hit, d, hits->b1 + i);
    hn::BlendedStore(hn::Load(d, s.best_b2 + i), hit, d, hits->b2 + i);
    hn::BlendedStore(prim, hn::RebindMask(di, hit), di, reinterpret_cast<int32_t*>(hits->prim) + i);
    result |= MaskBits(d, hit) << i;
  }
  return result;
}

HWY_INLINE Mask8 Occluded8Kernel(const Bvh8& bvh, const RayPacket8& rays, Mask8 active,
                                 const Traverse8Options& options) {
  const bool spheres = bvh.spheres.size() != 0;
  const bool grids = bvh.sdf_grids.size() != 0;
  if (bvh.empty() && !spheres && !grids) return 0;
  PacketState s;
  const Mask8 live = SetupPacket(rays, active & kAllLanes, &s);
  if (live == 0) return 0;
  Mask8 done = bvh.empty() ? 0 : TraverseLanes<true>(bvh, &s, live, options);
  if (spheres && done != live) done |= SphereLanes<true>(bvh, rays, &s, live & ~done);
  if (grids && done != live) done |= SdfGridLanes<true>(bvh, rays, &s, live & ~done);
  return done;
}

// The single-ray kernels test the spheres with the oracle's own scalar code (bit-identical by
// construction); only the packet kernels need the vector twin.
HWY_INLINE bool Intersect1Kernel(const Bvh8& bvh, const Ray& ray, Hit* hit) {
  if (!(ray.t_min < ray.t_max)) return false;
  LaneBest best{ray.t_max, kNoHit, 0.0f, 0.0f};
  if (!bvh.empty()) {
    WatertightLanes rv;
    const SingleRay r = MakeSingleRay(ray.o, ray.d, ray.t_min, ray.t_max, &rv);
    TraverseSingle<false>(bvh, 0, r, rv, 0, &best);
  }
  if (IntersectSpheres1(bvh.spheres, ray, &best.t, &best.prim)) best.b1 = best.b2 = 0.0f;
  if (bvh.sdf_grids.size() != 0 && IntersectSdfGrids1(bvh.sdf_grids, ray, &best.t, &best.prim))
    best.b1 = best.b2 = 0.0f;
  if (best.prim == kNoHit) return false;
  hit->t = best.t;
  hit->b1 = best.b1;
  hit->b2 = best.b2;
  hit->prim = best.prim;
  return true;
}

HWY_INLINE bool Occluded1Kernel(const Bvh8& bvh, const Ray& ray) {
  if (!(ray.t_min < ray.t_max)) return false;
  if (!bvh.empty()) {
    LaneBest best{ray.t_max, kNoHit, 0.0f, 0.0f};
    WatertightLanes rv;
    const SingleRay r = MakeSingleRay(ray.o, ray.d, ray.t_min, ray.t_max, &rv);
    if (TraverseSingle<true>(bvh, 0, r, rv, 0, &best)) return true;
  }
  return OccludedSpheres1(bvh.spheres, ray) ||
         (bvh.sdf_grids.size() != 0 && OccludedSdfGrids1(bvh.sdf_grids, ray));
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TRAVERSE8_INL_H_ toggle