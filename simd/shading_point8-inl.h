// Per-target helper (re-included once per Highway target): the shading point's frame, the ray
// origin offset and reads of the wavefront's SurfaceInteraction rows, eight rows per vector, in
// the scalar code's float operations and order (bit-identical to it without FMA contraction).
// Shared by simd/wavefront/interaction8, simd/wavefront/area_request8 and simd/wavefront/spawn8.

#if defined(PTLAB_SIMD_SHADING_POINT8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_SHADING_POINT8_INL_H_
#undef PTLAB_SIMD_SHADING_POINT8_INL_H_
#else
#define PTLAB_SIMD_SHADING_POINT8_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include "engine/render/interaction.h"
#include "hwy/highway.h"
#include "simd/transpose4-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

/// Frame(n) (engine/core/frame.h, Duff et al. 2017): s = (sx, sy, sz), t = (b, ty, tz).
template <class D, class V = hn::Vec<D>>
HWY_INLINE void FrameOfNormal(D d, V nx, V ny, V nz, V& sx, V& sy, V& sz, V& b, V& ty, V& tz) {
  const V one = hn::Set(d, 1.0f);
  const V sign = hn::CopySign(one, nz);
  const V a = hn::Div(hn::Set(d, -1.0f), hn::Add(sign, nz));
  b = hn::Mul(hn::Mul(nx, ny), a);
  sx = hn::Add(one, hn::Mul(hn::Mul(hn::Mul(sign, nx), nx), a));
  sy = hn::Mul(sign, b);
  sz = hn::Mul(hn::Neg(sign), nx);
  ty = hn::Add(sign, hn::Mul(hn::Mul(ny, ny), a));
  tz = hn::Neg(ny);
}

/// OffsetRayOrigin (engine/bvh/ray_offset.h) for one coordinate: the bit pattern of p stepped
/// by 256 ng units in the last place (the step negated where p < 0, so that it moves along +ng),
/// or p + ng / 65536 within 1/32 of zero.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V OffsetCoordinate(D d, V p, V ng) {
  const hn::RebindToSigned<D> di;
  const auto of = hn::ConvertTo(di, hn::Mul(hn::Set(d, 256.0f), ng));
  const auto step = hn::IfThenElse(hn::RebindMask(di, hn::Lt(p, hn::Zero(d))), hn::Neg(of), of);
  const V stepped = hn::BitCast(d, hn::Add(hn::BitCast(di, p), step));
  const V near_zero = hn::Add(p, hn::Mul(hn::Set(d, 1.0f / 65536.0f), ng));
  return hn::IfThenElse(hn::Lt(hn::Abs(p), hn::Set(d, 1.0f / 32.0f)), near_zero, stepped);
}

/// A SurfaceInteraction row read as floats: its size and the float offsets of its fields.
inline constexpr int32_t kInteractionFloats = int32_t(sizeof(SurfaceInteraction) / sizeof(float));
static_assert(sizeof(SurfaceInteraction) % sizeof(float) == 0);
static_assert(sizeof(Vec3f) == 3 * sizeof(float) && sizeof(Frame) == 9 * sizeof(float));
static_assert(sizeof(MaterialRef) == sizeof(uint32_t));
inline constexpr int32_t kInteractionP = int32_t(offsetof(SurfaceInteraction, p) / sizeof(float));
inline constexpr int32_t kInteractionNg =
    int32_t(offsetof(SurfaceInteraction, ng) / sizeof(float));
inline constexpr int32_t kInteractionN =
    int32_t((offsetof(SurfaceInteraction, frame) + offsetof(Frame, n)) / sizeof(float));
inline constexpr int32_t kInteractionMaterial =
    int32_t(offsetof(SurfaceInteraction, material) / sizeof(float));

/// Field `offset` (a kInteraction* constant, plus 0..2 for a vector's component) of the rows
/// whose float index `first` is (entry · kInteractionFloats): one gather.
template <class D, class VI>
HWY_INLINE hn::Vec<D> InteractionField(D d, const SurfaceInteraction* rows, VI first,
                                       int32_t offset) {
  const hn::RebindToSigned<D> di;
  return hn::GatherIndex(d, reinterpret_cast<const float*>(rows),
                         hn::Add(first, hn::Set(di, offset)));
}

/// The shading points p, ng and n (xyz each) of the rows `entry`: the rows' quads at floats 0,
/// 4 and 12 loaded and transposed (LoadRowQuads), where nine InteractionField gathers would
/// read them lane by lane.
template <class D, class VI, class V = hn::Vec<D>>
HWY_INLINE void InteractionPoints(D d, const SurfaceInteraction* rows, VI entry, V* p, V* ng,
                                  V* n) {
  static_assert(kInteractionP == 0 && kInteractionNg == 3 && kInteractionN == 12);
  V q[12];
  LoadRowQuads(d, reinterpret_cast<const float*>(rows), size_t(kInteractionFloats), entry,
               {0, 4, 12}, q);
  p[0] = q[0], p[1] = q[1], p[2] = q[2];
  ng[0] = q[3], ng[1] = q[4], ng[2] = q[5];
  n[0] = q[8], n[1] = q[9], n[2] = q[10];
}

/// The float index of each row's first field: entry · kInteractionFloats.
template <class VI>
HWY_INLINE VI InteractionFirst(VI entry) {
  return hn::Mul(entry, hn::Set(hn::DFromV<VI>(), kInteractionFloats));
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_SHADING_POINT8_INL_H_
