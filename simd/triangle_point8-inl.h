// Per-target helper (re-included once per Highway target): a point on a triangle from its
// barycentrics with the triangle's geometric and shading normals, as MakeInteraction and
// SampleAreaLight compute them, eight triangles per vector, from vertices and vertex normals
// already loaded (simd/wavefront/interaction8 and simd/wavefront/area_light8 load them from TriangleRows).

#if defined(PTLAB_SIMD_TRIANGLE_POINT8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TRIANGLE_POINT8_INL_H_
#undef PTLAB_SIMD_TRIANGLE_POINT8_INL_H_
#else
#define PTLAB_SIMD_TRIANGLE_POINT8_INL_H_
#endif

#include "hwy/highway.h"
#include "simd/transpose4-inl.h"
#include "simd/triangle_rows.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

/// b0 a + b1 b + b2 c in the scalar code's order ((b0 a + b1 b) + b2 c).
template <class V>
HWY_INLINE V Barycentric3(V b0, V a, V b1, V b, V b2, V c) {
  return hn::Add(hn::Add(hn::Mul(a, b0), hn::Mul(b, b1)), hn::Mul(c, b2));
}

/// The point at barycentrics (b0, b1, b2), b0 = 1 - b1 - b2, of the triangles with vertices
/// (v0, v1, v2) in lanes: p = V0 b0 + V1 b1 + V2 b2 and g = Cross(V1 - V0, V2 - V0)
/// normalized, +z where it has no length (has_ng false). The scalar code's float operations
/// in its order, so bit-identical to it without FMA contraction.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE void TrianglePointOf(D d, V v0x, V v0y, V v0z, V v1x, V v1y, V v1z, V v2x, V v2y, V v2z,
                                V b0, V b1, V b2, V& px, V& py, V& pz, V& gx, V& gy, V& gz,
                                M& has_ng) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  px = Barycentric3(b0, v0x, b1, v1x, b2, v2x);
  py = Barycentric3(b0, v0y, b1, v1y, b2, v2y);
  pz = Barycentric3(b0, v0z, b1, v1z, b2, v2z);
  const V e1x = hn::Sub(v1x, v0x), e1y = hn::Sub(v1y, v0y), e1z = hn::Sub(v1z, v0z);
  const V e2x = hn::Sub(v2x, v0x), e2y = hn::Sub(v2y, v0y), e2z = hn::Sub(v2z, v0z);
  const V cx = hn::Sub(hn::Mul(e1y, e2z), hn::Mul(e1z, e2y));
  const V cy = hn::Sub(hn::Mul(e1z, e2x), hn::Mul(e1x, e2z));
  const V cz = hn::Sub(hn::Mul(e1x, e2y), hn::Mul(e1y, e2x));
  const V glen = hn::Sqrt(hn::Add(hn::Add(hn::Mul(cx, cx), hn::Mul(cy, cy)), hn::Mul(cz, cz)));
  const V ginv = hn::Div(one, glen);
  has_ng = hn::Gt(glen, zero);
  gx = hn::IfThenElseZero(has_ng, hn::Mul(cx, ginv));
  gy = hn::IfThenElseZero(has_ng, hn::Mul(cy, ginv));
  gz = hn::IfThenElse(has_ng, hn::Mul(cz, ginv), one);
}

/// ShadingNormalAt from the three vertex normals (n0, n1, n2) of the lanes: their
/// interpolation normalized where `vertex_normal` is set and it has a length, else the
/// geometric normal g. The scalar code's operations in its order.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE void ShadingNormalOf(D d, M vertex_normal, V b0, V b1, V b2, const V* n0, const V* n1,
                                const V* n2, V gx, V gy, V gz, V& nx, V& ny, V& nz) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V sx = Barycentric3(b0, n0[0], b1, n1[0], b2, n2[0]);
  const V sy = Barycentric3(b0, n0[1], b1, n1[1], b2, n2[1]);
  const V sz = Barycentric3(b0, n0[2], b1, n1[2], b2, n2[2]);
  const V slen = hn::Sqrt(hn::Add(hn::Add(hn::Mul(sx, sx), hn::Mul(sy, sy)), hn::Mul(sz, sz)));
  const V sinv = hn::Div(one, slen);
  const M use = hn::And(vertex_normal, hn::Gt(slen, zero));
  nx = hn::IfThenElse(use, hn::Mul(sx, sinv), gx);
  ny = hn::IfThenElse(use, hn::Mul(sy, sinv), gy);
  nz = hn::IfThenElse(use, hn::Mul(sz, sinv), gz);
}

/// The point, geometric normal and shading normal (TrianglePointOf, ShadingNormalOf) of the
/// triangles whose TriangleRows columns are row[0, kTriangleRowFloats) (LoadRowColumns): the
/// vertex normal rows of tri_rows are read in the lanes of `on` whose triangle has vertex rows.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE void PointOfRows(D d, const TriangleRows& tri_rows, const V* row, M on, V b0, V b1, V b2,
                            V& px, V& py, V& pz, V& gx, V& gy, V& gz, V& nx, V& ny, V& nz,
                            M& has_ng) {
  const V* v = row + kRowV0;
  TrianglePointOf(d, v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], b0, b1, b2, px, py, pz,
                  gx, gy, gz, has_ng);
  nx = gx, ny = gy, nz = gz;
  if (tri_rows.normals.empty()) return;
  const hn::RebindToSigned<D> di;
  const auto i0 = hn::BitCast(di, row[kRowVertex0]);
  const auto vn = hn::And(hn::RebindMask(di, on), hn::Ne(i0, hn::Set(di, int32_t(kNoVertex))));
  if (hn::AllFalse(di, vn)) return;
  V n0[4], n1[4], n2[4];
  const float* normals = tri_rows.normals.data();
  LoadRowColumns<1>(d, normals, 4, hn::IfThenElseZero(vn, i0), n0);
  LoadRowColumns<1>(d, normals, 4, hn::IfThenElseZero(vn, hn::BitCast(di, row[kRowVertex0 + 1])),
                    n1);
  LoadRowColumns<1>(d, normals, 4, hn::IfThenElseZero(vn, hn::BitCast(di, row[kRowVertex0 + 2])),
                    n2);
  ShadingNormalOf(d, hn::RebindMask(d, vn), b0, b1, b2, n0, n1, n2, gx, gy, gz, nx, ny, nz);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TRIANGLE_POINT8_INL_H_
