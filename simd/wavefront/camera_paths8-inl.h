// Per-target kernel of simd/wavefront/camera_paths8.h (re-included once per Highway target):
// StartCameraPaths' integer operations lane by lane (simd/pcg8-inl.h), a vector of rows per
// step.

#if defined(PTLAB_SIMD_CAMERA_PATHS8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_CAMERA_PATHS8_INL_H_
#undef PTLAB_SIMD_CAMERA_PATHS8_INL_H_
#else
#define PTLAB_SIMD_CAMERA_PATHS8_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include "engine/core/rng.h"
#include "engine/render/packet_render.h"
#include "engine/sampling/sampler.h"
#include "engine/wavefront/camera_paths.h"
#include "hwy/highway.h"
#include "simd/pcg8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

inline void StartCameraPathsKernel(SamplerType type, uint64_t seed, uint64_t width, size_t n,
                                   const CameraPathInputs& in, const CameraPathOutputs& out) {
  // PathSampler's rows as four 64-bit words: state, increment, pixel_seed32 | index << 32,
  // type in the low byte (the rest padding).
  static_assert(PathSampler::RowLayoutHolds());
  const hn::CappedTag<uint64_t, 8> d;
  const hn::Rebind<uint32_t, decltype(d)> du;
  const hn::Rebind<int32_t, decltype(d)> di;
  const hn::Rebind<float, decltype(d)> df;
  const size_t lanes = hn::Lanes(d);
  const bool independent = type == SamplerType::kIndependent;
  // PixelSeed(seed, pixel) = MixBits(seed · stride + pixel): the product is the batch's.
  const auto seed_base = hn::Set(d, seed * kPixelSeedStride);
  const auto row_width = hn::Set(d, width);
  const auto low32 = hn::Set(d, 0xffffffffull);
  const auto type_word = hn::Set(d, uint64_t(static_cast<uint8_t>(type)));
  constexpr Pcg32Jump kJump1 = Pcg32JumpOf(1), kJump2 = Pcg32JumpOf(2), kJump3 = Pcg32JumpOf(3),
                      kJump4 = Pcg32JumpOf(4);
  uint64_t* const rows = reinterpret_cast<uint64_t*>(out.sampler);
  size_t k = 0;
  for (; k + lanes <= n; k += lanes) {
    const auto px = hn::LoadU(di, in.px + k), py = hn::LoadU(di, in.py + k);
    const auto pixel = hn::Add(hn::Mul(hn::PromoteTo(d, hn::BitCast(du, py)), row_width),
                               hn::PromoteTo(d, hn::BitCast(du, px)));
    const auto pixel_seed = MixBits(d, hn::Add(seed_base, pixel));
    const auto index = hn::PromoteTo(d, hn::LoadU(du, in.sample + k));
    const auto inc = Pcg32Increment(d, index);
    auto state = Pcg32SeededState(d, pixel_seed, inc);
    if (independent) {
      // Film jitter (draws 0, 1), then lens point (draws 2, 3), each from the seeded state.
      const auto jx = Pcg32Float(d, state), jy = Pcg32Float(d, Pcg32Advance(d, state, inc, kJump1));
      const auto lx = Pcg32Float(d, Pcg32Advance(d, state, inc, kJump2));
      const auto ly = Pcg32Float(d, Pcg32Advance(d, state, inc, kJump3));
      hn::StoreU(hn::Add(hn::ConvertTo(df, px), jx), df, out.sx + k);
      hn::StoreU(hn::Add(hn::ConvertTo(df, py), jy), df, out.sy + k);
      hn::StoreInterleaved2(lx, ly, df, reinterpret_cast<float*>(out.lens + k));
      state = Pcg32Advance(d, state, inc, kJump4);
    }
    const auto seed32 = hn::And(hn::Xor(pixel_seed, hn::ShiftRight<32>(pixel_seed)), low32);
    hn::StoreInterleaved4(state, inc, hn::Or(seed32, hn::ShiftLeft<32>(index)), type_word, d,
                          rows + 4 * k);
  }
  if (k < n) {
    const CameraPathInputs rest_in{in.px + k, in.py + k, in.sample + k};
    CameraPathOutputs rest_out{out.sampler + k, nullptr, nullptr, nullptr};
    if (independent)
      rest_out.sx = out.sx + k, rest_out.sy = out.sy + k, rest_out.lens = out.lens + k;
    ptlab::StartCameraPaths(type, seed, width, n - k, rest_in, rest_out);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_CAMERA_PATHS8_INL_H_
