// Per-target kernel of simd/wavefront/interaction8.h (re-included once per Highway target):
// MakeInteraction's operations in its order, eight hits per vector.

#if defined(PTLAB_SIMD_INTERACTION8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_INTERACTION8_INL_H_
#undef PTLAB_SIMD_INTERACTION8_INL_H_
#else
#define PTLAB_SIMD_INTERACTION8_INL_H_
#endif

#include <bit>
#include <cstddef>
#include <cstdint>

#include "engine/bvh/sdf_grid_intersect.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/core/packet8.h"
#include "engine/scene/scene.h"
#include "engine/wavefront/interaction.h"
#include "hwy/highway.h"
#include "simd/shading_point8-inl.h"
#include "simd/transpose4-inl.h"
#include "simd/triangle_point8-inl.h"
#include "simd/triangle_rows.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// SurfaceInteraction as the row kernel stores it: 20 four-byte fields, p, ng, frame (s, t, n),
// uv, prim, material, emitter, in that order.
static_assert(kInteractionFloats == 20 && offsetof(SurfaceInteraction, frame) == 24 &&
              offsetof(SurfaceInteraction, uv) == 60 && offsetof(SurfaceInteraction, prim) == 68 &&
              offsetof(SurfaceInteraction, material) == 72 &&
              offsetof(SurfaceInteraction, emitter) == 76);

// Four fields of the lanes i.. of a packet (vectors f0..f3) into their rows: lane j's
// (f0, f1, f2, f3) as 16 bytes at lane0 + j * stride floats. A 4x4 transpose per 128-bit block,
// so on 8-lane targets one vector holds the quads of lanes j and j + 4.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void StoreQuadRows(D d, V f0, V f1, V f2, V f3, float* lane0, size_t stride) {
#if HWY_TARGET == HWY_SCALAR
  lane0[0] = hn::GetLane(f0), lane0[1] = hn::GetLane(f1);
  lane0[2] = hn::GetLane(f2), lane0[3] = hn::GetLane(f3);
  (void)d, (void)stride;
#else
  V r0, r1, r2, r3;
  TransposeQuads(d, f0, f1, f2, f3, &r0, &r1, &r2, &r3);
  if constexpr (hn::MaxLanes(d) == 4) {
    hn::StoreU(r0, d, lane0), hn::StoreU(r1, d, lane0 + stride);
    hn::StoreU(r2, d, lane0 + 2 * stride), hn::StoreU(r3, d, lane0 + 3 * stride);
  } else {
    static_assert(hn::MaxLanes(d) == 8);
    const hn::Half<D> dh;
    hn::StoreU(hn::LowerHalf(dh, r0), dh, lane0);
    hn::StoreU(hn::LowerHalf(dh, r1), dh, lane0 + stride);
    hn::StoreU(hn::LowerHalf(dh, r2), dh, lane0 + 2 * stride);
    hn::StoreU(hn::LowerHalf(dh, r3), dh, lane0 + 3 * stride);
    hn::StoreU(hn::UpperHalf(dh, r0), dh, lane0 + 4 * stride);
    hn::StoreU(hn::UpperHalf(dh, r1), dh, lane0 + 5 * stride);
    hn::StoreU(hn::UpperHalf(dh, r2), dh, lane0 + 6 * stride);
    hn::StoreU(hn::UpperHalf(dh, r3), dh, lane0 + 7 * stride);
  }
#endif
}

// The hit lists of lanes i.. of a packet (HitLists): the queue entries of the hit lanes and of
// those on an area light compressed into the lists, in lane order, and the hit lanes counted
// by the group of their material (MaterialGroup: the tag, at most kMaterialTagCount).
template <class DI, class M = hn::Mask<DI>, class VI = hn::Vec<DI>>
HWY_INLINE void ListHits(DI di, M hit, M tri, VI material, VI emitter, size_t first_entry,
                         HitLists* lists) {
  const auto entries = hn::Iota(di, int32_t(first_entry));
  lists->hits += uint32_t(hn::CompressStore(
      entries, hit, di, reinterpret_cast<int32_t*>(lists->entries) + lists->hits));
  // EmitterTag::kArea is tag 0 (a sphere's EmitterRef::None, tag 15, is not), in the top 4 bits.
  static_assert(uint32_t(EmitterTag::kArea) == 0 &&
                EmitterRef::Make(EmitterTag::kSpot, 0).bits >> 28 == uint32_t(EmitterTag::kSpot) &&
                MaterialRef::Make(MaterialTag(1), 0).bits >> 28 == 1);
  const auto tag_bits = hn::Set(di, int32_t(0xf0000000u));
  const M area = hn::And(tri, hn::Eq(hn::And(emitter, tag_bits), hn::Zero(di)));
  if (!hn::AllFalse(di, area)) {
    lists->area_hits += uint32_t(hn::CompressStore(
        entries, area, di, reinterpret_cast<int32_t*>(lists->area_entries) + lists->area_hits));
  }
  const hn::RebindToUnsigned<DI> du;
  const auto group = hn::BitCast(
      di, hn::Min(hn::ShiftRight<28>(hn::BitCast(du, material)), hn::Set(du, kMaterialTagCount)));
  for (int g = 0; g < kMaterialGroups; ++g)
    lists->group_hits[g] +=
        uint32_t(hn::CountTrue(di, hn::And(hit, hn::Eq(group, hn::Set(di, g)))));
}

// ptlab::MakeInteractionBatch into rows, eight lanes at a time: every lane as a triangle hit
// (row 0 and barycentrics 0 in the lanes of no triangle hit, so that they stay finite): the
// lanes' TriangleRows loaded and transposed, TrianglePointOf, ShadingNormalOf, Frame(n), wo =
// Frame::ToLocal(-d * (1 / |d|)) and the material and emitter refs, stored into all the rows of the
// vector through 4x4 transposes; then the sphere lanes' rows again with the scalar code. The hit
// lists from the lanes' refs (sphere lanes' material gathered too) as each vector's rows are made.
inline void MakeInteractionRowsKernel(const Scene& scene, const TriangleRows& tri_rows,
                                      const RayPacket8* rays, const HitPacket8* hits,
                                      const Mask8* hit_mask, size_t packets,
                                      const InteractionRows& out, HitLists* lists) {
  const hn::CappedTag<float, 8> d;
  const hn::RebindToSigned<decltype(d)> di;
  const size_t lanes = hn::Lanes(d);
  const auto zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const auto zero_i = hn::Zero(di), sphere_bit = hn::Set(di, int32_t(kSphereHitBit));
  const auto as_i = [](const auto* p) { return reinterpret_cast<const int32_t*>(p); };
  const auto no_emitter = hn::Set(di, int32_t(EmitterRef::None().bits));
  alignas(32) static constexpr int32_t kLaneBits[8] = {1, 2, 4, 8, 16, 32, 64, 128};
  lists->hits = lists->area_hits = 0;
  for (uint32_t& count : lists->group_hits) count = 0;
  const bool with_uv = !scene.textures.empty();
  const bool instanced = !scene.instances.empty();
  for (size_t k = 0; k < packets; ++k) {
    const Mask8 hit = hit_mask[k] & kAllLanes;
    if (hit == 0) continue;
    const RayPacket8& r = rays[k];
    const HitPacket8& h = hits[k];
    float* const rows = reinterpret_cast<float*>(out.its + k * kPacketWidth);
    Mask8 spheres = 0;
    for (size_t i = 0; i < kPacketWidth; i += lanes) {
      const auto hit_i = hn::TestBit(hn::Set(di, int32_t(hit)), hn::Load(di, kLaneBits + i));
      const auto prim = hn::Load(di, as_i(h.prim) + i);
      auto sphere_i = hn::And(hit_i, hn::Ne(hn::And(prim, sphere_bit), zero_i));
      // Instanced triangles (ids from the scene's row count on; sphere ids are negative as
      // int32) go the spheres' scalar way, their material looked up lane by lane.
      auto instanced_i = hn::Lt(zero_i, zero_i);  // no lane
      if (instanced) {
        instanced_i = hn::AndNot(hn::Lt(prim, hn::Set(di, int32_t(scene.triangles.size()))), hit_i);
        if (!hn::AllFalse(di, instanced_i)) {
          uint8_t bits[8] = {};
          hn::StoreMaskBits(di, instanced_i, bits);
          spheres |= Mask8(bits[0]) << i;
        }
      }
      const auto tri_i = hn::AndNot(hn::Or(sphere_i, instanced_i), hit_i);
      const auto tri = hn::RebindMask(d, tri_i);
      const auto ti = hn::IfThenElseZero(tri_i, prim);
      const bool any_tri = !hn::AllFalse(di, tri_i);
      auto material = zero_i, emitter = no_emitter;
      // The hit triangles' rows (TriangleRows): v0, v1, v2, material, emitter, vertex rows.
      hn::Vec<decltype(d)> row[kTriangleRowFloats];
      if (any_tri) {
        LoadRowColumns<kTriangleRowFloats / 4>(d, tri_rows.triangles.data(), kTriangleRowFloats, ti,
                                               row);
        material = hn::BitCast(di, row[kRowMaterial]);
        emitter = hn::BitCast(di, row[kRowEmitter]);
      }
      if (!hn::AllFalse(di, sphere_i)) {
        uint8_t bits[8] = {};
        hn::StoreMaskBits(di, sphere_i, bits);
        spheres |= Mask8(bits[0]) << i;
        // Sdfgrid lanes (bit 30 too) take their material lane by lane; the spheres' gather.
        const auto grid_bit = hn::Set(di, int32_t(kSdfGridHitBit));
        const auto grid_i = hn::And(sphere_i, hn::Ne(hn::And(prim, grid_bit), zero_i));
        const auto ball_i = hn::AndNot(grid_i, sphere_i);
        const auto si = hn::IfThenElseZero(ball_i, hn::AndNot(sphere_bit, prim));
        material = hn::IfThenElse(
            ball_i, hn::GatherIndex(di, as_i(scene.spheres.material.data()), si), material);
        if (!hn::AllFalse(di, grid_i)) {
          alignas(32) int32_t prims[8], materials[8];
          hn::Store(prim, di, prims);
          hn::Store(material, di, materials);
          uint8_t grid_bits[8] = {};
          hn::StoreMaskBits(di, grid_i, grid_bits);
          for (Mask8 todo = grid_bits[0]; todo != 0; todo &= todo - 1) {
            const int j = std::countr_zero(todo);
            materials[j] =
                int32_t(scene.sdf_grids.material[SdfGridHitRow(uint32_t(prims[j]))].bits);
          }
          material = hn::Load(di, materials);
        }
      }
      if (!hn::AllFalse(di, instanced_i)) {
        alignas(32) int32_t prims[8], materials[8];
        hn::Store(prim, di, prims);
        hn::Store(material, di, materials);
        uint8_t bits[8] = {};
        hn::StoreMaskBits(di, instanced_i, bits);
        for (Mask8 todo = bits[0]; todo != 0; todo &= todo - 1) {
          const int j = std::countr_zero(todo);
          const InstancedRow at =
              FindInstancedRow(scene.instances, scene.triangles.size(), uint32_t(prims[j]));
          materials[j] = int32_t(scene.shading.material[at.row].bits);
        }
        material = hn::Load(di, materials);
      }
      ListHits(di, hit_i, tri_i, material, emitter, k * kPacketWidth + i, lists);
      if (!any_tri) continue;
      const auto b1 = hn::IfThenElseZero(tri, hn::Load(d, h.b1 + i));
      const auto b2 = hn::IfThenElseZero(tri, hn::Load(d, h.b2 + i));
      const auto b0 = hn::Sub(hn::Sub(one, b1), b2);
      auto px = zero, py = zero, pz = zero, gx = zero, gy = zero, gz = zero;
      auto nx = zero, ny = zero, nz = zero;
      auto has_ng = hn::Gt(zero, zero);
      PointOfRows(d, tri_rows, row, tri, b0, b1, b2, px, py, pz, gx, gy, gz, nx, ny, nz, has_ng);
      hn::Vec<decltype(d)> sx, sy, sz, b, ty, tz;
      FrameOfNormal(d, nx, ny, nz, sx, sy, sz, b, ty, tz);
      // wo = ToLocal(-d * (1 / |d|)); d = +z in the lanes of no triangle hit (the padding lanes
      // of a queue's last packet have d = 0).
      const auto dx = hn::IfThenElseZero(tri, hn::Load(d, r.dir_x + i));
      const auto dy = hn::IfThenElseZero(tri, hn::Load(d, r.dir_y + i));
      const auto dz = hn::IfThenElse(tri, hn::Load(d, r.dir_z + i), one);
      const auto inv = hn::Div(
          one, hn::Sqrt(hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz))));
      const auto wx = hn::Mul(hn::Neg(dx), inv), wy = hn::Mul(hn::Neg(dy), inv);
      const auto wz = hn::Mul(hn::Neg(dz), inv);
      const auto wo_x = hn::Add(hn::Add(hn::Mul(wx, sx), hn::Mul(wy, sy)), hn::Mul(wz, sz));
      const auto wo_y = hn::Add(hn::Add(hn::Mul(wx, b), hn::Mul(wy, ty)), hn::Mul(wz, tz));
      const auto wo_z = hn::Add(hn::Add(hn::Mul(wx, nx), hn::Mul(wy, ny)), hn::Mul(wz, nz));
      // Surface coordinates (SurfaceUvAt), only in a scene with textures: the mesh's uv
      // interpolated, b0 u0 + b1 u1 + b2 u2 in that order, where its mesh has uvs, else (b1, b2).
      auto u = zero, v = zero;
      if (with_uv) {
        u = b1, v = b2;
        if (!scene.vertices.u.empty()) {
          HWY_ALIGN int32_t tris[8], mesh_uvs[8];
          hn::Store(ti, di, tris);
          for (size_t j = 0; j < lanes; ++j)
            mesh_uvs[j] = scene.meshes.has_uvs[scene.shading.mesh[uint32_t(tris[j])]];
          const auto has_i =
              hn::And(tri_i, hn::Ne(hn::Load(di, mesh_uvs), zero_i));
          if (!hn::AllFalse(di, has_i)) {
            const auto corner = [&](size_t c) {
              return hn::IfThenElseZero(has_i, hn::BitCast(di, row[kRowVertex0 + c]));
            };
            const auto i0 = corner(0), i1 = corner(1), i2 = corner(2);
            const float* cu = scene.vertices.u.data();
            const float* cv = scene.vertices.v.data();
            const auto su = hn::Add(hn::Add(hn::Mul(b0, hn::GatherIndex(d, cu, i0)),
                                            hn::Mul(b1, hn::GatherIndex(d, cu, i1))),
                                    hn::Mul(b2, hn::GatherIndex(d, cu, i2)));
            const auto sv = hn::Add(hn::Add(hn::Mul(b0, hn::GatherIndex(d, cv, i0)),
                                            hn::Mul(b1, hn::GatherIndex(d, cv, i1))),
                                    hn::Mul(b2, hn::GatherIndex(d, cv, i2)));
            const auto has = hn::RebindMask(d, has_i);
            u = hn::IfThenElse(has, su, u), v = hn::IfThenElse(has, sv, v);
          }
        }
      }
      float* const lane0 = rows + i * size_t(kInteractionFloats);
      StoreQuadRows(d, px, py, pz, gx, lane0, size_t(kInteractionFloats));
      StoreQuadRows(d, gy, gz, sx, sy, lane0 + 4, size_t(kInteractionFloats));
      StoreQuadRows(d, sz, b, ty, tz, lane0 + 8, size_t(kInteractionFloats));
      StoreQuadRows(d, nx, ny, nz, u, lane0 + 12, size_t(kInteractionFloats));
      StoreQuadRows(d, v, hn::BitCast(d, prim), hn::BitCast(d, material),
                    hn::BitCast(d, emitter), lane0 + 16, size_t(kInteractionFloats));
      // The Vec3f rows of wo: x, y, z interleaved (a lane-by-lane copy measured 7 % of this
      // kernel).
      hn::StoreInterleaved3(wo_x, wo_y, wo_z, d,
                            reinterpret_cast<float*>(out.wo + k * kPacketWidth + i));
    }
    // Sphere and instanced lanes: the scalar code (an analytic surface, rare in triangle
    // scenes; an instance's transform).
    for (Mask8 todo = spheres; todo != 0; todo &= todo - 1) {
      const int j = std::countr_zero(todo);
      const size_t q = k * kPacketWidth + size_t(j);
      const Ray ray = GetLaneRay(r, j);
      SurfaceInteraction& its = out.its[q];
      its = MakeInteraction(scene, ray, {h.t[j], h.b1[j], h.b2[j], h.prim[j]});
      if (!with_uv) its.uv = {};  // the rows carry no surface coordinates
      out.wo[q] = LocalDirectionBack(its.frame, ray.d);
    }

  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_INTERACTION8_INL_H_
