// The sampler of a path sample: where each decision of a path gets its random numbers.
// `independent` is PCG32 (Nori's sampler: one stream per pixel sample, numbers drawn in call
// order); `sobol` is Owen-scrambled Sobol' with padding (engine/sampling/sobol.h), where each
// decision reads its own dimension, so the same decision of all the samples of a pixel is one
// well-stratified point set however many samples the render takes (progressive passes keep
// stratifying: sample indices continue across passes).
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "engine/core/rng.h"
#include "engine/core/vec.h"
#include "engine/sampling/sobol.h"

namespace ptlab {

enum class SamplerType : uint8_t { kIndependent, kSobol };

/// The XML / command-line name of a sampler type ("independent", "sobol").
const char* SamplerTypeName(SamplerType type);
/// The sampler type of a name; false for an unknown name.
bool SamplerTypeFromName(std::string_view name, SamplerType* type);

/// The decisions of one path vertex, in the order of their dimensions. Dimensions of a path
/// sample: 0 = pixel position (2-D), 1 = lens position (2-D), then kDecisionsPerVertex per
/// vertex (depth 0 = the camera ray's hit): DecisionDimension(depth, decision). With several
/// emitter samples per vertex, sample i of n reads point index * n + i of the light dimensions.
enum class Decision : uint32_t {
  kLightPick,       // 1-D: which emitter (independent only: `sobol` folds the pick into the
                    //      point's x, integrator::EmitterNumbers, and leaves this one unused)
  kLightPoint,      // 2-D: the point on it (x also picks an area light's triangle), or the
                    //      direction to an infinite light
  kBsdfLobe,        // 1-D: the BSDF's component
  kBsdfDirection,   // 2-D: the sampled direction
  kRoulette,        // 1-D: Russian roulette
};
inline constexpr uint32_t kDimensionPixel = 0, kDimensionLens = 1, kDecisionsPerVertex = 5;

constexpr uint32_t DecisionDimension(int depth, Decision d) {
  return 2u + uint32_t(depth) * kDecisionsPerVertex + uint32_t(d);
}

/// Random numbers of one path sample (pixel seed, sample index), a value type (32 bytes).
/// Each call names its dimension; `independent` ignores it and draws the next PCG32 numbers, so
/// a path that asks in the scalar integrators' order reproduces the PCG32 streams exactly.
class PathSampler {
 public:
  PathSampler() = default;
  PathSampler(SamplerType type, uint64_t pixel_seed, uint32_t sample_index)
      : rng_(pixel_seed, sample_index),
        pixel_seed32_(uint32_t(pixel_seed) ^ uint32_t(pixel_seed >> 32)),
        index_(sample_index),
        type_(type) {}

  /// Same type, stream, seed and index: the two draw the same numbers from here on.
  bool operator==(const PathSampler&) const = default;

  /// Its bytes, which kernels that read or store whole rows of samplers rely on
  /// (simd/wavefront/camera_paths8, simd/wavefront/vertices8): four 64-bit words, the stream's
  /// state and increment, then pixel_seed32 | index << 32, then the type in the low byte (the
  /// rest is padding).
  static constexpr bool RowLayoutHolds() {
    return Pcg32::StateThenIncrement() && offsetof(PathSampler, rng_) == 0 &&
           offsetof(PathSampler, pixel_seed32_) == 16 && offsetof(PathSampler, index_) == 20 &&
           offsetof(PathSampler, type_) == 24 && sizeof(PathSampler) == 32 &&
           sizeof(SamplerType) == 1 && std::endian::native == std::endian::little;
  }

  SamplerType type() const { return type_; }
  /// What the Sobol' points depend on: the pixel's 32-bit seed and the sample index.
  uint32_t pixel_seed32() const { return pixel_seed32_; }
  uint32_t index() const { return index_; }

  /// A number in [0, 1) for dimension `dim`; sub / sub_count: the sub-sample of a decision
  /// taken sub_count times per vertex (emitter samples).
  float Get1D(uint32_t dim, uint32_t sub = 0, uint32_t sub_count = 1) {
    if (type_ == SamplerType::kIndependent) return rng_.NextFloat();
    return Sobol1D(dim, sub, sub_count);
  }

  /// A point in [0, 1)² for dimension `dim` (see Get1D).
  Vec2f Get2D(uint32_t dim, uint32_t sub = 0, uint32_t sub_count = 1) {
    if (type_ == SamplerType::kIndependent) {
      const float a = rng_.NextFloat();
      return {a, rng_.NextFloat()};
    }
    return Sobol2D(dim, sub, sub_count);
  }

 private:
  SobolSeeds Seeds(uint32_t dim) const { return DimensionSeeds(pixel_seed32_, dim); }
  // The Sobol' branches out of line (sampler.cpp): inline, their hashing made Get2D too big to
  // inline, so the independent sampler's two PCG32 steps became a call in the wavefront's
  // per-path loop. The wavefront draws Sobol' numbers in batches and never calls these.
  float Sobol1D(uint32_t dim, uint32_t sub, uint32_t sub_count) const;
  Vec2f Sobol2D(uint32_t dim, uint32_t sub, uint32_t sub_count) const;

  Pcg32 rng_;
  uint32_t pixel_seed32_ = 0;  // the pixel's seed folded to 32 bits (Sobol' scrambles)
  uint32_t index_ = 0;
  SamplerType type_ = SamplerType::kIndependent;
};

}  // namespace ptlab
