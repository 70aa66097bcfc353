// Per-target helper (re-included once per Highway target): the radiance of area-light points
// eight lanes at a time, AreaLightRadianceAt's operations in its order (constant radiance, or
// the light's texture through EvalTexture8). Used by area_light8 and emission8.

#if defined(PTLAB_SIMD_AREA_RADIANCE8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_AREA_RADIANCE8_INL_H_
#undef PTLAB_SIMD_AREA_RADIANCE8_INL_H_
#else
#define PTLAB_SIMD_AREA_RADIANCE8_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include "engine/scene/scene.h"
#include "hwy/highway.h"
#include "simd/texture/texture8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

/// AreaLightRadianceAt for the lanes of `active`: light (row in AreaLightTable) at surface
/// coordinates (u, v), position p, triangle prim; other lanes get 0. Lanes whose light has no
/// texture read its constant radiance. Bit-identical to the oracle lane by lane.
HWY_INLINE void AreaLightRadiance8(const Scene& scene, hn::Vec<texture8::DTI> light,
                                   texture8::VT u, texture8::VT v, texture8::VT px,
                                   texture8::VT py, texture8::VT pz, hn::Vec<texture8::DTI> prim,
                                   texture8::MT active, texture8::VT* r, texture8::VT* g,
                                   texture8::VT* b) {
  using namespace texture8;
  const DT d;
  const DTI di;
  const AreaLightTable& lights = scene.area_lights;
  const VTI safe_light = hn::IfThenElseZero(hn::RebindMask(di, active), light);
  const VTI row = hn::Mul(safe_light, hn::Set(di, 3));
  const float* radiance = reinterpret_cast<const float*>(lights.radiance.data());
  VT cr = hn::GatherIndex(d, radiance, row);
  VT cg = hn::GatherIndex(d, radiance, hn::Add(row, hn::Set(di, 1)));
  VT cb = hn::GatherIndex(d, radiance, hn::Add(row, hn::Set(di, 2)));
  if (!lights.texture.empty()) {
    const VTI id = hn::GatherIndex(di, reinterpret_cast<const int32_t*>(lights.texture.data()),
                                   safe_light);
    const MT textured =
        hn::And(active, hn::RebindMask(d, hn::Ne(id, hn::Set(di, int32_t(kNoTexture)))));
    if (!hn::AllFalse(d, textured)) {
      VT tr, tg, tb;
      EvalTexture8(scene.textures, id, u, v, px, py, pz, prim, textured, &tr, &tg, &tb);
      cr = hn::IfThenElse(textured, tr, cr);
      cg = hn::IfThenElse(textured, tg, cg);
      cb = hn::IfThenElse(textured, tb, cb);
    }
  }
  *r = hn::IfThenElseZero(active, cr);
  *g = hn::IfThenElseZero(active, cg);
  *b = hn::IfThenElseZero(active, cb);
}

/// SurfaceUvAt for the lanes of `active` (triangle rows tri, barycentrics b1, b2; b0 = 1 - b1 -
/// b2 as the oracle forms it): the vertex uvs interpolated where the triangle's mesh has uvs,
/// (b1, b2) elsewhere. Bit-identical to the oracle lane by lane.
HWY_INLINE void SurfaceUv8(const Scene& scene, hn::Vec<texture8::DTI> tri, texture8::VT b1,
                           texture8::VT b2, texture8::MT active, texture8::VT* u,
                           texture8::VT* v) {
  using namespace texture8;
  const DT d;
  const DTI di;
  const size_t lanes = hn::Lanes(d);
  *u = b1, *v = b2;
  if (scene.vertices.u.empty()) return;  // no mesh of the scene has uvs
  // has_uvs is a byte per mesh: read lane by lane.
  alignas(32) int32_t tri_lanes[8], with_uv[8] = {};
  hn::Store(tri, di, tri_lanes);
  alignas(32) int32_t on[8];
  hn::Store(hn::VecFromMask(di, hn::RebindMask(di, active)), di, on);
  for (size_t j = 0; j < lanes; ++j)
    if (on[j] != 0)
      with_uv[j] = scene.meshes.has_uvs[scene.shading.mesh[uint32_t(tri_lanes[j])]] ? -1 : 0;
  const auto has_i = hn::Ne(hn::Load(di, with_uv), hn::Zero(di));
  const MT has = hn::RebindMask(d, has_i);
  if (hn::AllFalse(d, has)) return;
  const VTI safe_tri = hn::IfThenElseZero(has_i, tri);
  const auto vertex = [&](const AlignedVector<uint32_t>& column) {
    return hn::IfThenElseZero(
        has_i, hn::GatherIndex(di, reinterpret_cast<const int32_t*>(column.data()), safe_tri));
  };
  const VTI i0 = vertex(scene.shading.vertex0);
  const VTI i1 = vertex(scene.shading.vertex1);
  const VTI i2 = vertex(scene.shading.vertex2);
  const VT b0 = hn::Sub(hn::Sub(hn::Set(d, 1.0f), b1), b2);
  const auto interpolate = [&](const AlignedVector<float>& column) {
    const VT a0 = RMul(d, b0, hn::GatherIndex(d, column.data(), i0));
    const VT a1 = RMul(d, b1, hn::GatherIndex(d, column.data(), i1));
    const VT a2 = RMul(d, b2, hn::GatherIndex(d, column.data(), i2));
    return hn::Add(hn::Add(a0, a1), a2);
  };
  *u = hn::IfThenElse(has, interpolate(scene.vertices.u), b1);
  *v = hn::IfThenElse(has, interpolate(scene.vertices.v), b2);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_AREA_RADIANCE8_INL_H_
