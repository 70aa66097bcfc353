// PCG32 random number generator (O'Neill 2014, pcg-random.org), 32-bit output, 64-bit state.
#pragma once

#include <cstddef>
#include <cstdint>

namespace ptlab {

/// PCG32's LCG multiplier (its state steps as state * kPcg32Multiplier + inc, mod 2^64).
inline constexpr uint64_t kPcg32Multiplier = 6364136223846793005ULL;
/// MixBits' two multipliers (SplitMix64's finaliser).
inline constexpr uint64_t kMixBitsMultiplier1 = 0x7fb5d329728ea185ULL;
inline constexpr uint64_t kMixBitsMultiplier2 = 0x81dadef4bc2dd44dULL;

/// k steps of PCG32's LCG at once: state -> state * mul + inc * add (mod 2^64), with
/// mul = M^k and add = M^(k-1) + ... + M + 1 (Brown, "Random number generation with arbitrary
/// strides", 1994). Kernels that draw several numbers per stream get each draw's state from
/// one state with independent multiplies instead of a chain of k (simd/pcg8-inl.h).
struct Pcg32Jump {
  uint64_t mul = 1, add = 0;
};
constexpr Pcg32Jump Pcg32JumpOf(uint32_t steps) {
  Pcg32Jump jump;
  for (uint32_t i = 0; i < steps; ++i) {
    jump = {jump.mul * kPcg32Multiplier, jump.add * kPcg32Multiplier + 1};
  }
  return jump;
}

/// PCG-XSH-RR with a selectable stream. Deterministic for a given (seed, stream).
class Pcg32 {
 public:
  Pcg32() { Seed(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL); }
  Pcg32(uint64_t seed, uint64_t stream) { Seed(seed, stream); }

  /// The generator whose next draw steps from `state` with increment `inc` (odd): a stream
  /// that a kernel seeded or stepped (simd/pcg8-inl.h) as a Pcg32.
  static Pcg32 FromState(uint64_t state, uint64_t inc) {
    Pcg32 rng;
    rng.state_ = state, rng.inc_ = inc;
    return rng;
  }

  void Seed(uint64_t seed, uint64_t stream) {
    state_ = 0u;
    inc_ = (stream << 1u) | 1u;
    NextUint();
    state_ += seed;
    NextUint();
  }

  uint32_t NextUint() {
    const uint64_t old = state_;
    state_ = old * kPcg32Multiplier + inc_;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
  }

  /// Uniform float in [0, 1): the top 24 bits, so 1 - 2^-24 is the largest value.
  float NextFloat() { return static_cast<float>(NextUint() >> 8) * 0x1p-24f; }

  /// Same state and stream: the two draw the same numbers from here on.
  bool operator==(const Pcg32&) const = default;

  /// Its bytes, which kernels that store whole rows of generators rely on
  /// (PathSampler::RowLayoutHolds): the state, then the increment, 64 bits each.
  static constexpr bool StateThenIncrement() {
    return offsetof(Pcg32, state_) == 0 && offsetof(Pcg32, inc_) == 8 && sizeof(Pcg32) == 16;
  }

 private:
  uint64_t state_ = 0, inc_ = 0;
};

/// 64-bit mix (SplitMix64 finaliser), used to derive independent seeds from pixel/sample ids.
constexpr uint64_t MixBits(uint64_t v) {
  v ^= v >> 31;
  v *= kMixBitsMultiplier1;
  v ^= v >> 27;
  v *= kMixBitsMultiplier2;
  v ^= v >> 33;
  return v;
}

}  // namespace ptlab
