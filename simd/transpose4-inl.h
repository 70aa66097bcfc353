// Per-target helper (re-included once per Highway target): four vectors of floats as quads of
// rows, the 4x4 transpose within each 128-bit block (simd/wavefront/interaction8, simd/wavefront/continuation8), and
// its way back: columns loaded from rows (TriangleRows in simd/wavefront/interaction8 and simd/wavefront/area_light8,
// interaction rows in simd/wavefront/spawn8, simd/wavefront/area_request8 and simd/wavefront/vertices8).

#if defined(PTLAB_SIMD_TRANSPOSE4_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TRANSPOSE4_INL_H_
#undef PTLAB_SIMD_TRANSPOSE4_INL_H_
#else
#define PTLAB_SIMD_TRANSPOSE4_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// Lane j of (f0, f1, f2, f3) as a quad: lanes j, j + 1, j + 2, j + 3 of a 128-bit block give
// that block of r0, r1, r2, r3, so on 8-lane vectors r0 holds the quads of lanes 0 and 4, r1
// those of 1 and 5, and so on. Not on HWY_SCALAR (one lane, no blocks).
#if HWY_TARGET != HWY_SCALAR
template <class D, class V = hn::Vec<D>>
HWY_INLINE void TransposeQuads(D d, V f0, V f1, V f2, V f3, V* r0, V* r1, V* r2, V* r3) {
  const hn::Repartition<double, D> dd;
  const auto lo01 = hn::BitCast(dd, hn::InterleaveLower(d, f0, f1));
  const auto lo23 = hn::BitCast(dd, hn::InterleaveLower(d, f2, f3));
  const auto hi01 = hn::BitCast(dd, hn::InterleaveUpper(d, f0, f1));
  const auto hi23 = hn::BitCast(dd, hn::InterleaveUpper(d, f2, f3));
  *r0 = hn::BitCast(d, hn::InterleaveLower(dd, lo01, lo23));
  *r1 = hn::BitCast(d, hn::InterleaveUpper(dd, lo01, lo23));
  *r2 = hn::BitCast(d, hn::InterleaveLower(dd, hi01, hi23));
  *r3 = hn::BitCast(d, hn::InterleaveUpper(dd, hi01, hi23));
}
#endif

// Columns of the rows that the lanes of `row` index, four at a time: lane j of col[4 q + c] is
// base[row_j * stride + first[q] + c] (stride floats a row, each quad 16-byte readable). Each
// row's quads are 16-byte loads and four rows' quads are transposed at once (TransposeQuads;
// on 8-lane targets a vector holds the quads of lanes j and j + 4), so eight rows' quad costs
// 8 loads and 8 shuffles where GatherIndex would load 4 x 8 lanes one by one.
template <size_t kQuads, class D, class VI, class V = hn::Vec<D>>
HWY_INLINE void LoadRowQuads(D d, const float* base, size_t stride, VI row,
                             const size_t (&first)[kQuads], V* col) {
#if HWY_TARGET == HWY_SCALAR
  const float* r = base + size_t(uint32_t(hn::GetLane(row))) * stride;
  for (size_t q = 0; q < kQuads; ++q)
    for (size_t c = 0; c < 4; ++c) col[4 * q + c] = hn::Set(d, r[first[q] + c]);
#else
  constexpr size_t kLanes = hn::MaxLanes(d);
  const hn::RebindToSigned<D> di;
  if constexpr (kLanes != 4 && kLanes != 8) {
    // Other widths (two lanes: a tag rebound from 64-bit lanes on 128-bit targets): one
    // gather a column.
    const auto at = hn::Mul(row, hn::Set(di, int32_t(stride)));
    for (size_t q = 0; q < kQuads; ++q)
      for (size_t c = 0; c < 4; ++c) col[4 * q + c] = hn::GatherIndex(d, base + first[q] + c, at);
  } else {
    alignas(32) int32_t idx[kLanes];
    hn::Store(row, di, idx);
    const float* r[kLanes];
    for (size_t j = 0; j < kLanes; ++j) r[j] = base + size_t(uint32_t(idx[j])) * stride;
    for (size_t q = 0; q < kQuads; ++q) {
      const size_t at = first[q];
      V l[4];
      if constexpr (kLanes == 4) {
        for (size_t j = 0; j < 4; ++j) l[j] = hn::LoadU(d, r[j] + at);
      } else {
        const hn::Half<D> dh;
        for (size_t j = 0; j < 4; ++j)
          l[j] = hn::Combine(d, hn::LoadU(dh, r[j + 4] + at), hn::LoadU(dh, r[j] + at));
      }
      TransposeQuads(d, l[0], l[1], l[2], l[3], &col[4 * q], &col[4 * q + 1], &col[4 * q + 2],
                     &col[4 * q + 3]);
    }
  }
#endif
}

// The first 4 * kQuads columns of the rows (LoadRowQuads of quads 0, 4, 8, ...).
template <size_t kQuads, class D, class VI, class V = hn::Vec<D>>
HWY_INLINE void LoadRowColumns(D d, const float* base, size_t stride, VI row, V* col) {
  size_t first[kQuads];
  for (size_t q = 0; q < kQuads; ++q) first[q] = 4 * q;
  LoadRowQuads(d, base, stride, row, first, col);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TRANSPOSE4_INL_H_
