// Owen-scrambled Sobol' points in base 2, by hashing (Burley 2020, "Practical Hash-based Owen
// Scrambling", JCGT 9(4)): the first two Sobol' dimensions form a (0,2)-sequence; a nested
// uniform scramble of the sample index shuffles the sequence without breaking its aligned
// blocks (every block of 2^m consecutive indices stays a (0,m,2)-net), and a nested uniform
// scramble of each coordinate Owen-scrambles it. Padding (a different index shuffle per
// decision) gives every 1-D or 2-D decision of a path its own well-stratified points.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/vec.h"

namespace ptlab {

constexpr uint32_t ReverseBits32(uint32_t v) {
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
  v = ((v >> 8) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8);
  return (v >> 16) | (v << 16);
}

/// Laine and Karras' hash-based permutation: every output bit depends only on the input bits
/// of the same or lower significance (additions and multiplications by even constants carry
/// upwards only), so it is a nested permutation of the bit-reversed value.
constexpr uint32_t LaineKarrasPermutation(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

/// Nested uniform scramble of a 32-bit fixed-point value in [0, 1): each bit is flipped as a
/// function of the bits above it (Owen scrambling). On a sample index it is a shuffle that maps
/// every aligned block of 2^m indices onto an aligned block of 2^m indices.
constexpr uint32_t NestedUniformScramble(uint32_t x, uint32_t seed) {
  return ReverseBits32(LaineKarrasPermutation(ReverseBits32(x), seed));
}

/// Sobol' dimension 0 (the van der Corput sequence) as 32-bit fixed point.
constexpr uint32_t SobolDimension0(uint32_t index) { return ReverseBits32(index); }

/// Sobol' dimension 1 (primitive polynomial x + 1, m_1 = 1): the direction numbers follow
/// v_{k+1} = v_k xor (v_k >> 1) from v_1 = 2^31.
constexpr uint32_t SobolDimension1(uint32_t index) {
  uint32_t result = 0;
  for (uint32_t v = 1u << 31; index != 0; index >>= 1, v ^= v >> 1) {
    if (index & 1u) result ^= v;
  }
  return result;
}

/// 32-bit fixed point to a float in [0, 1): the top 24 bits, as Pcg32::NextFloat.
constexpr float FixedPointToFloat(uint32_t x) { return float(x >> 8) * 0x1p-24f; }

/// A 32-bit integer hash (Wellons' "lowbias32"): 32-bit multiplies and shifts only, so 8
/// lanes hash at once in SIMD code with the same bits.
constexpr uint32_t Hash32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

/// Scramble seeds of one decision: the index shuffle and one per coordinate.
struct SobolSeeds {
  uint32_t shuffle = 0, x = 0, y = 0;
};

/// The seeds of dimension `dim` of a pixel (pixel_seed: 32 bits of the pixel's seed).
constexpr SobolSeeds DimensionSeeds(uint32_t pixel_seed, uint32_t dim) {
  const uint32_t base = Hash32(pixel_seed ^ Hash32(dim + 0x9e3779b9u));
  return {base, Hash32(base ^ 0x85ebca6bu), Hash32(base ^ 0xc2b2ae35u)};
}

/// Sobol' dimension 1 with its bits reversed, without a loop over the index bits: the
/// generator matrix of dimension 1 is Pascal's triangle mod 2, so bit j of the reversed value is
/// the parity of the index bits k whose positions are supersets of j (j & k == j, Lucas), a
/// superset sum over GF(2) that five butterfly steps compute (one per bit of the position).
/// Equal to ReverseBits32(SobolDimension1(i)) for every i (tests/engine/sampling/sobol_test).
constexpr uint32_t SobolDimension1Reversed(uint32_t i) {
  i ^= (i >> 1) & 0x55555555u;
  i ^= (i >> 2) & 0x33333333u;
  i ^= (i >> 4) & 0x0f0f0f0fu;
  i ^= (i >> 8) & 0x00ff00ffu;
  return i ^ (i >> 16);
}

/// Point `index` of the shuffled, Owen-scrambled (0,2)-sequence with these seeds: the same bits
/// as NestedUniformScramble(SobolDimensionK(i), seed) with i = NestedUniformScramble(index,
/// seeds.shuffle), with the bit reversals that cancel left out (NestedUniformScramble reverses,
/// permutes and reverses back; dimension 0 is itself a reversal).
constexpr Vec2f ScrambledSobol2D(uint32_t index, const SobolSeeds& seeds) {
  const uint32_t i = NestedUniformScramble(index, seeds.shuffle);
  return {FixedPointToFloat(ReverseBits32(LaineKarrasPermutation(i, seeds.x))),
          FixedPointToFloat(
              ReverseBits32(LaineKarrasPermutation(SobolDimension1Reversed(i), seeds.y)))};
}

/// Point `index` of the shuffled, Owen-scrambled van der Corput sequence.
constexpr float ScrambledSobol1D(uint32_t index, const SobolSeeds& seeds) {
  const uint32_t i = NestedUniformScramble(index, seeds.shuffle);
  return FixedPointToFloat(ReverseBits32(LaineKarrasPermutation(i, seeds.x)));
}

}  // namespace ptlab
