// Per-target PCG32 streams on 64-bit lanes (re-included once per Highway target): Pcg32's
// seeding and draws and MixBits (engine/core/rng.h), lane by lane with the same bits. They are
// integer operations mod 2^64 and one exact conversion to float; the 64-bit multiplies are
// native on AVX3 and built from 32x32 -> 64-bit products elsewhere (Highway's operator*).

#if defined(PTLAB_SIMD_PCG8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_PCG8_INL_H_
#undef PTLAB_SIMD_PCG8_INL_H_
#else
#define PTLAB_SIMD_PCG8_INL_H_
#endif

#include <cstdint>

#include "engine/core/rng.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

/// MixBits of each lane.
template <class D64>
HWY_INLINE hn::Vec<D64> MixBits(D64 d, hn::Vec<D64> v) {
  v = hn::Xor(v, hn::ShiftRight<31>(v));
  v = hn::Mul(v, hn::Set(d, kMixBitsMultiplier1));
  v = hn::Xor(v, hn::ShiftRight<27>(v));
  v = hn::Mul(v, hn::Set(d, kMixBitsMultiplier2));
  return hn::Xor(v, hn::ShiftRight<33>(v));
}

/// The increment of Pcg32 stream `stream` (Pcg32::Seed's (stream << 1) | 1).
template <class D64>
HWY_INLINE hn::Vec<D64> Pcg32Increment(D64 d, hn::Vec<D64> stream) {
  return hn::Or(hn::ShiftLeft<1>(stream), hn::Set(d, 1));
}

/// The state of Pcg32(seed, stream) with increment inc = Pcg32Increment(stream): Seed's two
/// steps, from state 0 (0 * multiplier + inc, plus seed) and one more.
template <class D64>
HWY_INLINE hn::Vec<D64> Pcg32SeededState(D64 d, hn::Vec<D64> seed, hn::Vec<D64> inc) {
  return hn::Add(hn::Mul(hn::Add(inc, seed), hn::Set(d, kPcg32Multiplier)), inc);
}

/// The state `jump` steps after `state` (Pcg32JumpOf): two multiplies that do not wait on
/// each other, where stepping would chain one per step.
template <class D64>
HWY_INLINE hn::Vec<D64> Pcg32Advance(D64 d, hn::Vec<D64> state, hn::Vec<D64> inc, Pcg32Jump jump) {
  return hn::Add(hn::Mul(state, hn::Set(d, jump.mul)), hn::Mul(inc, hn::Set(d, jump.add)));
}

/// The float Pcg32::NextFloat returns from each lane's state (the state before its step):
/// XSH-RR's output (xorshift, then a rotation by the top five bits), its top 24 bits times
/// 2^-24, exact.
template <class D64>
HWY_INLINE hn::Vec<hn::Rebind<float, D64>> Pcg32Float(D64 d, hn::Vec<D64> state) {
  const hn::Rebind<uint32_t, D64> du32;
  const hn::Rebind<int32_t, D64> di32;
  const hn::Rebind<float, D64> df;
  const auto xorshifted = hn::And(hn::ShiftRight<27>(hn::Xor(hn::ShiftRight<18>(state), state)),
                                  hn::Set(d, 0xffffffffu));
  // A 32-bit rotate right by rot is the low half of (x:x) >> rot: one 64-bit variable shift.
  const auto doubled = hn::Or(hn::ShiftLeft<32>(xorshifted), xorshifted);
  const auto rotated = hn::Shr(doubled, hn::ShiftRight<59>(state));
  const auto top24 = hn::ShiftRight<8>(hn::TruncateTo(du32, rotated));
  return hn::Mul(hn::ConvertTo(df, hn::BitCast(di32, top24)), hn::Set(df, 0x1p-24f));
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_PCG8_INL_H_
