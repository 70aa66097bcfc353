// Primitives beside simd/traverse8's BVH: spheres (vector test) and sdfgrids (the oracle's code).
// Part of simd/traverse8-inl.h: re-included once per target with it (hwy/foreach_target.h).

#if defined(PTLAB_SIMD_TRAVERSE8_BESIDE_BVH_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TRAVERSE8_BESIDE_BVH_INL_H_
#undef PTLAB_SIMD_TRAVERSE8_BESIDE_BVH_INL_H_
#else
#define PTLAB_SIMD_TRAVERSE8_BESIDE_BVH_INL_H_
#endif

#include "hwy/highway.h"
#include "simd/traverse8_packet_setup-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// ---------------------------------------------------------------------------------------------
// Spheres beside the BVH (a scene holds a handful): every sphere against every live lane.

// IntersectSphere1 (engine/bvh/sphere_intersect.h) on one vector of rays, operation for
// operation (contraction off: bit-identical), with c = SphereOriginC given per lane. Returns the
// lanes with a root in (t_min, t_max) and that root in *t.
HWY_INLINE MF IntersectSphereLanes(DF d, VF cx, VF cy, VF cz, VF r, VF c, VF ox, VF oy, VF oz,
                                   VF dx, VF dy, VF dz, VF t_min, VF t_max, VF* t) {
  const VF zero = hn::Zero(d);
  const VF fx = hn::Sub(ox, cx), fy = hn::Sub(oy, cy), fz = hn::Sub(oz, cz);
  const VF a = hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz));
  const VF b = hn::Add(hn::Add(hn::Mul(fx, dx), hn::Mul(fy, dy)), hn::Mul(fz, dz));
  const VF r2 = hn::Mul(r, r);
  const VF s = hn::Div(b, a);
  const VF vx = hn::Sub(fx, hn::Mul(s, dx)), vy = hn::Sub(fy, hn::Mul(s, dy)),
           vz = hn::Sub(fz, hn::Mul(s, dz));
  const VF disc = hn::Sub(r2, hn::Add(hn::Add(hn::Mul(vx, vx), hn::Mul(vy, vy)), hn::Mul(vz, vz)));
  const MF real = hn::Ge(disc, zero);
  // Lanes without real roots take the square root of 0 (no NaN); they are masked out below.
  const VF root = hn::Sqrt(hn::Mul(a, hn::IfThenElseZero(real, disc)));
  const VF q = hn::IfThenElse(hn::Lt(b, zero), hn::Sub(root, b), hn::Neg(hn::Add(b, root)));
  const VF q_a = hn::Div(q, a), c_q = hn::Div(c, q);
  const MF swap = hn::Gt(q_a, c_q);
  const VF t0 = hn::IfThenElse(swap, c_q, q_a), t1 = hn::IfThenElse(swap, q_a, c_q);
  const MF in0 = hn::And(hn::Gt(t0, t_min), hn::Lt(t0, t_max));
  const MF in1 = hn::And(hn::Gt(t1, t_min), hn::Lt(t1, t_max));
  *t = hn::IfThenElse(in0, t0, t1);
  return hn::And(real, hn::Or(in0, in1));
}

// Closest hit: the live lanes' best hits so far (triangles, or t_max) updated with the
// spheres', in row order as IntersectSpheres1 does (b1 = b2 = 0 for a sphere).
// Any hit: returns the lanes of `live` that meet a sphere before their t_max.
template <bool kAnyHit>
HWY_INLINE uint32_t SphereLanes(const Bvh8& bvh, const RayPacket8& rays, PacketState* s,
                                uint32_t live) {
  const DF d;
  const DI di;
  const size_t lanes = hn::Lanes(d);
  const uint32_t half_mask = (1u << lanes) - 1;
  const SphereTable& sp = bvh.spheres;
  uint32_t hit_lanes = 0;
  for (size_t i = 0; i < 8; i += lanes) {
    const uint32_t on_bits = (live >> i) & half_mask;
    if (on_bits == 0) continue;
    const MF on = MaskFromBits(d, on_bits);
    const VF one = hn::Set(d, 1.0f);
    // Dead lanes compute with o = 0, d = (1, 1, 1) (no NaN) and are masked out.
    const VF ox = hn::Load(d, s->o_x + i), oy = hn::Load(d, s->o_y + i),
             oz = hn::Load(d, s->o_z + i);
    const VF dx = hn::IfThenElse(on, hn::Load(d, rays.dir_x + i), one);
    const VF dy = hn::IfThenElse(on, hn::Load(d, rays.dir_y + i), one);
    const VF dz = hn::IfThenElse(on, hn::Load(d, rays.dir_z + i), one);
    const VF t_min = hn::Load(d, s->wt.t_min + i);
    VF best = kAnyHit ? hn::Load(d, s->wt.t_max + i) : hn::Load(d, s->best_t + i);
    VI prim = hn::Load(di, s->best_prim + i);
    MF any = hn::FirstN(d, 0);  // no lane
    for (uint32_t k = 0; k < sp.size(); ++k) {
      // c in double, lane by lane, with the oracle's own function.
      alignas(32) float c[8];
      for (size_t j = 0; j < lanes; ++j)
        c[j] = SphereOriginC(s->o_x[i + j], s->o_y[i + j], s->o_z[i + j], sp.center_x[k],
                             sp.center_y[k], sp.center_z[k], sp.radius[k]);
      VF t;
      const MF hit = hn::And(
          on, IntersectSphereLanes(d, hn::Set(d, sp.center_x[k]), hn::Set(d, sp.center_y[k]),
                                   hn::Set(d, sp.center_z[k]), hn::Set(d, sp.radius[k]),
                                   hn::Load(d, c), ox, oy, oz, dx, dy, dz, t_min, best, &t));
      any = hn::Or(any, hit);
      if (kAnyHit) continue;
      best = hn::IfThenElse(hit, t, best);
      prim = hn::IfThenElse(hn::RebindMask(di, hit),
                            hn::Set(di, static_cast<int32_t>(kSphereHitBit | k)), prim);
    }
    hit_lanes |= MaskBits(d, any) << i;
    if (kAnyHit) continue;
    hn::Store(best, d, s->best_t + i);
    hn::Store(prim, di, s->best_prim + i);
    hn::Store(hn::IfThenElseZero(hn::Not(any), hn::Load(d, s->best_b1 + i)), d, s->best_b1 + i);
    hn::Store(hn::IfThenElseZero(hn::Not(any), hn::Load(d, s->best_b2 + i)), d, s->best_b2 + i);
  }
  return hit_lanes;
}

// Sdfgrids beside the BVH: each live lane's ray through the oracle's own scalar code
// (IntersectSdfGrids1 / OccludedSdfGrids1, engine/bvh/sdf_grid_intersect.h), so the packet's
// hits are the oracle's bit for bit on every target. Closest hit: the lane's best so far
// (triangles, spheres) is the grid's t_max, b1 = b2 = 0 on a grid hit. Any hit: the lanes of
// `live` that meet a grid before their t_max. The cell walk branches per ray; a vector walk is
// not done (docs/sdfgrid.md).
template <bool kAnyHit>
HWY_INLINE uint32_t SdfGridLanes(const Bvh8& bvh, const RayPacket8& rays, PacketState* s,
                                 uint32_t live) {
  uint32_t hit_lanes = 0;
  for (uint32_t todo = live; todo != 0; todo &= todo - 1) {
    const int j = std::countr_zero(todo);
    Ray ray = GetLaneRay(rays, j);
    ray.t_min = s->wt.t_min[j];
    ray.t_max = s->wt.t_max[j];
    if (kAnyHit) {
      if (OccludedSdfGrids1(bvh.sdf_grids, ray)) hit_lanes |= 1u << j;
      continue;
    }
    float t = s->best_t[j];
    uint32_t prim = kNoHit;
    if (IntersectSdfGrids1(bvh.sdf_grids, ray, &t, &prim)) {
      s->best_t[j] = t;
      s->best_prim[j] = static_cast<int32_t>(prim);
      s->best_b1[j] = s->best_b2[j] = 0.0f;
      hit_lanes |= 1u << j;
    }
  }
  return hit_lanes;
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TRAVERSE8_BESIDE_BVH_INL_H_ toggle
