// Per-target kernel of simd/interaction8.h (re-included once per Highway target):
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

#include "engine/bvh/sphere_intersect.h"
#include "engine/core/packet8.h"
#include "engine/render/interaction.h"
#include "engine/scene/scene.h"
#include "hwy/highway.h"
#include "simd/triangle_point8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

inline void MakeInteractionBatchKernel(const Scene& scene, const RayPacket8* rays,
                                       const HitPacket8* hits, const Mask8* hit_mask,
                                       size_t packets, const InteractionColumns& out) {
  const hn::CappedTag<float, 8> d;
  const hn::RebindToSigned<decltype(d)> di;
  const size_t lanes = hn::Lanes(d);
  const TriangleShadingTable& sh = scene.shading;
  const bool vertex_normals = !scene.vertices.n_x.empty();
  const bool with_uv = out.u != nullptr;  // the caller may want no surface coordinates
  const bool vertex_uvs = with_uv && !scene.vertices.u.empty();
  const auto zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const auto zero_i = hn::Zero(di);
  for (size_t k = 0; k < packets; ++k) {
    const HitPacket8& h = hits[k];
    const Mask8 hit = hit_mask[k] & kAllLanes;
    if (hit == 0) continue;
    // Triangle lanes: row of the hit (0 elsewhere, a row every non-empty table has) and a flag.
    // Per-lane flags: vertex normals (ShadingNormalAt's test) and texture coordinates
    // (SurfaceUvAt's: the mesh has uvs).
    alignas(32) int32_t tri[8], on[8], vn[8], vt[8];
    Mask8 tris = 0;
    for (int j = 0; j < 8; ++j) {
      const bool is_tri = LaneActive(hit, j) && !IsSphereHit(h.prim[j]);
      tri[j] = is_tri ? int32_t(h.prim[j]) : 0;
      on[j] = is_tri ? -1 : 0;
      vn[j] = is_tri && vertex_normals && sh.vertex0[h.prim[j]] != kNoVertex ? -1 : 0;
      vt[j] = is_tri && vertex_uvs && scene.meshes.has_uvs[sh.mesh[h.prim[j]]] ? -1 : 0;
      if (is_tri) tris |= LaneBit(j);
    }
    // Sphere lanes: the scalar MakeInteraction (analytic surface, rare in triangle scenes).
    for (Mask8 todo = hit & ~tris; todo != 0; todo &= todo - 1) {
      const int j = std::countr_zero(todo);
      const Hit one_hit{h.t[j], h.b1[j], h.b2[j], h.prim[j]};
      SetInteractionRow(out, k * kPacketWidth + size_t(j),
                        MakeInteraction(scene, GetLaneRay(rays[k], j), one_hit));
    }
    if (tris == 0) continue;
    for (size_t i = 0; i < kPacketWidth; i += lanes) {
      const auto ti = hn::Load(di, tri + i);
      const auto m = hn::RebindMask(d, hn::Ne(hn::Load(di, on + i), zero_i));
      if (hn::AllFalse(d, m)) continue;
      const auto b1 = hn::LoadU(d, h.b1 + i), b2 = hn::LoadU(d, h.b2 + i);
      const auto b0 = hn::Sub(hn::Sub(one, b1), b2);
      // Vertex rows, 0 in lanes with neither normals nor uvs. A lane with only one of them
      // still has a row in every non-empty VertexTable column (AddMesh keeps them aligned).
      const auto vn_i = hn::Ne(hn::Load(di, vn + i), zero_i);
      const auto vt_i = hn::Ne(hn::Load(di, vt + i), zero_i);
      const auto rows_i = hn::Or(vn_i, vt_i);
      const auto as_i = [](const uint32_t* p) { return reinterpret_cast<const int32_t*>(p); };
      auto i0 = zero_i, i1 = zero_i, i2 = zero_i;
      if (!hn::AllFalse(di, rows_i)) {
        i0 = hn::IfThenElseZero(rows_i, hn::GatherIndex(di, as_i(sh.vertex0.data()), ti));
        i1 = hn::IfThenElseZero(rows_i, hn::GatherIndex(di, as_i(sh.vertex1.data()), ti));
        i2 = hn::IfThenElseZero(rows_i, hn::GatherIndex(di, as_i(sh.vertex2.data()), ti));
      }
      auto px = zero, py = zero, pz = zero, gx = zero, gy = zero, gz = zero;
      auto nx = zero, ny = zero, nz = zero;
      auto has_ng = hn::Gt(zero, zero);
      TrianglePoint8(d, scene, ti, b0, b1, b2, hn::RebindMask(d, vn_i), i0, i1, i2, px, py, pz,
                     gx, gy, gz, nx, ny, nz, has_ng);
      // SurfaceUvAt: b0 uv0 + b1 uv1 + b2 uv2 where the mesh has uvs, else (b1, b2).
      auto u = b1, v = b2;
      if (!hn::AllFalse(di, vt_i)) {
        const VertexTable& vx = scene.vertices;
        const auto uv_m = hn::RebindMask(d, vt_i);
        u = hn::IfThenElse(uv_m,
                           Barycentric3(b0, hn::GatherIndex(d, vx.u.data(), i0), b1,
                                        hn::GatherIndex(d, vx.u.data(), i1), b2,
                                        hn::GatherIndex(d, vx.u.data(), i2)),
                           b1);
        v = hn::IfThenElse(uv_m,
                           Barycentric3(b0, hn::GatherIndex(d, vx.v.data(), i0), b1,
                                        hn::GatherIndex(d, vx.v.data(), i1), b2,
                                        hn::GatherIndex(d, vx.v.data(), i2)),
                           b2);
      }
      const size_t row = k * kPacketWidth + i;
      hn::BlendedStore(px, m, d, out.p_x + row);
      hn::BlendedStore(py, m, d, out.p_y + row);
      hn::BlendedStore(pz, m, d, out.p_z + row);
      hn::BlendedStore(gx, m, d, out.ng_x + row);
      hn::BlendedStore(gy, m, d, out.ng_y + row);
      hn::BlendedStore(gz, m, d, out.ng_z + row);
      hn::BlendedStore(nx, m, d, out.n_x + row);
      hn::BlendedStore(ny, m, d, out.n_y + row);
      hn::BlendedStore(nz, m, d, out.n_z + row);
      if (with_uv) {
        hn::BlendedStore(u, m, d, out.u + row);
        hn::BlendedStore(v, m, d, out.v + row);
      }
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_INTERACTION8_INL_H_
