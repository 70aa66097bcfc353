// Per-target helper (re-included once per Highway target): a point on a triangle from its
// barycentrics with the triangle's geometric and shading normals, as MakeInteraction and
// SampleAreaLight compute them, eight triangles per vector. Shared by simd/interaction8 and
// simd/emitter8.

#if defined(PTLAB_SIMD_TRIANGLE_POINT8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TRIANGLE_POINT8_INL_H_
#undef PTLAB_SIMD_TRIANGLE_POINT8_INL_H_
#else
#define PTLAB_SIMD_TRIANGLE_POINT8_INL_H_
#endif

#include "engine/scene/scene.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

/// b0 a + b1 b + b2 c in the scalar code's order ((b0 a + b1 b) + b2 c).
template <class V>
HWY_INLINE V Barycentric3(V b0, V a, V b1, V b, V b2, V c) {
  return hn::Add(hn::Add(hn::Mul(a, b0), hn::Mul(b, b1)), hn::Mul(c, b2));
}

/// For triangle rows `tri` at barycentrics (b0, b1, b2), b0 = 1 - b1 - b2: p = V0 b0 + V1 b1 +
/// V2 b2; g = Cross(V1 - V0, V2 - V0) normalized, +z where it has no length (has_ng false);
/// n = ShadingNormalAt: the interpolated vertex normal (rows i0, i1, i2 of VertexTable, read
/// only in `vertex_normal` lanes) where it has a length, else g. The scalar code's float
/// operations in its order, so bit-identical to it without FMA contraction.
template <class D, class VI, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE void TrianglePoint8(D d, const Scene& scene, VI tri, V b0, V b1, V b2,
                               M vertex_normal, VI i0, VI i1, VI i2, V& px, V& py, V& pz, V& gx,
                               V& gy, V& gz, V& nx, V& ny, V& nz, M& has_ng) {
  const TriangleTable& t = scene.triangles;
  const VertexTable& vt = scene.vertices;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V v0x = hn::GatherIndex(d, t.v0_x.data(), tri);
  const V v0y = hn::GatherIndex(d, t.v0_y.data(), tri);
  const V v0z = hn::GatherIndex(d, t.v0_z.data(), tri);
  const V v1x = hn::GatherIndex(d, t.v1_x.data(), tri);
  const V v1y = hn::GatherIndex(d, t.v1_y.data(), tri);
  const V v1z = hn::GatherIndex(d, t.v1_z.data(), tri);
  const V v2x = hn::GatherIndex(d, t.v2_x.data(), tri);
  const V v2y = hn::GatherIndex(d, t.v2_y.data(), tri);
  const V v2z = hn::GatherIndex(d, t.v2_z.data(), tri);
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
  nx = gx, ny = gy, nz = gz;
  if (hn::AllFalse(d, vertex_normal)) return;
  const V sx = Barycentric3(b0, hn::GatherIndex(d, vt.n_x.data(), i0), b1,
                            hn::GatherIndex(d, vt.n_x.data(), i1), b2,
                            hn::GatherIndex(d, vt.n_x.data(), i2));
  const V sy = Barycentric3(b0, hn::GatherIndex(d, vt.n_y.data(), i0), b1,
                            hn::GatherIndex(d, vt.n_y.data(), i1), b2,
                            hn::GatherIndex(d, vt.n_y.data(), i2));
  const V sz = Barycentric3(b0, hn::GatherIndex(d, vt.n_z.data(), i0), b1,
                            hn::GatherIndex(d, vt.n_z.data(), i1), b2,
                            hn::GatherIndex(d, vt.n_z.data(), i2));
  const V slen = hn::Sqrt(hn::Add(hn::Add(hn::Mul(sx, sx), hn::Mul(sy, sy)), hn::Mul(sz, sz)));
  const V sinv = hn::Div(one, slen);
  const M use = hn::And(vertex_normal, hn::Gt(slen, zero));
  nx = hn::IfThenElse(use, hn::Mul(sx, sinv), gx);
  ny = hn::IfThenElse(use, hn::Mul(sy, sinv), gy);
  nz = hn::IfThenElse(use, hn::Mul(sz, sinv), gz);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TRIANGLE_POINT8_INL_H_
