// Per-target kernels of simd/wavefront/sobol8.h (re-included once per Highway target). Each step is
// the integer operation of its scalar twin in engine/sampling/sobol.h, lane by lane.

#if defined(PTLAB_SIMD_SAMPLER8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_SAMPLER8_INL_H_
#undef PTLAB_SIMD_SAMPLER8_INL_H_
#else
#define PTLAB_SIMD_SAMPLER8_INL_H_
#endif

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "engine/sampling/sobol.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

using DU = hn::CappedTag<uint32_t, 8>;
using VU = hn::Vec<DU>;
using DI = hn::RebindToSigned<DU>;
using DF = hn::Rebind<float, DU>;

/// Hash32.
HWY_INLINE VU Hash32(DU d, VU x) {
  x = hn::Xor(x, hn::ShiftRight<16>(x));
  x = hn::Mul(x, hn::Set(d, 0x7feb352du));
  x = hn::Xor(x, hn::ShiftRight<15>(x));
  x = hn::Mul(x, hn::Set(d, 0x846ca68bu));
  return hn::Xor(x, hn::ShiftRight<16>(x));
}

/// ReverseBits32. With byte shuffles (every target but HWY_SCALAR): each byte's two nibbles
/// reversed by a 16-entry table lookup and swapped, then the four bytes of each lane reversed.
/// Otherwise: swap halves of ever smaller fields.
HWY_INLINE VU ReverseBits(DU d, VU v) {
#if HWY_TARGET != HWY_SCALAR
  const hn::Repartition<uint8_t, DU> d8;
  // Nibble n reversed, in the low (kLow) or high (kHigh) half of a byte.
  alignas(16) static constexpr uint8_t kLow[16] = {0x0, 0x8, 0x4, 0xc, 0x2, 0xa, 0x6, 0xe,
                                                   0x1, 0x9, 0x5, 0xd, 0x3, 0xb, 0x7, 0xf};
  alignas(16) static constexpr uint8_t kHigh[16] = {0x00, 0x80, 0x40, 0xc0, 0x20, 0xa0, 0x60, 0xe0,
                                                    0x10, 0x90, 0x50, 0xd0, 0x30, 0xb0, 0x70, 0xf0};
  alignas(16) static constexpr uint8_t kByteSwap[16] = {3, 2, 1, 0, 7, 6, 5, 4,
                                                        11, 10, 9, 8, 15, 14, 13, 12};
  const auto bytes = hn::BitCast(d8, v);
  const auto low_nibble = hn::And(bytes, hn::Set(d8, uint8_t{0x0f}));
  const auto high_nibble = hn::BitCast(d8, hn::And(hn::ShiftRight<4>(v), hn::Set(d, 0x0f0f0f0fu)));
  const auto reversed = hn::Or(hn::TableLookupBytes(hn::LoadDup128(d8, kHigh), low_nibble),
                               hn::TableLookupBytes(hn::LoadDup128(d8, kLow), high_nibble));
  return hn::BitCast(d, hn::TableLookupBytes(reversed, hn::LoadDup128(d8, kByteSwap)));
#else
  const auto swap = [d](VU x, uint32_t mask, auto shift) {
    constexpr int kShift = decltype(shift)::value;
    const VU m = hn::Set(d, mask);
    return hn::Or(hn::And(hn::ShiftRight<kShift>(x), m), hn::ShiftLeft<kShift>(hn::And(x, m)));
  };
  v = swap(v, 0x55555555u, std::integral_constant<int, 1>());
  v = swap(v, 0x33333333u, std::integral_constant<int, 2>());
  v = swap(v, 0x0f0f0f0fu, std::integral_constant<int, 4>());
  v = swap(v, 0x00ff00ffu, std::integral_constant<int, 8>());
  return hn::Or(hn::ShiftRight<16>(v), hn::ShiftLeft<16>(v));
#endif
}

/// LaineKarrasPermutation.
HWY_INLINE VU LaineKarras(DU d, VU x, VU seed) {
  x = hn::Add(x, seed);
  x = hn::Xor(x, hn::Mul(x, hn::Set(d, 0x6c50b47cu)));
  x = hn::Xor(x, hn::Mul(x, hn::Set(d, 0xb82f1e52u)));
  x = hn::Xor(x, hn::Mul(x, hn::Set(d, 0xc7afe638u)));
  return hn::Xor(x, hn::Mul(x, hn::Set(d, 0x8d22f6e6u)));
}

/// SobolDimension1Reversed: the five butterfly steps.
HWY_INLINE VU Dimension1Reversed(DU d, VU i) {
  i = hn::Xor(i, hn::And(hn::ShiftRight<1>(i), hn::Set(d, 0x55555555u)));
  i = hn::Xor(i, hn::And(hn::ShiftRight<2>(i), hn::Set(d, 0x33333333u)));
  i = hn::Xor(i, hn::And(hn::ShiftRight<4>(i), hn::Set(d, 0x0f0f0f0fu)));
  i = hn::Xor(i, hn::And(hn::ShiftRight<8>(i), hn::Set(d, 0x00ff00ffu)));
  return hn::Xor(i, hn::ShiftRight<16>(i));
}

/// FixedPointToFloat: the top 24 bits, exact in float.
HWY_INLINE hn::Vec<DF> ToFloat(DU, VU x) {
  const DF df;
  const DI di;
  return hn::Mul(hn::ConvertTo(df, hn::BitCast(di, hn::ShiftRight<8>(x))), hn::Set(df, 0x1p-24f));
}


template <bool kTwoD>
HWY_INLINE void SobolKernel(const uint32_t* HWY_RESTRICT pixel_seed,
                            const uint32_t* HWY_RESTRICT index, uint32_t dim, size_t n,
                            float* HWY_RESTRICT x, float* HWY_RESTRICT y) {
  const DU d;
  const DF df;
  const size_t lanes = hn::Lanes(d);
  const VU dim_hash = hn::Set(d, ptlab::Hash32(dim + 0x9e3779b9u));
  size_t i = 0;
  for (; i + lanes <= n; i += lanes) {
    const VU base = Hash32(d, hn::Xor(hn::LoadU(d, pixel_seed + i), dim_hash));
    const VU seed_x = Hash32(d, hn::Xor(base, hn::Set(d, 0x85ebca6bu)));
    // NestedUniformScramble(index, base): the shuffled index.
    const VU shuffled = ReverseBits(d, LaineKarras(d, ReverseBits(d, hn::LoadU(d, index + i)), base));
    hn::StoreU(ToFloat(d, ReverseBits(d, LaineKarras(d, shuffled, seed_x))), df, x + i);
    if constexpr (kTwoD) {
      const VU seed_y = Hash32(d, hn::Xor(base, hn::Set(d, 0xc2b2ae35u)));
      hn::StoreU(ToFloat(d, ReverseBits(d, LaineKarras(d, Dimension1Reversed(d, shuffled), seed_y))),
                 df, y + i);
    }
  }
  // The tail: the oracle, row by row (the same bits).
  for (; i < n; ++i) {
    const SobolSeeds seeds = DimensionSeeds(pixel_seed[i], dim);
    if constexpr (kTwoD) {
      const Vec2f p = ScrambledSobol2D(index[i], seeds);
      x[i] = p.x, y[i] = p.y;
    } else {
      x[i] = ScrambledSobol1D(index[i], seeds);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
