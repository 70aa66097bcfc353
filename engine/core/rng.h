// PCG32 random number generator (O'Neill 2014, pcg-random.org), 32-bit output, 64-bit state.
#pragma once

#include <cstdint>

namespace ptlab {

/// PCG-XSH-RR with a selectable stream. Deterministic for a given (seed, stream).
class Pcg32 {
 public:
  Pcg32() { Seed(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL); }
  Pcg32(uint64_t seed, uint64_t stream) { Seed(seed, stream); }

  void Seed(uint64_t seed, uint64_t stream) {
    state_ = 0u;
    inc_ = (stream << 1u) | 1u;
    NextUint();
    state_ += seed;
    NextUint();
  }

  uint32_t NextUint() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
  }

  /// Uniform float in [0, 1): the top 24 bits, so 1 - 2^-24 is the largest value.
  float NextFloat() { return static_cast<float>(NextUint() >> 8) * 0x1p-24f; }

 private:
  uint64_t state_ = 0, inc_ = 0;
};

/// 64-bit mix (SplitMix64 finaliser), used to derive independent seeds from pixel/sample ids.
constexpr uint64_t MixBits(uint64_t v) {
  v ^= v >> 31;
  v *= 0x7fb5d329728ea185ULL;
  v ^= v >> 27;
  v *= 0x81dadef4bc2dd44dULL;
  v ^= v >> 33;
  return v;
}

}  // namespace ptlab
