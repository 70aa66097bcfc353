// Shared pieces of simd/traverse8's kernels: lane types, far-scale and stack constants, mask bits.
// Part of simd/traverse8-inl.h: re-included once per target with it (hwy/foreach_target.h).

#if defined(PTLAB_SIMD_TRAVERSE8_COMMON_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TRAVERSE8_COMMON_INL_H_
#undef PTLAB_SIMD_TRAVERSE8_COMMON_INL_H_
#else
#define PTLAB_SIMD_TRAVERSE8_COMMON_INL_H_
#endif

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "engine/bvh/sdf_grid_intersect.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/bvh/watertight_triangle.h"
#include "engine/core/check.h"
#include "hwy/cache_control.h"
#include "hwy/highway.h"
#include "simd/bvh8.h"
#include "simd/packet8.h"
#include "simd/traverse8.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DF = hn::CappedTag<float, 8>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using MF = hn::Mask<DF>;

// Must equal kRobustFarScale of engine/bvh/intersect1.cpp (pbrt-v3 §3.9.2): 1 + 2 gamma(3).
constexpr float kMachineEpsilon = std::numeric_limits<float>::epsilon() * 0.5f;
constexpr float kGamma3 = (3 * kMachineEpsilon) / (1.0f - 3 * kMachineEpsilon);
constexpr float kRobustFarScale = 1.0f + 2.0f * kGamma3;
constexpr float kInf = std::numeric_limits<float>::infinity();

// Float offsets of the six plane columns inside a Bvh8Node.
constexpr uint32_t kLoX = 0, kLoY = 8, kLoZ = 16, kHiX = 24, kHiY = 32, kHiZ = 40;

// Worst case of either traversal stack: a node pushes at most 7 children beyond the one it
// descends into, along a path of fewer than kBvhMaxDepth nodes.
constexpr int kStackSize = 8 * kBvhMaxDepth + 8;

HWY_INLINE uint32_t MaskBits(DF d, MF m) {
  uint8_t bits[8] = {};
  hn::StoreMaskBits(d, m, bits);
  return bits[0];
}

HWY_INLINE MF MaskFromBits(DF d, uint32_t bits) {
  const uint8_t b[8] = {static_cast<uint8_t>(bits), 0, 0, 0, 0, 0, 0, 0};
  return hn::LoadMaskBits(d, b);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TRAVERSE8_COMMON_INL_H_ toggle
